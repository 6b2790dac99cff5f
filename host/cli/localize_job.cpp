#include "cli/localize_job.hpp"

#include <algorithm>
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
#include "intgrid/io/relations_io.hpp"
#include "intgrid/io/text_io.hpp"

namespace intgrid::cli {

LocalizeJobResult run_localize_job(const LocalizeJobOptions& o) {
  const io::RosMap ros = io::read_ros_map(o.map);
  navigation::KnownMapLocalizerConfig config = o.config;
  config.tracking.cell = ros.grid.geometry.resolution;
  try {
    slam::check_submap_slam_config(config.tracking);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(o.map, 0, "resolution", e.what());
  }
  const LogInput input = read_log_input(o.log);
  const core::Log& log = input.log;
  if (log.scans.empty()) throw io::InputError(o.log, 0, "scans", "the log has no scans");
  std::optional<std::vector<slam::TimedPose>> reference;
  if (o.reference) reference = slam::scan_poses(io::read_log(*o.reference));
  RelationScoring scoring;
  if (o.relations) scoring = read_relations_for(*o.relations, o.log, log);

  std::optional<navigation::KnownMapLocalizer> localizer;
  try {
    localizer.emplace(ros.grid, ros.occupied_thresh, ros.free_thresh, config, o.arithmetic,
                      o.initial);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(o.map, 0, "image", e.what());
  }
  io::OutputFolder out = open_output_folder(o.out);
  LocalizeJobResult r;
  const auto start = std::chrono::steady_clock::now();
  {
    TerminalProgress progress(o.arithmetic == core::Arithmetic::integer ? "localize (integer)"
                                                                        : "localize (double)");
    for (std::size_t i = 0; i < log.scans.size(); ++i) {
      const core::Scan& scan = log.scans[i];
      try {
        r.steps.push_back(localizer->localize(scan));
      } catch (const std::invalid_argument& e) {
        throw io::InputError(o.log, 0, "scans", e.what());
      }
      if (r.steps.back().pose) r.trajectory.push_back({scan.t, *r.steps.back().pose});
      if (o.progress) progress(i + 1, log.scans.size());
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The odometry as a tracker without the map would have it: carried from the first pose found.
  const auto first_fix = std::find_if(r.steps.begin(), r.steps.end(),
                                      [](const navigation::LocalizerStep& s) { return s.pose; });
  std::vector<slam::TimedPose> odometry;
  if (first_fix != r.steps.end()) {
    const std::size_t f = static_cast<std::size_t>(first_fix - r.steps.begin());
    for (std::size_t i = f; i < log.scans.size(); ++i)
      odometry.push_back(
          {log.scans[i].t, core::compose(*first_fix->pose,
                                         core::relative(log.scans[f].robot, log.scans[i].robot))});
  }
  if (reference && !r.trajectory.empty()) {
    try {
      r.ate = slam::absolute_trajectory_error(r.trajectory, *reference);
      r.odometry_ate = slam::absolute_trajectory_error(odometry, *reference);
    } catch (const std::invalid_argument& e) {
      throw io::InputError(*o.reference, 0, "t", std::string(e.what()) + " in " + o.log.string());
    }
  }

  std::vector<slam::RelationResult> relation_results;
  if (o.relations) {
    relation_results = slam::relation_errors(by_time(r.trajectory), scoring.relations);
    r.relations = slam::summarize_relations(relation_results);
    r.odometry_relations = slam::summarize_relations(scoring.odometry);
  }

  std::size_t matched = 0, wide = 0, lost = 0, tracked = 0, verified = 0, refixed = 0;
  for (const navigation::LocalizerStep& s : r.steps) {
    matched += s.fix.matched;
    wide += s.fix.wide;
    lost += s.state == navigation::LocalizerState::lost;
    tracked += s.state == navigation::LocalizerState::tracking;
    verified += s.verified;
    refixed += s.refixed;
  }
  const double log_seconds = log.scans.back().t - log.scans.front().t;
  r.metrics = {{"map", o.map.string()},
               {"log", o.log.string()},
               {"arith", o.arithmetic == core::Arithmetic::integer ? "int" : "float"},
               {"scans", log.scans.size()},
               {"tracked_scans", tracked},
               {"matched_scans", matched},
               {"wide_searches", wide},
               {"lost", lost},
               {"verified_scans", verified},
               {"refixed", refixed},
               {"skipped_records", skipped_records_json(input.skipped)},
               {"seconds", r.seconds},
               {"log_seconds", log_seconds},
               {"real_time_factor", r.seconds > 0.0 ? log_seconds / r.seconds : 0.0}};
  r.metrics["initial"] = o.initial ? nlohmann::json{o.initial->x, o.initial->y, o.initial->theta}
                                   : nlohmann::json(nullptr);
  r.metrics["first_pose_scan"] = first_fix != r.steps.end()
                                     ? nlohmann::json(first_fix - r.steps.begin())
                                     : nlohmann::json(nullptr);
  if (r.ate) {
    r.metrics["reference"] = o.reference->string();
    r.metrics["ate"] = error_json(*r.ate);
    r.metrics["odometry_ate"] = error_json(*r.odometry_ate);
  }
  // Relations with an end at a scan that was not tracked count as unmatched.
  if (o.relations)
    add_relation_metrics(r.metrics, *o.relations, *r.relations, *r.odometry_relations,
                         relation_results, log.scans.front().t);

  if (o.relations)
    write_relation_errors(out.file("relations.csv"), relation_results, scoring.odometry);
  if (o.tum) io::write_tum_trajectory(*o.tum, r.trajectory);
  write_trajectory(out.file("trajectory.txt"), r.trajectory,
                   "the localizer's estimate of each scan, in the map's frame");
  io::write_file_atomically(out.file("fit.csv"), [&](std::ostream& f) {
    f << "t,state,verified,refixed,evidence,matched,wide,hits,fit,fused_scans\n";
    for (std::size_t i = 0; i < r.steps.size(); ++i) {
      const navigation::LocalizerStep& s = r.steps[i];
      f << io::format_number(log.scans[i].t) << ',' << navigation::state_name(s.state) << ','
        << int{s.verified} << ',' << int{s.refixed} << ',' << io::format_number(s.fix.evidence)
        << ',' << int{s.fix.matched} << ',' << int{s.fix.wide} << ',' << s.fix.hits << ','
        << io::format_number(s.fix.fit) << ',' << s.fused_scans << '\n';
    }
  });
  io::RgbImage image = io::render_probability_grid(ros.grid);
  io::draw_polyline_world(image, ros.grid.geometry, positions(odometry), {150, 150, 150});
  if (reference)
    io::draw_polyline_world(image, ros.grid.geometry, positions(*reference), {30, 160, 30});
  // Each stretch tracked without a break its own line: a robot found again elsewhere is not
  // joined to where it was lost.
  std::vector<slam::TimedPose> stretch;
  for (std::size_t i = 0; i <= r.steps.size(); ++i) {
    if (i < r.steps.size() && r.steps[i].pose) {
      stretch.push_back({log.scans[i].t, *r.steps[i].pose});
      continue;
    }
    io::draw_polyline_world(image, ros.grid.geometry, positions(stretch), {220, 30, 30});
    stretch.clear();
  }
  std::vector<std::string> caption = {
      "Lines: red the localized path, grey the raw odometry from its first pose" +
          std::string(reference ? ", green the reference" : "") + ".",
      map_scale_caption(ros.grid.geometry, "the map's")};
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
