// The experiments of thesis section 4.5 (docs/algorithms.md 7): one trial is a random true pose in
// a known map, one simulated scan from it (the map used as the world, with noise, uniform
// contamination and unmodelled obstacles the map lacks), and the errors of an estimate of that
// pose. A pure library: the caller runs the localizers, counts successes and writes the results.
//
// Determinism: every random number comes from the simulator's SimRandom
// (intgrid/simulation/simulator.hpp), the true pose from the generator the caller passes, the
// obstacles and the readings from two streams derived from the trial's seed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <numbers>
#include <optional>
#include <vector>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/localization/global_localization.hpp"
#include "intgrid/simulation/simulator.hpp"

namespace intgrid::experiments {

// The places a true pose may take: the centres of the map's free cells whose clearance (distance
// to the nearest non-free cell centre, clearance_map) is at least `clearance`, plus a uniform
// offset within the cell. Keeps a pointer to map, which must outlive it.
class GlobalTrialWorld {
 public:
  // Throws std::invalid_argument: a bad grid or thresholds, a negative or non-finite clearance,
  // no cell with that clearance.
  GlobalTrialWorld(const core::ProbabilityGrid& map, double occupied_threshold,
                   double free_threshold, double clearance);

  const core::ProbabilityGrid& map() const { return *map_; }
  double occupied_threshold() const { return occupied_threshold_; }
  double free_threshold() const { return free_threshold_; }
  double clearance() const { return clearance_; }
  std::size_t start_cells() const { return cells_.size(); }

  // A uniform cell of those, a uniform point in it (cells with clearance >= one cell keep every
  // such point clearance - half a cell diagonal from obstacles) and a uniform heading in
  // [-pi, pi). Draws four numbers.
  core::Pose2 random_pose(simulation::SimRandom& random) const;

 private:
  const core::ProbabilityGrid* map_;
  double occupied_threshold_, free_threshold_, clearance_;
  std::vector<std::size_t> cells_;  // grid indices, in index order
};

// A uniform pose inside a random candidate pose cell whose 8 neighbours are candidates too, with
// a uniform heading. Loops until it finds one: the map must have such a cell. Throws
// std::invalid_argument for a pose grid smaller than 3 x 3.
core::Pose2 random_candidate_pose(const localization::LocalizationMap& map,
                                  simulation::SimRandom& random);

// What one trial's sensor sees. Defaults: the thesis's default condition, 60 readings of 3 cm
// noise, here all round and reaching 30 m.
struct GlobalTrialConditions {
  std::size_t readings = 60;            // beams, equally spaced over fov
  double fov = 2.0 * std::numbers::pi;  // rad; 2 pi: all round
  double max_range = 30.0;     // m; no hit within it is no return (the bundled SICK reads to 80 m)
  double noise = 0.03;         // m, Gaussian range noise
  double contamination = 0.0;  // share of readings replaced by uniform (0, max_range)
  std::size_t obstacles = 0;   // small unmodelled discs (0.2 to 0.4 m) within range
  std::optional<double> large_obstacle;  // m: a 1 m disc this far straight ahead of the robot
  double obstacle_clearance = 0.5;       // m from the true position to every small disc's cell
};
// Throws std::invalid_argument naming the field.
void check_global_trial_conditions(const GlobalTrialConditions& c);

struct GlobalTrial {
  core::Pose2 truth;  // robot = sensor pose (the simulated sensor has no mount)
  core::Scan scan;    // the simulated scan, t = 0, robot = truth
  std::vector<localization::RangeReading> readings;  // its usable readings (readings_of, all beams)
  std::vector<simulation::Disc> obstacles;  // the unmodelled obstacles (the small ones first)
};

// One trial from truth: the world is the map around truth (a window max_range + one cell each
// way, which holds every cell a ray can reach) with the unmodelled obstacles added (placed in the
// window's free cells by simulator's place_obstacles, stream 1 of seed), read by a LiDAR of
// c.readings beams through corrupt_range (stream 2 of seed). Throws std::invalid_argument for bad
// conditions, or naming obstacles.count when the discs do not fit.
GlobalTrial simulate_global_trial(const GlobalTrialWorld& world, const GlobalTrialConditions& c,
                                  const core::Pose2& truth, std::uint64_t seed);

struct GlobalTrialError {
  double position = 0.0;  // m between the estimated and true positions
  double heading = 0.0;   // rad, |wrap(estimate - truth)| in [0, pi]
  bool success = false;   // position <= position_tolerance and heading <= heading_tolerance
};

GlobalTrialError global_trial_error(const core::Pose2& truth, const core::Pose2& estimate,
                                    double position_tolerance, double heading_tolerance);

}  // namespace intgrid::experiments
