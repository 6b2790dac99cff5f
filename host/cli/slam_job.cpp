#include "cli/slam_job.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/log_input.hpp"
#include "cli/output_folder_option.hpp"
#include "cli/progress.hpp"
#include "cli/trajectory_output.hpp"
#include "intgrid/core/parallel.hpp"
#include "intgrid/figures/figure_layout.hpp"
#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/image_io.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/io/map_io.hpp"
#include "intgrid/io/relations_io.hpp"
#include "intgrid/io/text_io.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"

namespace intgrid::cli {
namespace {

// The submaps engine's settings, nested as SubmapSlamConfig is (the fields' paths of
// check_submap_slam_config), and the map's eps.
nlohmann::json submap_settings_json(const slam::SubmapSlamConfig& c, const core::SepsCodec& codec) {
  const auto& t = c.tracking;
  const auto& l = c.loops;
  const auto& g = c.graph;
  return {{"cell", c.cell},
          {"headings", c.headings},
          {"sensor", {{"sigma", c.sensor.sigma}, {"max_range", c.sensor.max_range}}},
          {"map",
           {{"seps_bits", c.map.seps_bits},
            {"seps_levels", c.map.seps_levels},
            {"empty_divisor", c.map.empty_divisor}}},
          {"eps", codec.eps()},
          {"submaps",
           {{"scans", c.submaps.scans},
            {"rematch", c.submaps.rematch},
            {"handover_scans", c.submaps.handover_scans}}},
          {"filter",
           {{"distance", c.filter.distance},
            {"degrees", c.filter.degrees},
            {"seconds", c.filter.seconds}}},
          {"tracking",
           {{"window", t.window},
            {"window_degrees", t.window_degrees},
            {"wide_below", t.wide_below},
            {"wide_window", t.wide_window},
            {"wide_degrees", t.wide_degrees},
            {"prior_xy", t.prior_xy},
            {"prior_xy_per_m", t.prior_xy_per_m},
            {"prior_degrees", t.prior_degrees},
            {"prior_degrees_per_degree", t.prior_degrees_per_degree},
            {"min_hits", t.min_hits}}},
          {"loops",
           {{"every", l.every},
            {"max_distance", l.max_distance},
            {"submaps", l.submaps},
            {"window", l.window},
            {"window_degrees", l.window_degrees},
            {"min_score", l.min_score},
            {"drift", l.drift},
            {"switch_off", l.switch_off},
            {"sigma_xy", l.sigma_xy},
            {"sigma_degrees", l.sigma_degrees}}},
          {"graph",
           {{"local_sigma_xy", g.local_sigma_xy},
            {"local_sigma_degrees", g.local_sigma_degrees},
            {"odometry_sigma_xy", g.odometry_sigma_xy},
            {"odometry_sigma_degrees", g.odometry_sigma_degrees},
            {"optimize_every", g.optimize_every},
            {"iterations", g.iterations},
            {"huber", g.huber}}}};
}

}  // namespace

const char* engine_name(SlamEngine engine) {
  return engine == SlamEngine::grid ? "grid" : "submaps";
}

std::string slam_summary(const SlamJobResult& r) {
  std::string line;
  if (r.ate)
    line = io::printed("ATE %.3f m (raw odometry %.2f m), ", r.ate->rmse, r.odometry_ate->rmse);
  if (r.submap_stats) {
    const slam::SubmapSlamStats& s = *r.submap_stats;
    const auto count = [](std::size_t n, const char* one, const char* many) {
      return io::printed("%zu %s", n, n == 1 ? one : many);
    };
    line += count(s.nodes, "node", "nodes") + " in " + count(s.submaps, "submap", "submaps") +
            ", " + count(s.loop_closures, "loop closure", "loop closures") +
            io::printed(" of %zu searched, ", s.loop_searches);
  } else {
    line += io::printed("E(sigma) %.1f mm, ", r.run.mean_sigma() * 1e3);
  }
  return line + io::printed("%.2f s for %.1f s of data (%.1fx real time)", r.seconds, r.log_seconds,
                            r.seconds > 0.0 ? r.log_seconds / r.seconds : 0.0);
}

std::string relation_summary(const std::string& what, const slam::RelationError& e) {
  return io::printed(
      "%s: %zu matched, %zu unmatched; translation %.3g ± %.3g m (median %.3g), rotation %.3g ± "
      "%.3g deg (median %.3g); %zu off by more than %g m or %g deg",
      what.c_str(), e.matched, e.unmatched, e.trans_mean, e.trans_std, e.trans_median,
      e.rot_mean_deg, e.rot_std_deg, e.rot_median_deg, e.off, slam::kRelationOffMetres,
      slam::kRelationOffDegrees);
}

// The map's cells, estimated from the odometry before SLAM runs, against --max-memory: a log
// whose odometry wanders kilometres (or jumps there in one step) would otherwise have the
// engine grow its grids until std::bad_alloc or the out-of-memory kill. The grid engine's map is
// the square its setup allocates (15 bytes a cell in either arithmetic, 1 more for the copy the
// run returns); the submaps engine's, the odometry's bounding box in the first pose's frame
// grown by the range and the ISM's spread (the final map grows by copying, so twice its cells,
// and the largest submap is taken as large as the map: 3 grid cells of 1 or 8 bytes, 1 byte
// for the map the run returns, and the loop search's cache of max-pooled submaps, each as large
// as the map, up to its bound: slam::pyramid_cache_bytes). Both then write the map: probabilities
// twice (8 bytes each), the PGM and the image with its figure (7 bytes). What SLAM corrects of the
// odometry is left out: the estimate is of the size the odometry implies, not a bound.
void require_memory_for(const core::Log& log, const SlamJobOptions& o) {
  constexpr double kOutputBytes = 8.0 + 8.0 + 7.0;
  const auto metres = [](double v) { return io::printed("%.4g", v); };
  double cells = 0.0, bytes_per_cell = 0.0, cell = 0.0;
  std::string extent;
  if (o.engine == SlamEngine::grid) {
    const double reach = slam::odometry_reach(log.scans);
    slam::SlamSetup setup;
    try {
      setup = slam::make_slam_setup(o.grid_config, log.scans.front(), reach);
    } catch (const std::invalid_argument& e) {
      // The configuration was checked: what is left is the map's size.
      bad_option("--cell", "a map of " + metres(o.grid_config.cell) +
                               " m cells around the first pose of " + o.log.string() +
                               ", whose odometry reaches " + metres(reach) +
                               " m from it: " + e.what());
    }
    cell = o.grid_config.cell;
    cells = static_cast<double>(setup.map_geometry.width) * setup.map_geometry.height;
    bytes_per_cell = 15.0 + 1.0 + kOutputBytes;
    extent = "the square around the first pose that holds its odometry (reaching " + metres(reach) +
             " m) and the range";
  } else {
    const slam::SubmapSlamConfig& c = o.submap_config;
    const core::Pose2 first = log.scans.front().robot;
    double x_lo = 0.0, x_hi = 0.0, y_lo = 0.0, y_hi = 0.0;
    for (const core::Scan& s : log.scans) {
      const core::Pose2 p = core::relative(first, s.robot);
      x_lo = std::min(x_lo, p.x), x_hi = std::max(x_hi, p.x);
      y_lo = std::min(y_lo, p.y), y_hi = std::max(y_hi, p.y);
    }
    cell = c.cell;
    const double margin = c.sensor.max_range + 8.0 * c.sensor.sigma + 68.0 * cell;
    cells = std::ceil((x_hi - x_lo + 2.0 * margin) / cell) *
            std::ceil((y_hi - y_lo + 2.0 * margin) / cell);
    const double cell_bytes = o.arithmetic == core::Arithmetic::integer ? 1.0 : 8.0;
    bytes_per_cell = 3.0 * cell_bytes + 1.0 + kOutputBytes +
                     slam::pyramid_cache_bytes(c, o.arithmetic, cells) / cells;
    extent =
        "the odometry's " + metres(x_hi - x_lo) + " x " + metres(y_hi - y_lo) + " m and the range";
  }
  require_memory(cells * bytes_per_cell, o.max_memory_bytes, "--cell",
                 "a map of " + io::printed("%.3g", cells) + " cells of " + metres(cell) +
                     " m over " + extent + " in " + o.log.string());
}

SlamJobResult run_slam_job(const SlamJobOptions& o) {
  if (o.engine == SlamEngine::grid)
    check_slam_options(o.grid_config);
  else
    check_submap_slam_options(o.submap_config);
  LogInput input = read_log_input(o.log);
  const core::Log& log = input.log;
  std::optional<core::Log> reference;
  if (o.reference) reference = io::read_log(*o.reference);
  try {
    slam::check_slam_log(log);
    if (o.engine == SlamEngine::grid) slam::check_one_sensor_geometry(log);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(o.log, 0, "scans", e.what());
  }
  require_memory_for(log, o);
  if (reference && reference->scans.empty())
    throw io::InputError(*o.reference, 0, "scans", "the reference log has no scans");

  SlamJobResult r;
  r.engine = o.engine;
  // The relations are read and scored on the raw odometry before SLAM runs: the SLAM trajectory
  // has the same times (one pose a scan), so a file for another log is refused at once.
  RelationScoring scoring;
  std::vector<slam::RelationResult> slam_results;
  if (o.relations) {
    scoring = read_relations_for(*o.relations, o.log, log);
    r.odometry_relations = slam::summarize_relations(scoring.odometry);
  }
  io::OutputFolder out = open_output_folder(o.out);
  const auto start = std::chrono::steady_clock::now();
  {
    TerminalProgress progress(o.arithmetic == core::Arithmetic::integer ? "SLAM (integer)"
                                                                        : "SLAM (double)");
    core::Progress report;
    if (o.progress) report = std::ref(progress);
    if (o.engine == SlamEngine::grid) {
      r.run = slam::run_grid_slam(log, o.grid_config, o.arithmetic, report);
    } else {
      slam::SubmapSlamStats stats;
      r.run = slam::run_submap_slam(log, o.submap_config, o.arithmetic, &stats, report);
      r.submap_stats = stats;
    }
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
  if (o.relations) {
    slam_results = slam::relation_errors(by_time(r.run.trajectory), scoring.relations);
    r.relations = slam::summarize_relations(slam_results);
  }

  r.metrics = {{"log", o.log.string()},
               {"engine", engine_name(o.engine)},
               {"arith", o.arithmetic == core::Arithmetic::integer ? "int" : "float"},
               {"scans", r.run.scans},
               {"readings", r.run.readings},
               {"unusable_readings", r.run.unusable_readings},
               {"skipped_records", skipped_records_json(input.skipped)},
               {"reordered_scans", log.reordered_scans},
               {"seconds", r.seconds},
               {"log_seconds", r.log_seconds},
               {"real_time_factor", r.seconds > 0.0 ? r.log_seconds / r.seconds : 0.0}};
  if (r.submap_stats) {
    const slam::SubmapSlamStats& s = *r.submap_stats;
    r.metrics.update({{"threads", core::threads_or_every_core(o.submap_config.threads)},
                      {"nodes", s.nodes},
                      {"submaps", s.submaps},
                      {"wide_searches", s.wide_searches},
                      {"handovers", s.handovers},
                      {"unmatched_scans", s.unmatched_scans},
                      {"loop_searches", s.loop_searches},
                      {"loop_closures", s.loop_closures},
                      {"rejected_closures", s.rejected_closures},
                      {"switched_off_closures", s.switched_off_closures},
                      {"optimizations", s.optimizations},
                      {"peak_pyramid_bytes", s.peak_pyramid_bytes},
                      {"settings", submap_settings_json(o.submap_config, r.run.codec)}});
  } else {
    const slam::GridSlamConfig& c = o.grid_config;
    r.metrics.update({{"skipped_scans", r.run.skipped_scans},
                      {"localizations", r.run.localizations},
                      {"mappings", r.run.mappings},
                      {"e_sigma_m", r.run.mean_sigma()},
                      {"settings",
                       {{"res", c.cell},
                        {"lambda", c.schedule.lambda},
                        {"xi", c.schedule.xi},
                        {"beams", c.beam.beams},
                        {"headings", c.headings},
                        {"window_cells", c.window.cells},
                        {"window_headings", c.window.headings},
                        {"sigma", c.sensor.sigma},
                        {"max_range", c.sensor.max_range},
                        {"eps", r.run.codec.eps()}}}});
  }
  if (r.ate) {
    r.metrics["reference"] = o.reference->string();
    r.metrics["ate"] = error_json(*r.ate);
    r.metrics["odometry_ate"] = error_json(*r.odometry_ate);
  }
  if (o.relations)
    add_relation_metrics(r.metrics, *o.relations, *r.relations, *r.odometry_relations, slam_results,
                         log.scans.front().t);

  write_trajectory(out.file("trajectory.txt"), r.run.trajectory, "the SLAM estimate of each scan");
  if (o.relations) write_relation_errors(out.file("relations.csv"), slam_results, scoring.odometry);
  const core::ProbabilityGrid map = slam::slam_map_probabilities(r.run);
  io::write_ros_map(out.file("map.yaml"), io::RosMap{map});
  io::RgbImage image = io::render_probability_grid(map);
  io::draw_polyline_world(image, map.geometry, positions(slam::scan_poses(log)), {150, 150, 150});
  if (reference)
    io::draw_polyline_world(image, map.geometry, positions(slam::scan_poses(*reference)),
                            {30, 160, 30});
  io::draw_polyline_world(image, map.geometry, positions(r.run.trajectory), {220, 30, 30});
  std::vector<std::string> caption = {"Lines: red the SLAM trajectory, grey the raw odometry" +
                                          std::string(reference ? ", green the reference" : "") +
                                          ".",
                                      map_scale_caption(map.geometry, "the log's")};
  if (r.relations) {
    char line[160];
    std::snprintf(line, sizeof line,
                  "Relation error %.3f +- %.3f m, %.2f deg (raw odometry %.3f m, %.2f deg).",
                  r.relations->trans_mean, r.relations->trans_std, r.relations->rot_mean_deg,
                  r.odometry_relations->trans_mean, r.odometry_relations->rot_mean_deg);
    caption.emplace_back(line);
  }
  const std::string title =
      "SLAM map of " + o.log.filename().string() + " (" + engine_name(o.engine) + " engine, " +
      (o.arithmetic == core::Arithmetic::integer ? "integer" : "double") + ")";
  io::write_png(out.file("map.png"),
                figures::compose_figure(title, {{{"occupancy", std::move(image)}}},
                                        io::ProbabilityScale::grey, caption));
  r.metrics["peak_memory_bytes"] = peak_memory_bytes();  // all but metrics.json done
  io::write_file_atomically(out.file("metrics.json"), r.metrics.dump(2) + "\n");
  out.commit();
  if (o.tum) io::write_tum_trajectory(*o.tum, r.run.trajectory);
  return r;
}

}  // namespace intgrid::cli
