#include "intgrid/slam/log_run.hpp"

#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/scan_insertion.hpp"
#include "intgrid/slam/grid_slam.hpp"
#include "intgrid/slam/probabilities.hpp"

namespace intgrid::slam {
namespace {

std::string scan_name(const core::Log& log, std::size_t i) {
  return scan_label(i + 1, log.scans[i].t);
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
  for (const core::Scan& s : log.scans) moves = moves || s.robot != first.robot;
  if (!moves && log.scans.size() > 1)
    core::fail<std::invalid_argument>(
        "the log has no odometry: no ODOM record, and every scan carries the same robot pose");
}

void check_one_sensor_geometry(const core::Log& log) {
  for (std::size_t i = 1; i < log.scans.size(); ++i)
    if (const char* differs = geometry_difference(log.scans[i], log.scans.front()))
      core::fail<std::invalid_argument>(
          scan_name(log, i) + " has another " + differs +
          " than the first scan; the grid engine needs one sensor geometry (the submaps engine "
          "takes each scan's own)");
}

std::vector<QuantizedScan> quantize_scans(const core::Log& log, const GridSlamConfig& config,
                                          SlamRun& run) {
  std::vector<QuantizedScan> out;
  out.reserve(log.scans.size());
  for (std::size_t i = 0; i < log.scans.size(); ++i)
    out.push_back(quantize_scan(log.scans[i], i > 0 ? &log.scans[i - 1].robot : nullptr, config,
                                scan_name(log, i), run.readings, run.unusable_readings));
  return out;
}

double odometry_reach(std::span<const core::Scan> scans) {
  double reach = 0.0;
  if (scans.empty()) return reach;
  const core::Pose2 first = scans.front().robot;
  for (const core::Scan& s : scans)
    reach = std::max(reach, std::hypot(s.robot.x - first.x, s.robot.y - first.y));
  return reach;
}

SlamRun run_grid_slam(const core::Log& log, const GridSlamConfig& config,
                      core::Arithmetic arithmetic, const core::Progress& progress) {
  check_grid_slam_config(config);
  check_slam_log(log);
  check_one_sensor_geometry(log);
  GridSlam slam(config, arithmetic, log.scans.front(), odometry_reach(log.scans));
  SlamRun run;
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    slam.insert(log.scans[i]);
    run.trajectory.push_back({log.scans[i].t, slam.pose()});
    run.sigma.push_back(slam.sigma());
    if (progress) progress(i + 1, log.scans.size());
  }
  run.map = slam.map();
  run.codec = slam.codec();
  run.frame = slam.frame();
  run.scans = slam.scans();
  run.localizations = slam.localizations();
  run.mappings = slam.mappings();
  run.skipped_scans = slam.skipped_scans();
  run.readings = slam.readings();
  run.unusable_readings = slam.unusable_readings();
  return run;
}

core::ProbabilityGrid slam_map_probabilities(const SlamRun& run) {
  return slam_map_probabilities(run.map, run.codec, run.frame);
}

core::ProbabilityGrid slam_map_probabilities(const core::Grid<std::int8_t>& map,
                                             const core::SepsCodec& codec,
                                             const core::Pose2& frame) {
  const core::GridGeometry& full = map.geometry;
  int x0 = full.width, y0 = full.height, x1 = -1, y1 = -1;
  for (int iy = 0; iy < full.height; ++iy)
    for (int ix = 0; ix < full.width; ++ix)
      if (map.at(ix, iy) != 0) {
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
    return codec.probability(map.at(ix + x0, iy + y0));
  };
  const core::Pose2& f = frame;
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
