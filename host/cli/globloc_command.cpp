// `intgrid globloc`: global localization of a log's scans in a known map, each from no prior.
#include <map>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/globloc_job.hpp"

namespace intgrid::cli {

// The command line's names of the methods: global_method_name's.
static std::map<std::string, localization::GlobalMethod> method_names() {
  std::map<std::string, localization::GlobalMethod> names;
  for (const localization::GlobalMethod m : kGlobalMethods) names.emplace(global_method_name(m), m);
  return names;
}

CLI::Option* add_global_method_option(CLI::App& cmd, localization::GlobalMethod& method) {
  return cmd
      .add_option("--method", method,
                  "pog: pose occupancy grid (S_eps index sums); markov: Gaussian beam model; "
                  "markov-mixture: hit + short + random + max; likelihood-field")
      ->transform(CLI::CheckedTransformer(method_names(), CLI::ignore_case))
      ->default_str("pog");
}

void add_global_loc_options(CLI::App& cmd, localization::GlobalLocConfig& c) {
  cmd.add_option("--pose-res", c.pose_res, "pose-grid step (m), not finer than the map's cells")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd.add_option("--headings", c.headings, "heading bins of the pose grid")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd.add_option("--sigma", c.sigma, "range noise of the readings (m)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd.add_option("--max-range", c.max_range, "readings at or past this are not used (m)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd.add_option("--levels", c.seps_levels, "each reading's strongest claim, in S_eps steps")
      ->check(CLI::Range(1, 127))
      ->capture_default_str();
  cmd.add_option("--veto-levels", c.veto_levels,
                 "bound of a reading's negative claims (--levels: rule 2's own bound)")
      ->check(CLI::Range(0, 127))
      ->capture_default_str();
}

void add_globloc_command(CLI::App& app) {
  auto o = std::make_shared<GlobLocJobOptions>();
  CLI::App* cmd = app.add_subcommand(
      "globloc",
      "global localization (thesis chapter 4): each scan of a log on its own in a known map, from "
      "no prior");
  cmd->add_option("--map", o->map, "the known map (ROS map_server YAML)")->required();
  cmd->add_option("--log", o->log, "log file (project format or CARMEN)")->required();
  cmd->add_option("--out", o->out, "output folder: poses.txt, pose_grid.png, metrics.json")
      ->required();
  cmd->add_option("--scans", o->scans,
                  "FIRST:LAST, the scans to localize (0-based, inclusive; default all)");
  cmd->add_option("--every", o->every, "localize every N-th of the selected scans")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000000}))
      ->capture_default_str();
  cmd->add_option("--beams", o->beams, "readings a scan, spread evenly over it (0: all)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  add_global_method_option(*cmd, o->method);
  add_global_loc_options(*cmd, o->config);
  cmd->add_option("--reference", o->reference,
                  "reference log: the share of scans within 0.5 m and 15 degrees of its pose at "
                  "the same time, in metrics.json");
  cmd->callback([o] {
    const GlobLocJobResult r = run_globloc_job(*o);
    print_json(r.metrics);
  });
}

}  // namespace intgrid::cli
