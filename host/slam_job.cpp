#include "host/slam_job.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "host/atomic_file.hpp"
#include "host/image_io.hpp"
#include "host/input_error.hpp"
#include "host/log_io.hpp"
#include "host/map_io.hpp"
#include "host/progress.hpp"
#include "host/text_io.hpp"

namespace intgrid {
namespace {

nlohmann::json error_json(const TrajectoryError& e) {
  return {{"rmse_m", e.rmse},
          {"max_m", e.max},
          {"matched", e.matched},
          {"mean_heading_error_deg", e.mean_heading * 180.0 / M_PI}};
}

void write_trajectory(const std::filesystem::path& file, const std::vector<TimedPose>& poses) {
  write_file_atomically(file, [&](std::ostream& out) {
    out << "# t x y theta (s, m, m, rad): the SLAM estimate of each scan\n";
    for (const TimedPose& p : poses)
      out << format_number(p.t) << ' ' << format_number(p.pose.x) << ' ' << format_number(p.pose.y)
          << ' ' << format_number(p.pose.theta) << '\n';
  });
}

std::vector<Pose2> positions(const std::vector<TimedPose>& poses) {
  std::vector<Pose2> out;
  for (const TimedPose& p : poses) out.push_back(p.pose);
  return out;
}

}  // namespace

SlamJobResult run_slam_job(const SlamJobOptions& o) {
  const Log log = read_log(o.log);
  std::optional<Log> reference;
  if (o.reference) reference = read_log(*o.reference);
  try {
    check_slam_log(log);
  } catch (const std::invalid_argument& e) {
    throw InputError(o.log, 0, "scans", e.what());
  }
  if (reference && reference->scans.empty())
    throw InputError(*o.reference, 0, "scans", "the reference log has no scans");

  SlamJobResult r;
  const auto start = std::chrono::steady_clock::now();
  {
    TerminalProgress progress(o.arithmetic == Arithmetic::integer ? "SLAM (integer)"
                                                                  : "SLAM (double)");
    Progress report;
    if (o.progress) report = std::ref(progress);
    r.run = run_slam(log, o.config, o.arithmetic, report);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.log_seconds = log.scans.back().t - log.scans.front().t;
  if (reference) {
    const std::vector<TimedPose> ref = scan_poses(*reference);
    try {
      r.ate = absolute_trajectory_error(r.run.trajectory, ref);
      r.odometry_ate = absolute_trajectory_error(scan_poses(log), ref);
    } catch (const std::invalid_argument& e) {
      throw InputError(*o.reference, 0, "t", std::string(e.what()) + " in " + o.log.string());
    }
  }

  const SlamConfig& c = o.config;
  r.metrics = {{"log", o.log.string()},
               {"arith", o.arithmetic == Arithmetic::integer ? "int" : "float"},
               {"scans", r.run.scans},
               {"skipped_scans", r.run.skipped_scans},
               {"localizations", r.run.localizations},
               {"mappings", r.run.mappings},
               {"readings", r.run.readings},
               {"unusable_readings", r.run.unusable_readings},
               {"seconds", r.seconds},
               {"log_seconds", r.log_seconds},
               {"real_time_factor", r.seconds > 0.0 ? r.log_seconds / r.seconds : 0.0},
               {"e_sigma_m", r.run.mean_sigma()},
               {"settings",
                {{"res", c.cell},
                 {"lambda", c.lambda},
                 {"xi", c.xi},
                 {"beams", c.beams},
                 {"headings", c.headings},
                 {"window_cells", c.window_cells},
                 {"window_headings", c.window_headings},
                 {"sigma", c.sigma},
                 {"max_range", c.max_range},
                 {"eps", r.run.codec.eps()}}}};
  if (r.ate) {
    r.metrics["reference"] = o.reference->string();
    r.metrics["ate"] = error_json(*r.ate);
    r.metrics["odometry_ate"] = error_json(*r.odometry_ate);
  }

  std::filesystem::create_directories(o.out);
  write_trajectory(o.out / "trajectory.txt", r.run.trajectory);
  const ProbabilityGrid map = slam_map_probabilities(r.run);
  write_ros_map(o.out / "map.yaml", RosMap{map});
  RgbImage image = render_probability_grid(map);
  draw_polyline_world(image, map.geometry, positions(scan_poses(log)), {150, 150, 150});
  if (reference)
    draw_polyline_world(image, map.geometry, positions(scan_poses(*reference)), {30, 160, 30});
  draw_polyline_world(image, map.geometry, positions(r.run.trajectory), {220, 30, 30});
  write_png(o.out / "map.png", image);
  write_file_atomically(o.out / "metrics.json", r.metrics.dump(2) + "\n");
  return r;
}

}  // namespace intgrid
