// Event-driven grid-based SLAM (docs/algorithms.md 6, thesis chapter 3): an occupancy grid map M
// and a pose grid Pi, a window of (x, y, theta) hypotheses that re-centres as the robot moves,
// updated by three events: motion (every scan), localization (every lambda-th scan) and mapping
// (every xi-th scan).
//
// The per-scan path works on integers only: ranges and odometry arrive in millimetres and
// angle units (2^16 a turn), geometry uses a fixed-point sine table, rays are walked cell by
// cell with exact integer comparisons, and the map M is an S_eps grid in both arithmetics.
// The arithmetic of probabilities is the template parameter: double precision
// (DoubleProbabilities) or U_gamma indices (IndexProbabilities, probabilities.hpp). Every
// table that needs floating point to build is built once, before the first scan, by
// make_slam_setup.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/range_sensor.hpp"
#include "intgrid/core/ray_insertion.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/core/ugamma.hpp"

namespace intgrid::slam {

// The options of a run, nested by concern. Defaults: chosen on the bundled real log and the
// simulated floor (docs/results.md says which data chose which).
struct GridSlamConfig {
  double cell = 0.1;    // map cell and pose-grid step (m), a whole number of millimetres
  int headings = 1024;  // heading bins per turn: a power of two, 8..65536

  // When the events run: localization every lambda-th scan, mapping every xi-th.
  struct Schedule {
    int lambda = 1;
    int xi = 1;
  } schedule;

  // The range sensor (sigma 5 cm, as the bundled log's map was built; readings to 30 m).
  core::RangeSensor sensor{0.05, 30.0};

  // The beam model of the localization event.
  struct BeamModel {
    double likelihood_floor = 1e-3;  // p(z | x, M) for readings the map cannot explain
    int beams = 90;                  // readings a localization uses, spread evenly over the scan
    // The localization multiplies Pi by the beams' likelihood raised to 1 / tempering: the beams
    // of one scan are not independent (those on one wall share its error in the map), and
    // treating them so collapses Pi onto one cell, whose mean then carries the lattice's
    // rounding. 16 is the smallest tempering at which the bundled real log's E(sigma) reaches
    // that rounding, cell sqrt(2/12) (41 mm at 10 cm), in both arithmetics (docs/results.md).
    int tempering = 16;
  } beam;

  // Spread of the motion model: sigma_xy = xy0 + xy_per_m |translation| + xy_per_rad |rotation|,
  // sigma_theta = theta0 + theta_per_m |translation| + theta_per_rad |rotation|.
  struct MotionModel {
    double xy0 = 0.01;
    double xy_per_m = 0.1;
    double xy_per_rad = 0.05;
    double theta0 = 0.002;
    double theta_per_m = 0.02;
    double theta_per_rad = 0.1;
  } motion;

  // The pose grid Pi: a window of hypotheses around the predicted pose.
  struct PoseWindow {
    int cells = 11;  // cells per side in x and y (odd)
    // Heading bins (odd): +-10.5 degrees at 1024, as the odometry's heading can miss by several
    // degrees in one scan and the motion model reaches only 3 sigma from its mean.
    int headings = 61;
    double pose_cutoff = 0.01;  // mapping skips poses less probable than this
    // A localization drops the poses it leaves less probable than this, so that the next one
    // weighs the poses the motion model carries the rest to, not the whole window. Low, as the
    // far tail is what recovers from an odometry glitch: at 1e-20 the real log's double run
    // already changes (docs/results.md).
    double pose_prune = 1e-40;
  } window;

  // The map M: an S_eps grid in both arithmetics.
  struct Map {
    int seps_bits = 8;     // index width
    int seps_levels = 16;  // eps such that one reading's strongest occupied index is this
    // A reading's empty indices are divided by this (rounded away from 0): many beams cross a
    // wall cell near its edge, but few end in it, so full-strength empty evidence erases walls.
    int empty_divisor = 1;
    double margin = 10.0;  // metres of map beyond the odometry's reach plus max_range
  } map;

  // The pose grid's probabilities in the integer arithmetic: U_gamma indices.
  struct UGammaOptions {
    int bits = 16;
    int steps_per_halving = 16;
  } ugamma;
};

// Throws std::invalid_argument naming the offending field by its path (`window.cells`).
void check_grid_slam_config(const GridSlamConfig& config);

// The scan geometry, fixed for a run, in integer units.
struct SlamSensor {
  std::vector<std::int32_t> bearing;  // angle units, beam i in the sensor frame
  std::int32_t mount_x_mm = 0;
  std::int32_t mount_y_mm = 0;
  std::int32_t mount_theta = 0;  // angle units
};

// One scan's inputs to the per-scan path: ranges in mm (0: no usable return) and the odometry
// increment since the previous scan in the previous robot frame. Made from a core::Scan by
// quantize_scan (grid_slam.hpp), the one place where SI units become the path's integers.
struct QuantizedScan {
  std::vector<std::int32_t> range_mm;
  std::int32_t odom_dx_mm = 0;
  std::int32_t odom_dy_mm = 0;
  std::int32_t odom_dtheta = 0;  // angle units
};

// The pose estimate after a scan: the mean of Pi and its standard deviation, in the SLAM frame
// (the first scan's robot pose is the origin).
struct SlamEstimate {
  std::int64_t x_um = 0;
  std::int64_t y_um = 0;
  std::int64_t theta_q8 = 0;  // angle units * 256
  std::int64_t sigma_um = 0;  // sqrt(var x + var y)
};

// A pose in the SLAM frame: mm and angle units (not wrapped).
struct SlamPose {
  std::int64_t x_mm = 0;
  std::int64_t y_mm = 0;
  std::int64_t theta = 0;
  bool operator==(const SlamPose&) const = default;
};

// Everything the per-scan path needs that takes floating point to build.
struct SlamSetup {
  GridSlamConfig config;
  core::SepsCodec codec{8, 0.1};  // the map's
  SlamSensor sensor;
  core::GridGeometry map_geometry;  // the SLAM frame's cell (0, 0) is centred on its origin pose
  int origin_cell_x = 0;            // map cell of the SLAM frame's cell (0, 0)
  int origin_cell_y = 0;
  std::int32_t cell_mm = 0;
  std::int32_t sigma_mm = 0;
  std::int32_t max_range_mm = 0;
  int max_seps_index = 0;
  std::vector<std::int32_t> sin_q16;  // sin(2 pi a / 2^16) * 2^16, a = 0..2^16 - 1
  core::NarrowIsmTable ism;           // the map's, quantized to S_eps
  // Motion spread, as fixed-point factors: sigma = base + (factor * magnitude) >> 16.
  std::int32_t motion_xy0_mm = 0;
  std::int64_t motion_xy_per_mm_q16 = 0;
  std::int64_t motion_xy_per_unit_q16 = 0;  // mm per angle unit
  std::int32_t motion_theta0 = 0;           // angle units
  std::int64_t motion_theta_per_mm_q16 = 0;
  std::int64_t motion_theta_per_unit_q16 = 0;
};

// Builds the setup of a run over scans with this geometry whose odometry stays within
// `reach_m` metres of the first pose. Throws std::invalid_argument for a bad configuration.
SlamSetup make_slam_setup(const GridSlamConfig& config, const core::Scan& geometry, double reach_m);

// The conversions of one pose-grid probability type, built once by the setup.
template <class Probabilities>
Probabilities make_probabilities(const SlamSetup& setup);

// One SLAM run. Probabilities is DoubleProbabilities or IndexProbabilities.
template <class Probabilities>
class GridSlamEngine {
 public:
  using P = typename Probabilities::P;

  GridSlamEngine(const SlamSetup& setup, Probabilities probabilities);

  // One scan: the motion update, then localization and mapping when the schedule says so. A
  // scan without any usable reading only moves the pose grid. Throws std::runtime_error if the
  // pose window reaches the map's edge.
  void process(const QuantizedScan& scan);

  const SlamSetup& setup() const { return setup_; }
  SlamEstimate estimate() const { return estimate_; }
  const core::Grid<std::int8_t>& map() const { return map_; }
  std::size_t scans() const { return scans_; }
  std::size_t localizations() const { return localizations_; }
  std::size_t mappings() const { return mappings_; }
  std::size_t skipped_scans() const { return skipped_; }
  // The pose grid: window_headings slices of window_cells^2, x fastest, one cell and one
  // heading bin apart; its origin (element 0) lies anywhere, at the predicted mean less half
  // the window, so that no fraction of a move is lost to the lattice.
  const std::vector<P>& pose_grid() const { return pi_; }
  // The SLAM-frame pose of pose-grid element q: mm and angle units.
  SlamPose pose_of(std::size_t q) const;
  const Probabilities& probabilities() const { return prob_; }

 private:
  struct Ray {
    std::uint32_t begin, mid, end;  // [begin, mid): before the reading; [mid, end): near it
    std::int32_t z_mm;
  };

  core::IntegerRays rays() const { return {setup_.sin_q16, setup_.cell_mm}; }
  std::int32_t heading_unit() const { return core::kAngleUnitsPerTurn / setup_.config.headings; }
  // The heading of slice k, wrapped to one turn.
  std::int32_t slice_angle(int k) const {
    return static_cast<std::int32_t>((theta0_ + std::int64_t{k} * heading_unit()) &
                                     (core::kAngleUnitsPerTurn - 1));
  }
  std::size_t pose_index(int i, int j, int k) const;
  bool slice_is_empty(int k) const;  // every pose of heading slice k has probability 0
  std::int64_t map_index(int cx, int cy) const;
  void check_window_inside_map() const;

  void motion_update(const QuantizedScan& scan);
  void localize(const QuantizedScan& scan);
  void map_scan(const QuantizedScan& scan);
  void add_pose_scan(int cx, int cy, std::int32_t angle, const QuantizedScan& scan);
  void update_estimate();
  void normalize();

  SlamSetup setup_;
  Probabilities prob_;
  core::Grid<std::int8_t> map_;
  // P_M(e) of every map cell, kept with map_ for the localization.
  std::vector<typename Probabilities::EmptyProduct> cell_empty_;
  std::vector<P> pi_, next_, row_, plane_;
  int n_ = 0, nt_ = 0;  // window cells per side, headings
  // The window's origin: SLAM-frame cell (ox_, oy_) with the pose (fx_, fy_) mm from its centre
  // (|f| <= half a cell), and heading theta0_.
  int ox_ = 0, oy_ = 0;
  std::int64_t fx_ = 0, fy_ = 0, theta0_ = 0;
  SlamEstimate estimate_;
  std::size_t scans_ = 0, localizations_ = 0, mappings_ = 0, skipped_ = 0;
  // Scratch of the events, sized by the constructor for the largest scan the setup allows: the
  // motion and localization events allocate nothing.
  std::vector<P> kernel_x_, kernel_y_, kernel_t_;
  std::vector<std::uint32_t> heading_rays_;  // per heading, into scan_rays_
  std::vector<std::int32_t> ray_offsets_;
  std::vector<P> ray_likelihoods_;
  std::vector<Ray> scan_rays_;
  std::vector<typename Probabilities::EmptyProduct> empty_products_;  // per pose of a slice's box
  std::vector<typename Probabilities::Joint> joints_;                 // per pose of a slice's box
  std::vector<std::int16_t> scan_image_;
  std::vector<std::int32_t> touched_, slot_, mix_cells_;
  std::vector<P> mix_occupied_, mix_empty_, mix_weight_;
};

}  // namespace intgrid::slam
