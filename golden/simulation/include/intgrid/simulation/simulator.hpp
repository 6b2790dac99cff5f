// The seeded simulator (docs/algorithms.md 8): a world map (any occupancy grid, or a procedural
// floorplan), a trajectory through its free space, odometry with the usual alpha noise model,
// range sensors by exact ray casting (a LiDAR and a ring of cones), range noise, drop-outs,
// uniform contamination, and unmodelled obstacles that the sensors see but the map lacks.
//
// Determinism: every random number comes from SimRandom (xoshiro256** seeded by splitmix64),
// uniforms from its bits and normals by Box-Muller, so the same seed gives the same output bit
// for bit whatever the C++ standard library (no std:: distributions). The only platform
// functions used are sqrt (exact in IEEE 754) and log, sin, cos, atan2 of the C library, as
// everywhere in the golden model. Independent parts (trajectory, obstacles, odometry, range
// noise) draw from separate streams derived from the seed, so changing, say, the obstacle
// count does not change the odometry noise.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <optional>
#include <vector>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/types.hpp"

namespace intgrid::simulation {

// ---------------------------------------------------------------------------------------------
// Random numbers

// One step of splitmix64: advances state and returns 64 well-mixed bits.
std::uint64_t splitmix64(std::uint64_t& state);

// The seed of stream `stream` of a simulation seeded with seed (a splitmix64 hash of both).
std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream);

// xoshiro256** (Blackman and Vigna), its state filled from the seed by splitmix64.
class SimRandom {
 public:
  explicit SimRandom(std::uint64_t seed);

  std::uint64_t next_u64();
  // Uniform on [0, 1): a multiple of 2^-53 from the top 53 bits.
  double uniform();
  // Uniform on (0, 1): (k + 1/2) 2^-53, never 0 nor 1.
  double uniform_open();
  // Uniform on [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [0, n), unbiased (rejection); n must be positive.
  std::uint64_t below(std::uint64_t n);
  // A standard normal deviate: Box-Muller from exactly two uniforms, sqrt(-2 ln u1) cos(2 pi u2).
  double normal();
  // True with probability p: one uniform, uniform() < p.
  bool bernoulli(double p) { return uniform() < p; }

 private:
  std::array<std::uint64_t, 4> s_{};
};

// ---------------------------------------------------------------------------------------------
// Geometry and thresholds

struct Point2 {
  double x = 0.0;
  double y = 0.0;
};

// A disc obstacle (centre and radius, metres).
struct Disc {
  double x = 0.0;
  double y = 0.0;
  double radius = 0.0;
};

// A cell stops a ray when P >= this (ROS map_server's default occupied_thresh).
inline constexpr double kSimOccupiedThreshold = 0.65;
// A cell is free space for the robot when P < this (ROS map_server's default free_thresh; the
// unknown grey 205 of a PGM, P = 50/255, is not free).
inline constexpr double kSimFreeThreshold = 0.196;

// ---------------------------------------------------------------------------------------------
// World: procedural floorplan

// An office floor (all sizes metres): an outer wall around width x height; a rectangular
// corridor loop `room_depth` in from the outer wall; rooms between the outer wall and the
// corridor (about room_length long along it, each partition moved by up to a quarter of that
// by the seed) and two rooms in the block the corridor encloses, each with one door onto the
// corridor; furniture blocks in the rooms, 0.3 m from walls and from each other and 1.2 m from
// doors, which keeps all free space connected. Walls and furniture have P = 1, everything else
// P = 0 (there is no unknown cell). The grid covers [0, width] x [0, height] rounded to whole
// cells (origin 0, 0); its outermost cells are wall.
struct FloorplanConfig {
  double width = 20.0;
  double height = 15.0;
  double cell = 0.1;
  double wall = 0.2;          // wall thickness
  double room_depth = 3.5;    // rooms between the outer wall and the corridor
  double corridor = 1.6;      // corridor width (between its walls)
  double door = 0.9;          // door width
  double room_length = 4.0;   // mean room length along the corridor
  std::size_t furniture = 8;  // up to this many blocks (0.4-1.2 m x 0.4-1.0 m) in random rooms
};
// Throws std::invalid_argument naming the field: non-finite or non-positive sizes, a floor too
// small for rooms, corridor and an inner block of at least 1 m, a door narrower than 3 cells or
// longer than a room allows, a corridor narrower than 4 cells, more than 10^8 cells.
void check_floorplan_config(const FloorplanConfig& c);

struct Floorplan {
  core::ProbabilityGrid grid;
  // The corridor's centre line, a closed loop (the last point joins the first), counter-clockwise
  // from the middle of the bottom corridor; every point of it is at least corridor / 2 - cell
  // from any wall.
  std::vector<Point2> corridor_loop;
};

Floorplan make_floorplan(const FloorplanConfig& c, std::uint64_t seed);
// make_floorplan(c, seed).grid.
core::ProbabilityGrid procedural_floorplan(const FloorplanConfig& c, std::uint64_t seed);

// ---------------------------------------------------------------------------------------------
// Trajectory

// Defaults: 0.5 m/s and 1 rad/s at 5 scans/s, so consecutive poses are at most 0.1 m and
// 0.2 rad (11.5 degrees) apart.
struct TrajectoryConfig {
  std::size_t scans = 400;    // poses, one per scan
  double scan_period = 0.2;   // s between scans
  double speed = 0.5;         // m/s, the largest translation per scan is speed * period
  double turn_rate = 1.0;     // rad/s, the largest rotation per scan is turn_rate * period
  double robot_radius = 0.3;  // m kept from every non-free cell (random waypoints)
  double free_threshold = kSimFreeThreshold;  // cells with P < this are free
  double min_leg = 3.0;  // m: random waypoints at least this far apart when possible
};
// Throws std::invalid_argument naming the field: zero or more than 10^7 scans, a non-positive or
// non-finite period, speed or turn rate, a negative or non-finite radius or leg, a free threshold
// outside (0, 1].
void check_trajectory_config(const TrajectoryConfig& c);

// Poses along a polyline, one per scan period: the robot turns toward the next vertex at most
// turn_rate * period a step (turning in place while the remaining turn is larger), then moves
// toward it at most speed * period, stopping at each vertex; every position lies on the
// polyline. A closed route is repeated (last point back to the first) until c.scans poses exist;
// an open one ends the trajectory early if it runs out. The first pose is route[0], heading
// toward the first distinct vertex. Throws std::invalid_argument unless the route has two
// distinct finite points.
std::vector<core::Pose2> follow_route(const std::vector<Point2>& route, bool closed,
                                      const TrajectoryConfig& c);

// Distance from each cell centre to the nearest non-free cell centre (P >= free_threshold or
// NaN), the cells just outside the grid counting as non-free: an exact Euclidean distance
// transform (Felzenszwalb and Huttenlocher). Non-free cells hold 0.
core::Grid<double> clearance_map(const core::ProbabilityGrid& world, double free_threshold);

// A trajectory through free space: the robot starts on a random cell of the largest connected
// region of cells with clearance (clearance_map >= robot_radius + sqrt(2) cell, which keeps
// every point of every such cell robot_radius from every non-free cell and from the grid's
// edge), then goes from random waypoint to random waypoint of that region (at least min_leg
// apart when possible) along shortest 8-connected paths that cut no corner, shortened by line
// of sight, sampled by follow_route's rules. Throws std::invalid_argument if the world has fewer
// than two such cells.
std::vector<core::Pose2> random_trajectory(const core::ProbabilityGrid& world,
                                           const TrajectoryConfig& c, std::uint64_t seed);

// ---------------------------------------------------------------------------------------------
// Odometry

// The odometry motion model (Thrun, Burgard and Fox, Probabilistic Robotics, table 5.6): each
// true increment is split into rotation1, translation, rotation2, and each is corrupted by a
// zero-mean normal deviate of variance
//   rot1:  alpha1 rot1^2 + alpha2 trans^2
//   trans: alpha3 trans^2 + alpha4 (rot1^2 + rot2^2)
//   rot2:  alpha1 rot2^2 + alpha2 trans^2
// (trans in m, rotations in rad). With the defaults (10% of each rotation and translation as
// standard deviation, plus 0.045 rad per metre driven) the default run, one lap of the
// floorplan's corridor, ends about 1 m from the truth (RMS over seeds 1 to 10); all zero gives
// the true poses exactly.
struct OdometryNoiseConfig {
  double alpha1 = 0.01;   // rotation from rotation
  double alpha2 = 0.002;  // rotation from translation (rad^2 / m^2)
  double alpha3 = 0.01;   // translation from translation
  double alpha4 = 0.002;  // translation from rotation (m^2 / rad^2)
};
// Throws std::invalid_argument naming the alpha that is negative or not finite.
void check_odometry_noise(const OdometryNoiseConfig& c);

// The odometry poses of a true trajectory: the first is the first true pose, each next one the
// previous odometry pose composed with the noisy increment. Three normals are drawn a step.
std::vector<core::Pose2> noisy_odometry(const std::vector<core::Pose2>& truth,
                                        const OdometryNoiseConfig& c, SimRandom& random);

// ---------------------------------------------------------------------------------------------
// Range sensors

enum class SensorKind {
  lidar,  // one ray per beam
  cone,   // each beam a cone: the nearest hit over rays_per_cone rays across cone_fov
};

// Beam i has bearing angle0 + i * dangle in the sensor frame; the defaults are a LiDAR of 361
// beams over 180 degrees (0.5 degree steps, as the SICK LMS of the bundled logs) reaching 8 m.
struct SensorConfig {
  SensorKind kind = SensorKind::lidar;
  std::size_t beams = 361;                 // beams, or cones
  double angle0 = -std::numbers::pi / 2;   // rad
  double dangle = std::numbers::pi / 360;  // rad
  double max_range = 8.0;                  // m; no hit within it is no return (0)
  double cone_fov = 0.0;                   // cone: full field of view of each cone, rad
  std::size_t rays_per_cone = 0;           // cone: 0 = enough rays to be at most one world
                                           // cell apart at max_range (at least 2)
  core::Pose2 mount;                       // sensor pose in the robot frame
  double occupied_threshold = kSimOccupiedThreshold;  // P >= this stops a ray
};

// beams over fov radians centred on the sensor axis (fov = 2 pi: equally spaced all round, no
// duplicate beam; one beam: straight ahead).
SensorConfig lidar_sensor(std::size_t beams = 361, double fov = std::numbers::pi,
                          double max_range = 8.0);
// A ring of cones equally spaced all round from the sensor axis; defaults: 16 cones of 30
// degrees reaching 5 m (a sonar ring).
SensorConfig cone_ring_sensor(std::size_t cones = 16, double cone_fov = std::numbers::pi / 6,
                              double max_range = 5.0);

// Throws std::invalid_argument naming the field: zero or more than 100000 beams, non-finite
// angles or mount, a non-positive or non-finite max range, an occupied threshold outside (0, 1],
// for a cone a FOV outside (0, pi) or more than 100000 rays.
void check_sensor_config(const SensorConfig& c);

// Distance from (x, y) along direction angle to the first cell with P >= occupied_threshold,
// by exact grid traversal (Amanatides and Woo): the distance at which the ray enters that cell,
// 0 if (x, y) is in one, max_range if there is none within max_range (the world outside the
// grid holds no obstacle). Requires a finite start, angle and max_range >= 0.
double ray_cast(const core::ProbabilityGrid& world, double x, double y, double angle,
                double max_range, double occupied_threshold = kSimOccupiedThreshold);

// The noiseless range of each beam of sensor from robot pose robot: the ray cast of its bearing
// (a LiDAR) or the smallest over its cone's rays (a cone), max_range meaning no hit.
std::vector<double> true_ranges(const core::ProbabilityGrid& world, const SensorConfig& sensor,
                                const core::Pose2& robot);

// ---------------------------------------------------------------------------------------------
// Range noise and corruption

struct RangeNoiseConfig {
  double sigma = 0.01;         // m, additive Gaussian noise on every return (SICK-like)
  double dropout = 0.0;        // probability a reading is 0 (no return)
  double contamination = 0.0;  // probability a reading is uniform on (0, max_range)
};
// Throws std::invalid_argument naming the field: a negative or non-finite sigma, a probability
// outside [0, 1] or NaN.
void check_range_noise(const RangeNoiseConfig& c);

// One reading from the true range r (max_range = no hit). Always draws one normal and three
// uniforms (so one reading's outcome never shifts the next one's numbers), then in order: with
// probability dropout 0; else with probability contamination a uniform on (0, max_range); else
// 0 for no hit; else r + sigma N(0, 1), and 0 if that is <= 0 or >= max_range.
double corrupt_range(double true_range, double max_range, const RangeNoiseConfig& c,
                     SimRandom& random);

// One scan taken from robot pose robot (t = 0): the sensor's geometry and mount, true_ranges
// corrupted reading by reading in beam order.
core::Scan simulate_scan(const core::ProbabilityGrid& world, const SensorConfig& sensor,
                         const RangeNoiseConfig& noise, const core::Pose2& robot,
                         SimRandom& random);
// The same with a SimRandom seeded with seed.
core::Scan simulate_scan(const core::ProbabilityGrid& world, const SensorConfig& sensor,
                         const RangeNoiseConfig& noise, const core::Pose2& robot,
                         std::uint64_t seed);

// ---------------------------------------------------------------------------------------------
// Unmodelled obstacles

// Small discs at random free positions (wholly inside the grid, their cells all free in the
// world; they may overlap each other) keeping clearance from every true position, and optionally
// one large disc straight ahead of the first true pose (not checked against the trajectory or
// the walls, for single-pose experiments). A disc occupies the grid cells whose centre it
// covers, and the one holding its centre.
struct ObstacleConfig {
  std::size_t count = 0;                 // small discs
  double min_diameter = 0.2;             // m
  double max_diameter = 0.4;             // m
  double clearance = 0.5;                // m from every true position to every cell of a small disc
  std::optional<double> large_distance;  // m from the first true position to the large disc
  double large_diameter = 1.0;           // m
};
// Throws std::invalid_argument naming the field: non-finite or non-positive diameters,
// min_diameter > max_diameter, a negative clearance or large distance, more than 10^6 discs.
void check_obstacle_config(const ObstacleConfig& c);

// The discs, placed by random (throws std::invalid_argument naming obstacles.count if fewer than
// count fit after 1000 tries a disc).
std::vector<Disc> place_obstacles(const core::ProbabilityGrid& world,
                                  const std::vector<core::Pose2>& truth, const ObstacleConfig& c,
                                  double free_threshold, SimRandom& random);

// Sets P = 1 in the cells each disc occupies (inside the grid).
void add_obstacles(core::ProbabilityGrid& world, const std::vector<Disc>& discs);

// ---------------------------------------------------------------------------------------------
// The whole simulation

struct SimulationConfig {
  TrajectoryConfig trajectory;
  // If not empty: a closed route (e.g. Floorplan::corridor_loop) followed instead of random
  // waypoints.
  std::vector<Point2> route;
  // If not empty: the true poses themselves (e.g. a reference log's), one scan each; trajectory's
  // scans and route are then unused.
  std::vector<core::Pose2> true_poses;
  OdometryNoiseConfig odometry;
  SensorConfig sensor;
  RangeNoiseConfig noise;
  ObstacleConfig obstacles;
  double start_time = 1e9;  // s, time of the first scan; scan i is at start_time + i * period
};
// Every part's check, non-finite true poses or route points, a non-finite start time, and a
// free threshold above the occupied threshold (the robot would drive through walls).
void check_simulation_config(const SimulationConfig& c);

struct Simulation {
  // Scans with robot = odometry pose, and one OdometryRecord per scan with that pose and time.
  core::Log log;
  // The same scans with robot = true pose, no odometry records: a reference log.
  core::Log truth;
  // The world map, without the unmodelled obstacles.
  core::ProbabilityGrid world;
  // What the sensors saw: world plus obstacles.
  core::ProbabilityGrid sensed_world;
  // The unmodelled obstacles (the small ones first).
  std::vector<Disc> obstacles;
};

// Streams derived from seed: 1 trajectory, 2 obstacles, 3 odometry, 4 range noise. Throws
// std::invalid_argument for a bad config or world (check_geometry).
Simulation simulate(const core::ProbabilityGrid& world, const SimulationConfig& c,
                    std::uint64_t seed);

}  // namespace intgrid::simulation
