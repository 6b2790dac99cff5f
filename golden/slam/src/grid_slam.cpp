#include "intgrid/slam/grid_slam.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <variant>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/scan_insertion.hpp"
#include "intgrid/core/units.hpp"
#include "intgrid/slam/log_run.hpp"
#include "intgrid/slam/probabilities.hpp"

namespace intgrid::slam {
namespace {}  // namespace

std::string scan_label(std::size_t number, double t) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", t);
  return "scan " + std::to_string(number) + " (t = " + text + ")";
}

const char* geometry_difference(const core::Scan& b, const core::Scan& a) {
  return b.ranges.size() != a.ranges.size()             ? "beam count"
         : b.angle0 != a.angle0 || b.dangle != a.dangle ? "bearings"
         : b.max_range != a.max_range                   ? "maximum range"
         : b.sensor_mount != a.sensor_mount             ? "sensor mount"
                                                        : nullptr;
}

QuantizedScan quantize_scan(const core::Scan& scan, const core::Pose2* previous_robot,
                            double max_range, const std::string& name, std::size_t& readings,
                            std::size_t& unusable) {
  QuantizedScan s;
  const long long max_mm = core::millimetres(max_range);
  s.range_mm.reserve(scan.ranges.size());
  for (const double r : scan.ranges) {
    ++readings;
    const long long mm = core::classify_range(r, scan.max_range) == core::RangeClass::valid
                             ? core::millimetres(r)
                             : 0;
    const bool usable = mm > 0 && mm < max_mm;
    unusable += !usable;
    s.range_mm.push_back(usable ? static_cast<std::int32_t>(mm) : 0);
  }
  if (previous_robot) {
    const core::Pose2 u = core::relative(*previous_robot, scan.robot);
    if (!std::isfinite(u.x) || !std::isfinite(u.y) || !std::isfinite(u.theta) ||
        std::hypot(u.x, u.y) > 1000.0)
      core::fail<std::invalid_argument>(name +
                                        ": the odometry jumps more than 1 km or is not finite");
    s.odom_dx_mm = static_cast<std::int32_t>(core::millimetres(u.x));
    s.odom_dy_mm = static_cast<std::int32_t>(core::millimetres(u.y));
    s.odom_dtheta = static_cast<std::int32_t>(core::angle_units(core::wrap_angle(u.theta)));
  }
  return s;
}

struct GridSlam::Engine {
  std::variant<GridSlamEngine<IndexProbabilities>, GridSlamEngine<DoubleProbabilities>> slam;

  template <class F>
  decltype(auto) visit(F&& f) {
    return std::visit(std::forward<F>(f), slam);
  }
  template <class F>
  decltype(auto) visit(F&& f) const {
    return std::visit(std::forward<F>(f), slam);
  }
};

namespace {

template <class Pr>
GridSlamEngine<Pr> make_engine(const SlamSetup& setup) {
  return GridSlamEngine<Pr>(setup, make_probabilities<Pr>(setup));
}

}  // namespace

GridSlam::GridSlam(const GridSlamConfig& config, core::Arithmetic arithmetic,
                   const core::Scan& first, double reach_m)
    : geometry_(first), frame_(first.robot), previous_robot_(first.robot) {
  const SlamSetup setup = make_slam_setup(config, first, reach_m);
  geometry_.ranges.assign(first.ranges.size(), 0.0);
  engine_ = arithmetic == core::Arithmetic::integer
                ? std::make_unique<Engine>(Engine{make_engine<IndexProbabilities>(setup)})
                : std::make_unique<Engine>(Engine{make_engine<DoubleProbabilities>(setup)});
}

GridSlam::~GridSlam() = default;
GridSlam::GridSlam(GridSlam&&) noexcept = default;
GridSlam& GridSlam::operator=(GridSlam&&) noexcept = default;

void GridSlam::insert(const core::Scan& scan) {
  const std::size_t number = scans() + 1;
  if (const char* differs = geometry_difference(scan, geometry_))
    core::fail<std::invalid_argument>(scan_label(number, scan.t) + " has another " + differs +
                                      " than the first scan; the grid engine needs one sensor "
                                      "geometry (the submaps engine takes each scan's own)");
  const GridSlamConfig& config =
      engine_->visit([](const auto& s) -> const GridSlamConfig& { return s.setup().config; });
  const QuantizedScan q = quantize_scan(scan, number > 1 ? &previous_robot_ : nullptr, config,
                                        scan_label(number, scan.t), readings_, unusable_);
  engine_->visit([&](auto& s) { s.process(q); });
  previous_robot_ = scan.robot;
}

core::Pose2 GridSlam::pose() const {
  const SlamEstimate e = engine_->visit([](const auto& s) { return s.estimate(); });
  const core::Pose2 local{static_cast<double>(e.x_um) * 1e-6, static_cast<double>(e.y_um) * 1e-6,
                          static_cast<double>(e.theta_q8) / 256.0 * core::kRadiansPerAngleUnit};
  core::Pose2 world = core::compose(frame_, local);
  world.theta = core::wrap_angle(world.theta);
  return world;
}

double GridSlam::sigma() const {
  return static_cast<double>(engine_->visit([](const auto& s) { return s.estimate(); }).sigma_um) *
         1e-6;
}

const core::Grid<std::int8_t>& GridSlam::map() const {
  return engine_->visit([](const auto& s) -> const core::Grid<std::int8_t>& { return s.map(); });
}

const core::SepsCodec& GridSlam::codec() const {
  return engine_->visit([](const auto& s) -> const core::SepsCodec& { return s.setup().codec; });
}

core::ProbabilityGrid GridSlam::map_probabilities() const {
  return slam_map_probabilities(map(), codec(), frame_);
}

std::size_t GridSlam::scans() const {
  return engine_->visit([](const auto& s) { return s.scans(); });
}
std::size_t GridSlam::localizations() const {
  return engine_->visit([](const auto& s) { return s.localizations(); });
}
std::size_t GridSlam::mappings() const {
  return engine_->visit([](const auto& s) { return s.mappings(); });
}
std::size_t GridSlam::skipped_scans() const {
  return engine_->visit([](const auto& s) { return s.skipped_scans(); });
}

}  // namespace intgrid::slam
