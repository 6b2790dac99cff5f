#include "intgrid/slam/log_run.hpp"

#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/scan_insertion.hpp"
#include "intgrid/slam/probabilities.hpp"

namespace intgrid::slam {
namespace {

constexpr double kUnitRadians = 2.0 * std::numbers::pi / core::kAngleUnitsPerTurn;

std::string scan_name(const core::Log& log, std::size_t i) {
  char t[64];
  std::snprintf(t, sizeof t, "%.6f", log.scans[i].t);
  return "scan " + std::to_string(i + 1) + " (t = " + t + ")";
}

bool same_pose(const core::Pose2& a, const core::Pose2& b) {
  return a.x == b.x && a.y == b.y && a.theta == b.theta;
}

template <class Pr>
void run_with(const SlamSetup& setup, const std::vector<SlamScan>& scans, const core::Log& log,
              SlamRun& run, const core::Progress& progress) {
  GridSlam<Pr> slam(setup, make_probabilities<Pr>(setup));
  const core::Pose2 frame = log.scans.front().robot;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    slam.process(scans[i]);
    const SlamEstimate e = slam.estimate();
    const core::Pose2 local{static_cast<double>(e.x_um) * 1e-6, static_cast<double>(e.y_um) * 1e-6,
                            static_cast<double>(e.theta_q8) / 256.0 * kUnitRadians};
    core::Pose2 world = core::compose(frame, local);
    world.theta = core::wrap_angle(world.theta);
    run.trajectory.push_back({log.scans[i].t, world});
    run.sigma.push_back(static_cast<double>(e.sigma_um) * 1e-6);
    if (progress) progress(i + 1, scans.size());
  }
  run.map = slam.map();
  run.localizations = slam.localizations();
  run.mappings = slam.mappings();
  run.skipped_scans = slam.skipped_scans();
}

}  // namespace

double SlamRun::mean_sigma() const {
  return sigma.empty()
             ? 0.0
             : std::accumulate(sigma.begin(), sigma.end(), 0.0) / static_cast<double>(sigma.size());
}

void check_slam_log(const core::Log& log) {
  if (log.scans.empty()) core::fail<std::invalid_argument>("the log has no scans");
  const core::Scan& first = log.scans.front();
  if (first.ranges.empty()) core::fail<std::invalid_argument>(scan_name(log, 0) + " has no ranges");
  bool moves = !log.odometry.empty();
  for (std::size_t i = 1; i < log.scans.size(); ++i) {
    const core::Scan& s = log.scans[i];
    moves = moves || !same_pose(s.robot, first.robot);
    const char* differs = s.ranges.size() != first.ranges.size()                 ? "beam count"
                          : s.angle0 != first.angle0 || s.dangle != first.dangle ? "bearings"
                          : s.max_range != first.max_range                       ? "maximum range"
                          : !same_pose(s.sensor_mount, first.sensor_mount)       ? "sensor mount"
                                                                                 : nullptr;
    if (differs)
      core::fail<std::invalid_argument>(scan_name(log, i) + " has another " + differs +
                                        " than the first scan; SLAM needs one sensor geometry");
  }
  if (!moves && log.scans.size() > 1)
    core::fail<std::invalid_argument>(
        "the log has no odometry: no ODOM record, and every scan carries the same robot pose");
}

std::vector<SlamScan> quantize_scans(const core::Log& log, const SlamConfig& config, SlamRun& run) {
  std::vector<SlamScan> out;
  out.reserve(log.scans.size());
  const long long max_mm = std::llround(config.max_range * 1000.0);
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const core::Scan& scan = log.scans[i];
    SlamScan s;
    s.range_mm.reserve(scan.ranges.size());
    for (const double r : scan.ranges) {
      ++run.readings;
      const long long mm = core::classify_range(r, scan.max_range) == core::RangeClass::valid
                               ? std::llround(r * 1000.0)
                               : 0;
      const bool usable = mm > 0 && mm < max_mm;
      run.unusable_readings += !usable;
      s.range_mm.push_back(usable ? static_cast<std::int32_t>(mm) : 0);
    }
    if (i > 0) {
      const core::Pose2 u = core::relative(log.scans[i - 1].robot, scan.robot);
      if (!std::isfinite(u.x) || !std::isfinite(u.y) || !std::isfinite(u.theta) ||
          std::hypot(u.x, u.y) > 1000.0)
        core::fail<std::invalid_argument>(scan_name(log, i) +
                                          ": the odometry jumps more than 1 km or is not finite");
      s.odom_dx_mm = static_cast<std::int32_t>(std::llround(u.x * 1000.0));
      s.odom_dy_mm = static_cast<std::int32_t>(std::llround(u.y * 1000.0));
      s.odom_dtheta =
          static_cast<std::int32_t>(std::llround(core::wrap_angle(u.theta) / kUnitRadians));
    }
    out.push_back(std::move(s));
  }
  return out;
}

SlamRun run_slam(const core::Log& log, const SlamConfig& config, core::Arithmetic arithmetic,
                 const core::Progress& progress) {
  check_slam_config(config);
  check_slam_log(log);
  SlamRun run;
  const std::vector<SlamScan> scans = quantize_scans(log, config, run);
  const core::Pose2 first = log.scans.front().robot;
  double reach = 0.0;
  for (const core::Scan& s : log.scans)
    reach = std::max(reach, std::hypot(s.robot.x - first.x, s.robot.y - first.y));
  const SlamSetup setup = make_slam_setup(config, log.scans.front(), reach);
  run.codec = setup.codec;
  run.scans = scans.size();
  if (arithmetic == core::Arithmetic::integer)
    run_with<IndexProbabilities>(setup, scans, log, run, progress);
  else
    run_with<DoubleProbabilities>(setup, scans, log, run, progress);
  run.frame = first;
  return run;
}

core::ProbabilityGrid slam_map_probabilities(const SlamRun& run) {
  // The part of the map that any scan reached, and 10 cells around it.
  const core::GridGeometry& full = run.map.geometry;
  int x0 = full.width, y0 = full.height, x1 = -1, y1 = -1;
  for (int iy = 0; iy < full.height; ++iy)
    for (int ix = 0; ix < full.width; ++ix)
      if (run.map.at(ix, iy) != 0) {
        x0 = std::min(x0, ix);
        y0 = std::min(y0, iy);
        x1 = std::max(x1, ix);
        y1 = std::max(y1, iy);
      }
  if (x1 < 0) x0 = y0 = x1 = y1 = full.width / 2;
  x0 = std::max(0, x0 - 10);
  y0 = std::max(0, y0 - 10);
  x1 = std::min(full.width - 1, x1 + 10);
  y1 = std::min(full.height - 1, y1 + 10);
  core::GridGeometry g{x1 - x0 + 1, y1 - y0 + 1, full.resolution,
                       full.origin_x + x0 * full.resolution, full.origin_y + y0 * full.resolution};
  const auto probability = [&](int ix, int iy) {
    return run.codec.probability(run.map.at(ix + x0, iy + y0));
  };
  const core::Pose2& f = run.frame;
  if (f.theta == 0.0) {
    g.origin_x += f.x;
    g.origin_y += f.y;
    core::ProbabilityGrid out(g, 0.5);
    for (int iy = 0; iy < g.height; ++iy)
      for (int ix = 0; ix < g.width; ++ix) out.at(ix, iy) = probability(ix, iy);
    return out;
  }
  // Rotated: an axis-aligned grid over the map's corners, each cell read at its centre.
  const double w = g.width * g.resolution, h = g.height * g.resolution;
  double wx0 = 1e300, wy0 = 1e300, wx1 = -1e300, wy1 = -1e300;
  for (const auto& [cx, cy] : {std::pair{0.0, 0.0}, {w, 0.0}, {0.0, h}, {w, h}}) {
    const core::Pose2 p = core::compose(f, {g.origin_x + cx, g.origin_y + cy, 0.0});
    wx0 = std::min(wx0, p.x);
    wy0 = std::min(wy0, p.y);
    wx1 = std::max(wx1, p.x);
    wy1 = std::max(wy1, p.y);
  }
  const core::GridGeometry out_g{static_cast<int>(std::ceil((wx1 - wx0) / g.resolution)),
                                 static_cast<int>(std::ceil((wy1 - wy0) / g.resolution)),
                                 g.resolution, wx0, wy0};
  core::ProbabilityGrid out(out_g, 0.5);
  for (int iy = 0; iy < out_g.height; ++iy)
    for (int ix = 0; ix < out_g.width; ++ix) {
      const core::Pose2 p = core::relative(f, {out_g.centre_x(ix), out_g.centre_y(iy), 0.0});
      const int mx = g.cell_x(p.x), my = g.cell_y(p.y);
      if (g.contains(mx, my)) out.at(ix, iy) = probability(mx, my);
    }
  return out;
}

}  // namespace intgrid::slam
