// The set-up of a SLAM run: every table the per-scan path needs that takes floating point to
// build, and the GridSlamEngine constructor (which sizes the map from it).
#include <cmath>
#include <stdexcept>
#include <string>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/ray_insertion.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/core/units.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"
#include "intgrid/slam/probabilities.hpp"

namespace intgrid::slam {
namespace {

using core::require_field;

// The setup's fields are 32-bit: their configured ranges keep them far inside.
std::int32_t angle_units(double radians) {
  return static_cast<std::int32_t>(core::angle_units(radians));
}
std::int32_t millimetres(double metres) {
  return static_cast<std::int32_t>(core::millimetres(metres));
}

}  // namespace

void check_grid_slam_config(const GridSlamConfig& c) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  require_field(positive(c.cell) && c.cell >= 0.001 && c.cell <= 10.0, "cell",
                "must be in [0.001, 10] metres");
  require_field(std::abs(c.cell * 1000.0 - std::round(c.cell * 1000.0)) < 1e-6, "cell",
                "must be a whole number of millimetres");
  require_field(c.headings >= 8 && c.headings <= core::kAngleUnitsPerTurn &&
                    (c.headings & (c.headings - 1)) == 0,
                "headings", "must be a power of two from 8 to 65536");
  require_field(c.window.cells >= 1 && c.window.cells <= 255 && c.window.cells % 2 == 1,
                "window.cells", "must be odd, 1..255");
  require_field(c.window.headings >= 1 && c.window.headings <= 255 && c.window.headings % 2 == 1 &&
                    c.window.headings <= c.headings,
                "window.headings", "must be odd, 1..255 and at most headings");
  require_field(c.schedule.lambda >= 1, "schedule.lambda", "must be >= 1");
  require_field(c.schedule.xi >= 1, "schedule.xi", "must be >= 1");
  core::check_range_sensor(c.sensor, "sensor");
  require_field(positive(c.beam.likelihood_floor) && c.beam.likelihood_floor < 1.0,
                "beam.likelihood_floor", "must be in (0, 1)");
  require_field(c.beam.beams >= 1, "beam.beams", "must be >= 1");
  require_field(c.map.empty_divisor >= 1 && c.map.empty_divisor <= 127, "map.empty_divisor",
                "must be 1..127");
  require_field(c.beam.tempering >= 1 && c.beam.tempering <= 1000, "beam.tempering",
                "must be 1..1000");
  require_field(std::isfinite(c.window.pose_cutoff) && c.window.pose_cutoff > 0.0 &&
                    c.window.pose_cutoff <= 1.0,
                "window.pose_cutoff", "must be in (0, 1]");
  require_field(std::isfinite(c.window.pose_prune) && c.window.pose_prune >= 0.0 &&
                    c.window.pose_prune < c.window.pose_cutoff,
                "window.pose_prune", "must be in [0, window.pose_cutoff)");
  for (const double v : {c.motion.xy0, c.motion.xy_per_m, c.motion.xy_per_rad, c.motion.theta0,
                         c.motion.theta_per_m, c.motion.theta_per_rad})
    require_field(non_negative(v) && v < 100.0, "motion", "must be finite, >= 0 and < 100");
  require_field(c.map.seps_bits >= 2 && c.map.seps_bits <= 8, "map.seps_bits",
                "must be 2..8 (the map is 8-bit)");
  require_field(c.map.seps_levels >= 1 && c.map.seps_levels < (1 << (c.map.seps_bits - 1)),
                "map.seps_levels", "must be >= 1 and below the largest index");
  require_field(c.ugamma.bits >= 12 && c.ugamma.bits <= 24, "ugamma.bits", "must be 12..24");
  require_field(c.ugamma.steps_per_halving >= 1 && c.ugamma.steps_per_halving <= 256,
                "ugamma.steps_per_halving", "must be 1..256");
  require_field(non_negative(c.map.margin) && c.map.margin <= 1000.0, "map.margin",
                "must be in [0, 1000]");
}

SlamSetup make_slam_setup(const GridSlamConfig& config, const core::Scan& geometry,
                          double reach_m) {
  check_grid_slam_config(config);
  if (!std::isfinite(reach_m) || reach_m < 0.0)
    core::fail<std::invalid_argument>("SLAM: bad odometry reach");
  SlamSetup s;
  s.config = config;
  s.cell_mm = millimetres(config.cell);
  s.sigma_mm = std::max<std::int32_t>(1, millimetres(config.sensor.sigma));
  s.max_range_mm = millimetres(config.sensor.max_range);

  for (std::size_t i = 0; i < geometry.ranges.size(); ++i)
    s.sensor.bearing.push_back(angle_units(geometry.bearing(i)));
  s.sensor.mount_x_mm = millimetres(geometry.sensor_mount.x);
  s.sensor.mount_y_mm = millimetres(geometry.sensor_mount.y);
  s.sensor.mount_theta = angle_units(geometry.sensor_mount.theta);
  const double mount = std::hypot(geometry.sensor_mount.x, geometry.sensor_mount.y);
  if (!std::isfinite(mount) || mount > 100.0)
    core::fail<std::invalid_argument>("SLAM: the sensor is mounted more than 100 m from the robot");

  // A square map centred on the first pose, cell (half, half) centred on it, that holds every
  // ray of every window pose (GridSlamEngine::check_window_inside_map) while the odometry stays
  // within reach_m.
  const double half_m = reach_m + config.sensor.max_range + 3.0 * config.sensor.sigma +
                        2.0 * mount + config.map.margin;
  if (!(half_m / config.cell < 32767.0))
    core::fail<std::invalid_argument>("SLAM: the map would exceed 65535 cells a side");
  const auto half =
      static_cast<long long>(std::ceil(half_m / config.cell)) + config.window.cells / 2 + 4;
  if (2 * half + 1 > 65535)
    core::fail<std::invalid_argument>("SLAM: the map would exceed 65535 cells a side");
  s.origin_cell_x = s.origin_cell_y = static_cast<int>(half);
  s.map_geometry.width = s.map_geometry.height = static_cast<int>(2 * half + 1);
  s.map_geometry.resolution = config.cell;
  s.map_geometry.origin_x = s.map_geometry.origin_y =
      -(static_cast<double>(half) + 0.5) * config.cell;
  core::check_geometry(s.map_geometry);

  s.sin_q16 = core::make_sine_table_q16();

  // The narrow ISM of every reading on a grid of z_step, as the map job's integer path makes it.
  s.codec = core::SepsCodec::for_levels(config.map.seps_bits,
                                        core::narrow_pmax(config.cell, config.sensor.sigma),
                                        config.map.seps_levels);
  s.max_seps_index = s.codec.max_index();
  s.ism = core::make_index_ism_table(core::GaussianBeamModel{config.sensor.sigma, 0.0}, config.cell,
                                     s.codec, std::max<std::int32_t>(1, s.cell_mm / 8),
                                     s.max_range_mm, config.map.empty_divisor);

  const double unit_rad = core::kRadiansPerAngleUnit;
  s.motion_xy0_mm = millimetres(config.motion.xy0);
  s.motion_xy_per_mm_q16 = std::llround(config.motion.xy_per_m * 65536.0);
  s.motion_xy_per_unit_q16 = std::llround(config.motion.xy_per_rad * 1000.0 * unit_rad * 65536.0);
  s.motion_theta0 = angle_units(config.motion.theta0);
  s.motion_theta_per_mm_q16 = std::llround(config.motion.theta_per_m / unit_rad / 1000.0 * 65536.0);
  s.motion_theta_per_unit_q16 = std::llround(config.motion.theta_per_rad * 65536.0);
  return s;
}

template <>
DoubleProbabilities make_probabilities<DoubleProbabilities>(const SlamSetup& setup) {
  DoubleProbabilities p;
  p.codec = setup.codec;
  p.floor = setup.config.beam.likelihood_floor;
  p.cutoff = setup.config.window.pose_cutoff;
  p.prune = setup.config.window.pose_prune;
  p.max_seps = setup.max_seps_index;
  for (int n = -p.max_seps; n <= p.max_seps; ++n) {
    p.occupied_of.push_back(setup.codec.probability(n));
    p.empty_of.push_back(setup.codec.probability(-n));
  }
  return p;
}

template <>
IndexProbabilities make_probabilities<IndexProbabilities>(const SlamSetup& setup) {
  IndexProbabilities p;
  p.u = core::UGamma(setup.config.ugamma.bits, setup.config.ugamma.steps_per_halving);
  p.floor = p.u.from_probability(setup.config.beam.likelihood_floor);
  p.cutoff = p.u.from_probability(setup.config.window.pose_cutoff);
  p.prune = p.u.from_probability(setup.config.window.pose_prune);
  p.max_seps = setup.max_seps_index;
  const double lambda = setup.codec.lambda();
  for (int n = -p.max_seps; n <= p.max_seps; ++n) {
    // ln p_n = -ln(1 + e^(-n lambda)), kept precise near 1.
    p.occupied_of.push_back(p.u.from_log(-std::log1p(std::exp(-n * lambda))));
    p.empty_of.push_back(p.u.from_log(-std::log1p(std::exp(n * lambda))));
  }
  const double ln_inv_gamma = std::log(2.0) / setup.config.ugamma.steps_per_halving;
  p.gaussian_q20 = std::llround(std::ldexp(1.0, 20) / (2.0 * ln_inv_gamma));
  p.seps_per_step_q16 = std::llround(65536.0 * ln_inv_gamma / lambda);
  for (core::UIndex i = 0;; ++i) {
    const long long w = std::llround(std::ldexp(std::exp(-ln_inv_gamma * i), 20));
    if (w == 0) break;
    p.weight_q20.push_back(w);
  }
  return p;
}

template <class Pr>
GridSlamEngine<Pr>::GridSlamEngine(const SlamSetup& setup, Pr probabilities)
    : setup_(setup),
      prob_(std::move(probabilities)),
      map_(setup.map_geometry, std::int8_t{0}),
      n_(setup.config.window.cells),
      nt_(setup.config.window.headings) {
  const std::size_t poses =
      static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_) * static_cast<std::size_t>(nt_);
  pi_.assign(poses, prob_.zero());
  next_.assign(poses, prob_.zero());
  row_.assign(static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_), prob_.zero());
  plane_ = row_;
  cell_empty_.assign(map_.cells.size(), prob_.empty_factor(0));
  empty_products_.assign(row_.size(), prob_.empty_product_start());
  joints_.assign(row_.size(), typename Pr::Joint{});
  ox_ = oy_ = -(n_ / 2);
  theta0_ = -std::int64_t{nt_ / 2} * heading_unit();
  pi_[pose_index(n_ / 2, n_ / 2, nt_ / 2)] = prob_.one();
  scan_image_.assign(map_.cells.size(), 0);
  slot_.assign(map_.cells.size(), -1);
  kernel_x_.reserve(2 * static_cast<std::size_t>(n_));
  kernel_y_.reserve(2 * static_cast<std::size_t>(n_));
  kernel_t_.reserve(2 * static_cast<std::size_t>(nt_));
  heading_rays_.assign(static_cast<std::size_t>(nt_) + 1, 0);
  // A localization walks at most `beams` rays per heading, each to max_range + 3 sigma: a walk
  // of length L crosses at most sqrt(2) L / cell + 2 cells.
  const std::size_t count = setup.sensor.bearing.size();
  const std::size_t beams = static_cast<std::size_t>(setup.config.beam.beams);
  const std::size_t stride = std::max<std::size_t>(1, (count + beams - 1) / beams);
  const std::size_t rays_per_heading = (count + stride / 2) / stride + 1;
  const std::size_t cells_per_ray =
      2 * static_cast<std::size_t>((setup.max_range_mm + 3 * setup.sigma_mm) / setup.cell_mm) + 4;
  scan_rays_.reserve(static_cast<std::size_t>(nt_) * rays_per_heading);
  ray_offsets_.reserve(scan_rays_.capacity() * cells_per_ray);
  ray_likelihoods_.reserve(ray_offsets_.capacity());
}

template GridSlamEngine<DoubleProbabilities>::GridSlamEngine(const SlamSetup&, DoubleProbabilities);
template GridSlamEngine<IndexProbabilities>::GridSlamEngine(const SlamSetup&, IndexProbabilities);

}  // namespace intgrid::slam
