// `intgrid localize`: a log's scans localized one after another in a known map.
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "cli/commands.hpp"
#include "cli/localize_job.hpp"
#include "intgrid/core/parallel.hpp"

namespace intgrid::cli {

void add_localize_command(CLI::App& app) {
  auto o = std::make_shared<LocalizeJobOptions>();
  CLI::App* cmd = app.add_subcommand(
      "localize", "localization in a known map: a log's scans found, tracked and found again");
  cmd->footer(
      "The robot found by global localization (the pose grid fusing the scans as they come, "
      "until unambiguous), or from --initial; then tracked by the submaps SLAM's localization "
      "event (the odometry's prediction matched by S_eps index sums) against the map; declared "
      "lost when 3 matched scans in a row fit the map (hits within a cell of an occupied cell) "
      "under a quarter of the recent fitting scans' median, and found again. Global "
      "localization also checks the tracked pose a step after a fix and every 10 m: an answer "
      "elsewhere is tracked beside it for 10 scans, and the one fitting the map better goes on. "
      "No mapping, no loop closure. Writes DIR/trajectory.txt (t x y theta of the tracked "
      "scans, the map's frame), fit.csv (each scan's state: locating, tracking, lost, "
      "recovering; verified, refixed, evidence, fit, scans fused), map.png (the path on the map) "
      "and metrics.json (with --reference: the ATE, no alignment; with --relations: their "
      "errors, and relations.csv).");
  cmd->add_option("--map", o->map, "the known map (ROS map_server YAML); its cell is the grid's")
      ->required();
  cmd->add_option("--log", o->log, "log file (project format or CARMEN)")->required();
  cmd->add_option("--out", o->out, "output folder: trajectory.txt, fit.csv, map.png, metrics.json")
      ->required();
  cmd->add_option_function<std::vector<double>>(
         "--initial",
         [o](const std::vector<double>& v) {
           o->initial = core::Pose2{v[0], v[1], v[2] * std::numbers::pi / 180.0};
         },
         "the robot's pose in the map's frame at the first scan (default: found by global "
         "localization)")
      ->expected(3)
      ->type_name("X Y DEGREES")
      ->check(CLI::TypeValidator<double>());
  cmd->add_option("--reference", o->reference,
                  "reference log in the map's frame: adds the trajectory error (ATE) to "
                  "metrics.json");
  cmd->add_option("--relations", o->relations,
                  "benchmark relations of the log: adds their errors to metrics.json (a "
                  "relation with an end at a scan not tracked counts as unmatched) and writes "
                  "DIR/relations.csv");
  cmd->add_option("--tum", o->tum, "also write the tracked scans' poses here in the TUM format");
  add_arithmetic_option(*cmd, o->arithmetic, "int: S_eps index sums; float: log-odds in double")
      ->default_str("int");
  o->config.tracking.threads = 0;
  cmd->add_option("--threads", o->config.tracking.threads,
                  "threads of each scan's match and of the global localization (0: every core); "
                  "the same result for any count")
      ->transform(whole_range(0, 256))
      ->capture_default_str();
  cmd->callback([o] {
    if (o->initial && (!std::isfinite(o->initial->x) || !std::isfinite(o->initial->y) ||
                       !std::isfinite(o->initial->theta)))
      bad_option("--initial", "must be three finite numbers");
    o->config.search.threads = core::threads_or_every_core(o->config.tracking.threads);
    const LocalizeJobResult r = run_localize_job(*o);
    print_json(r.metrics);
    char ate[64] = "";
    if (r.ate) std::snprintf(ate, sizeof ate, ", ATE %.3f m", r.ate->rmse);
    std::fprintf(stderr, "localize: %zu scans, %.2f s for %.1f s of data (%.0fx real time)%s\n",
                 r.steps.size(), r.seconds, r.metrics["log_seconds"].get<double>(),
                 r.metrics["real_time_factor"].get<double>(), ate);
  });
}

}  // namespace intgrid::cli
