#include "cli/localize_job.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/log_input.hpp"
#include "cli/output_folder_option.hpp"
#include "cli/progress.hpp"
#include "cli/trajectory_output.hpp"
#include "intgrid/figures/figure_layout.hpp"
#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/image_io.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/io/map_io.hpp"
#include "intgrid/io/text_io.hpp"

namespace intgrid::cli {

LocalizeJobResult run_localize_job(const LocalizeJobOptions& o) {
  const io::RosMap ros = io::read_ros_map(o.map);
  slam::SubmapSlamConfig config = o.config;
  config.cell = ros.grid.geometry.resolution;
  try {
    slam::check_submap_slam_config(config);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(o.map, 0, "resolution", e.what());
  }
  const LogInput input = read_log_input(o.log);
  const core::Log& log = input.log;
  if (log.scans.empty()) throw io::InputError(o.log, 0, "scans", "the log has no scans");
  std::optional<std::vector<slam::TimedPose>> reference;
  if (o.reference) reference = slam::scan_poses(io::read_log(*o.reference));

  slam::MapLocalizer localizer(config, o.arithmetic, slam::map_indices(ros.grid, config),
                               o.initial);
  io::OutputFolder out = open_output_folder(o.out);
  LocalizeJobResult r;
  const auto start = std::chrono::steady_clock::now();
  {
    TerminalProgress progress(o.arithmetic == core::Arithmetic::integer ? "localize (integer)"
                                                                        : "localize (double)");
    for (std::size_t i = 0; i < log.scans.size(); ++i) {
      const core::Scan& scan = log.scans[i];
      try {
        r.fixes.push_back(localizer.localize(scan));
      } catch (const std::invalid_argument& e) {
        throw io::InputError(o.log, 0, "scans", e.what());
      }
      r.trajectory.push_back({scan.t, r.fixes.back().pose});
      if (o.progress) progress(i + 1, log.scans.size());
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The odometry as a tracker without the map would have it: carried from the same start.
  std::vector<slam::TimedPose> odometry;
  for (const core::Scan& scan : log.scans)
    odometry.push_back(
        {scan.t, core::compose(o.initial, core::relative(log.scans.front().robot, scan.robot))});
  if (reference) {
    try {
      r.ate = slam::absolute_trajectory_error(r.trajectory, *reference);
      r.odometry_ate = slam::absolute_trajectory_error(odometry, *reference);
    } catch (const std::invalid_argument& e) {
      throw io::InputError(*o.reference, 0, "t", std::string(e.what()) + " in " + o.log.string());
    }
  }

  std::size_t matched = 0, wide = 0;
  for (const slam::MapFix& f : r.fixes) {
    matched += f.matched;
    wide += f.wide;
  }
  const double log_seconds = log.scans.back().t - log.scans.front().t;
  r.metrics = {{"map", o.map.string()},
               {"log", o.log.string()},
               {"arith", o.arithmetic == core::Arithmetic::integer ? "int" : "float"},
               {"scans", log.scans.size()},
               {"matched_scans", matched},
               {"wide_searches", wide},
               {"skipped_records", skipped_records_json(input.skipped)},
               {"seconds", r.seconds},
               {"log_seconds", log_seconds},
               {"real_time_factor", r.seconds > 0.0 ? log_seconds / r.seconds : 0.0},
               {"initial", {o.initial.x, o.initial.y, o.initial.theta}}};
  if (r.ate) {
    r.metrics["reference"] = o.reference->string();
    r.metrics["ate"] = error_json(*r.ate);
    r.metrics["odometry_ate"] = error_json(*r.odometry_ate);
  }

  write_trajectory(out.file("trajectory.txt"), r.trajectory,
                   "the localizer's estimate of each scan, in the map's frame");
  io::write_file_atomically(out.file("fit.csv"), [&](std::ostream& f) {
    f << "t,evidence,matched,wide\n";
    for (std::size_t i = 0; i < r.fixes.size(); ++i)
      f << io::format_number(r.trajectory[i].t) << ',' << io::format_number(r.fixes[i].evidence)
        << ',' << int{r.fixes[i].matched} << ',' << int{r.fixes[i].wide} << '\n';
  });
  io::RgbImage image = io::render_probability_grid(ros.grid);
  io::draw_polyline_world(image, ros.grid.geometry, positions(odometry), {150, 150, 150});
  if (reference)
    io::draw_polyline_world(image, ros.grid.geometry, positions(*reference), {30, 160, 30});
  io::draw_polyline_world(image, ros.grid.geometry, positions(r.trajectory), {220, 30, 30});
  std::vector<std::string> caption = {
      "Lines: red the localized path, grey the raw odometry from the same start" +
          std::string(reference ? ", green the reference" : "") + ".",
      "Scale: one pixel is one " + io::format_number(ros.grid.geometry.resolution * 100.0) +
          " cm cell (" + io::format_number(1.0 / ros.grid.geometry.resolution) +
          " pixels a metre); north up, the map's frame."};
  if (r.ate) {
    char line[160];
    std::snprintf(line, sizeof line, "ATE %.3f m, %.3f m at most (raw odometry %.3f m).",
                  r.ate->rmse, r.ate->max, r.odometry_ate->rmse);
    caption.emplace_back(line);
  }
  const std::string title =
      "Localization of " + o.log.filename().string() + " in " + o.map.filename().string() + " (" +
      (o.arithmetic == core::Arithmetic::integer ? "integer" : "double") + ")";
  io::write_png(out.file("map.png"),
                figures::compose_figure(title, {{{"occupancy", std::move(image)}}},
                                        io::ProbabilityScale::grey, caption));
  r.metrics["peak_memory_bytes"] = peak_memory_bytes();
  io::write_file_atomically(out.file("metrics.json"), r.metrics.dump(2) + "\n");
  out.commit();
  return r;
}

}  // namespace intgrid::cli
