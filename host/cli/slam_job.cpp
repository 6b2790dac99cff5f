#include "cli/slam_job.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/image_io.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/io/map_io.hpp"
#include "intgrid/io/text_io.hpp"

namespace intgrid::cli {
namespace {

nlohmann::json error_json(const slam::TrajectoryError& e) {
  return {{"rmse_m", e.rmse},
          {"max_m", e.max},
          {"matched", e.matched},
          {"mean_heading_error_deg", e.mean_heading * 180.0 / M_PI}};
}

void write_trajectory(const std::filesystem::path& file,
                      const std::vector<slam::TimedPose>& poses) {
  io::write_file_atomically(file, [&](std::ostream& out) {
    out << "# t x y theta (s, m, m, rad): the SLAM estimate of each scan\n";
    for (const slam::TimedPose& p : poses)
      out << io::format_number(p.t) << ' ' << io::format_number(p.pose.x) << ' '
          << io::format_number(p.pose.y) << ' ' << io::format_number(p.pose.theta) << '\n';
  });
}

std::vector<core::Pose2> positions(const std::vector<slam::TimedPose>& poses) {
  std::vector<core::Pose2> out;
  for (const slam::TimedPose& p : poses) out.push_back(p.pose);
  return out;
}

}  // namespace

SlamJobResult run_slam_job(const SlamJobOptions& o) {
  check_slam_options(o.config);
  const core::Log log = io::read_log(o.log);
  std::optional<core::Log> reference;
  if (o.reference) reference = io::read_log(*o.reference);
  try {
    slam::check_slam_log(log);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(o.log, 0, "scans", e.what());
  }
  if (reference && reference->scans.empty())
    throw io::InputError(*o.reference, 0, "scans", "the reference log has no scans");

  SlamJobResult r;
  const auto start = std::chrono::steady_clock::now();
  {
    TerminalProgress progress(o.arithmetic == core::Arithmetic::integer ? "SLAM (integer)"
                                                                        : "SLAM (double)");
    core::Progress report;
    if (o.progress) report = std::ref(progress);
    r.run = slam::run_slam(log, o.config, o.arithmetic, report);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.log_seconds = log.scans.back().t - log.scans.front().t;
  if (reference) {
    const std::vector<slam::TimedPose> ref = slam::scan_poses(*reference);
    try {
      r.ate = slam::absolute_trajectory_error(r.run.trajectory, ref);
      r.odometry_ate = slam::absolute_trajectory_error(slam::scan_poses(log), ref);
    } catch (const std::invalid_argument& e) {
      throw io::InputError(*o.reference, 0, "t", std::string(e.what()) + " in " + o.log.string());
    }
  }

  const slam::SlamConfig& c = o.config;
  r.metrics = {{"log", o.log.string()},
               {"arith", o.arithmetic == core::Arithmetic::integer ? "int" : "float"},
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
                 {"lambda", c.schedule.lambda},
                 {"xi", c.schedule.xi},
                 {"beams", c.beam.beams},
                 {"headings", c.headings},
                 {"window_cells", c.window.cells},
                 {"window_headings", c.window.headings},
                 {"sigma", c.beam.sigma},
                 {"max_range", c.beam.max_range},
                 {"eps", r.run.codec.eps()}}}};
  if (r.ate) {
    r.metrics["reference"] = o.reference->string();
    r.metrics["ate"] = error_json(*r.ate);
    r.metrics["odometry_ate"] = error_json(*r.odometry_ate);
  }

  std::filesystem::create_directories(o.out);
  write_trajectory(o.out / "trajectory.txt", r.run.trajectory);
  const core::ProbabilityGrid map = slam::slam_map_probabilities(r.run);
  io::write_ros_map(o.out / "map.yaml", io::RosMap{map});
  io::RgbImage image = io::render_probability_grid(map);
  io::draw_polyline_world(image, map.geometry, positions(slam::scan_poses(log)), {150, 150, 150});
  if (reference)
    io::draw_polyline_world(image, map.geometry, positions(slam::scan_poses(*reference)),
                            {30, 160, 30});
  io::draw_polyline_world(image, map.geometry, positions(r.run.trajectory), {220, 30, 30});
  io::write_png(o.out / "map.png", image);
  io::write_file_atomically(o.out / "metrics.json", r.metrics.dump(2) + "\n");
  return r;
}

}  // namespace intgrid::cli
