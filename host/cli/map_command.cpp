#include "cli/commands.hpp"

#include <cstdio>
#include <memory>
#include "cli/log_input.hpp"
#include "cli/map_job.hpp"

namespace intgrid::cli {

void add_map_command(CLI::App& app) {
  auto o = std::make_shared<MapJobOptions>();
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("map", "map a log with its own poses into an occupancy grid");
  cmd->footer(
      "Writes DIR/map.yaml + map.pgm (ROS map_server) and map.png with the sensor's path in "
      "red. Readings that are 0, NaN, infinite, negative or at/over the scan's maximum range are "
      "not inserted, and are counted.");
  cmd->add_option("--log", o->log, "log file (project format or CARMEN)")->required();
  cmd->add_option("--out", o->out, "output folder: map.yaml, map.pgm, map.png")->required();
  cmd->add_option("--cell,--res", o->resolution, "cell size (m)")->required()->check(positive());
  add_arithmetic_option(*cmd, o->arithmetic, "int: S_eps indices; float: double-precision Bayes")
      ->default_str("int");
  add_model_options(*cmd, *o);
  cmd->add_option("--threads", o->threads,
                  "threads inserting the log, each into its own band of the grid's rows (0: every "
                  "core); the same map for any count")
      ->transform(whole_range(0, 256))
      ->capture_default_str();
  add_max_memory_option(*cmd, o->max_memory_bytes);
  cmd->add_flag("--json", *json, "print the run's figures as JSON");
  cmd->callback([o, json] {
    const MapJobResult r = run_map_job(*o);
    const nlohmann::json j = {
        {"out", o->out.string()},
        {"arith", o->arithmetic == core::Arithmetic::integer ? "int" : "float"},
        {"seconds", r.seconds},
        {"eps", r.codec ? nlohmann::json(r.codec->eps()) : nlohmann::json()},
        {"stats", stats_json(r.stats)},
        {"skipped_records", skipped_records_json(r.skipped_records)}};
    if (*json) return print_json(j);
    std::printf("wrote %s/map.yaml, map.pgm, map.png\n", o->out.string().c_str());
    std::printf(
        "%zu scans, %zu readings inserted, %zu skipped (zero %zu, NaN/inf %zu, negative %zu, "
        ">= max range %zu), %.3f s\n",
        r.stats.scans, r.stats.inserted, r.stats.skipped(), r.stats.zero, r.stats.not_finite,
        r.stats.negative, r.stats.at_or_over_max, r.seconds);
  });
}

}  // namespace intgrid::cli
