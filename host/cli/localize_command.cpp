// `intgrid localize`: a log's scans tracked one after another in a known map, from a given pose.
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "cli/commands.hpp"
#include "cli/localize_job.hpp"

namespace intgrid::cli {

void add_localize_command(CLI::App& app) {
  auto o = std::make_shared<LocalizeJobOptions>();
  CLI::App* cmd = app.add_subcommand(
      "localize", "localization in a known map: a log's scans tracked one after another");
  cmd->footer(
      "The submaps SLAM's localization event (the odometry's prediction matched by S_eps index "
      "sums) against the map, from --initial at the first scan; no mapping, no loop closure. "
      "Writes DIR/trajectory.txt (t x y theta, the map's frame), fit.csv (each scan's evidence, "
      "matched, wide search), map.png (the path on the map) and metrics.json (with --reference: "
      "the ATE, no alignment). Not yet: a start with no pose, recovery when lost (issue 36).");
  cmd->add_option("--map", o->map, "the known map (ROS map_server YAML); its cell is the grid's")
      ->required();
  cmd->add_option("--log", o->log, "log file (project format or CARMEN)")->required();
  cmd->add_option("--out", o->out, "output folder: trajectory.txt, fit.csv, map.png, metrics.json")
      ->required();
  cmd->add_option_function<std::vector<double>>(
         "--initial",
         [o](const std::vector<double>& v) {
           o->initial = {v[0], v[1], v[2] * std::numbers::pi / 180.0};
         },
         "the robot's pose in the map's frame at the first scan")
      ->expected(3)
      ->type_name("X Y DEGREES")
      ->check(CLI::TypeValidator<double>())
      ->required();
  cmd->add_option("--reference", o->reference,
                  "reference log in the map's frame: adds the trajectory error (ATE) to "
                  "metrics.json");
  add_arithmetic_option(*cmd, o->arithmetic, "int: S_eps index sums; float: log-odds in double")
      ->default_str("int");
  o->config.threads = 0;
  cmd->add_option("--threads", o->config.threads,
                  "threads of each scan's match (0: every core); the same result for any count")
      ->transform(whole_range(0, 256))
      ->capture_default_str();
  cmd->callback([o] {
    if (!std::isfinite(o->initial.x) || !std::isfinite(o->initial.y) ||
        !std::isfinite(o->initial.theta))
      bad_option("--initial", "must be three finite numbers");
    const LocalizeJobResult r = run_localize_job(*o);
    print_json(r.metrics);
    char ate[64] = "";
    if (r.ate) std::snprintf(ate, sizeof ate, ", ATE %.3f m", r.ate->rmse);
    std::fprintf(stderr, "localize: %zu scans, %.2f s for %.1f s of data (%.0fx real time)%s\n",
                 r.fixes.size(), r.seconds, r.metrics["log_seconds"].get<double>(),
                 r.metrics["real_time_factor"].get<double>(), ate);
  });
}

}  // namespace intgrid::cli
