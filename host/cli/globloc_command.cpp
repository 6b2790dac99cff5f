// `intgrid globloc`: global localization of a log's scans in a known map, each from no prior.
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli/commands.hpp"
#include "cli/globloc_job.hpp"

namespace intgrid::cli {

CLI::Option* add_global_method_option(CLI::App& cmd, localization::GlobalMethod& method) {
  std::vector<std::pair<std::string, localization::GlobalMethod>> names;
  for (const localization::GlobalMethod m : kGlobalMethods)
    names.emplace_back(global_method_name(m), m);
  return add_choice_option(cmd, "--method", method, names,
                           "pog: pose occupancy grid (S_eps index sums); markov: Gaussian beam "
                           "model; markov-mixture: hit + short + random + max; likelihood-field")
      ->default_str("pog");
}

const FieldFlags& global_loc_flags() {
  static const FieldFlags flags = {{"pose_res", "--pose-cell"}, {"headings", "--headings"},
                                   {"sigma", "--sigma"},        {"max_range", "--max-range"},
                                   {"seps_levels", "--levels"}, {"veto_levels", "--veto-levels"}};
  return flags;
}

void check_global_loc_options(const localization::GlobalLocConfig& c) {
  if (c.veto_levels > c.seps_levels)
    bad_option("--veto-levels", std::to_string(c.veto_levels) + " exceeds --levels " +
                                    std::to_string(c.seps_levels));
  naming_flags(global_loc_flags(), [&] { localization::check_global_loc_config(c); });
}

void add_global_loc_options(CLI::App& cmd, localization::GlobalLocConfig& c) {
  cmd.add_option("--pose-cell,--pose-res", c.pose_res,
                 "pose-grid step (m), not finer than the map's cells")
      ->check(positive())
      ->capture_default_str();
  cmd.add_option("--headings", c.headings, "heading bins of the pose grid")
      ->transform(whole_range(4, 4096))
      ->capture_default_str();
  cmd.add_option("--sigma", c.sigma, "range noise of the readings (m)")
      ->check(positive())
      ->capture_default_str();
  cmd.add_option("--max-range", c.max_range, "readings at or past this are not used (m)")
      ->check(positive())
      ->capture_default_str();
  cmd.add_option("--levels", c.seps_levels, "each reading's strongest claim, in S_eps steps")
      ->transform(whole_range(1, core::max_index_for_bits(c.seps_bits)))
      ->capture_default_str();
  cmd.add_option("--veto-levels", c.veto_levels,
                 "bound of a reading's negative claims, at most --levels (--levels: rule 2's own "
                 "bound)")
      ->transform(whole_range(0, core::max_index_for_bits(c.seps_bits)))
      ->capture_default_str();
}

void add_globloc_command(CLI::App& app) {
  auto o = std::make_shared<GlobLocJobOptions>();
  CLI::App* cmd = app.add_subcommand(
      "globloc",
      "global localization: each scan of a log on its own in a known map, from no prior");
  cmd->footer(
      "Thesis chapter 4. Writes DIR/poses.txt (t x y theta score), pose_grid.png (the first "
      "scan's pose grid, max over headings, estimate marked) and metrics.json (with --reference: "
      "the share of scans within 0.5 m and 15 degrees of the reference pose).");
  cmd->add_option("--map", o->map, "the known map (ROS map_server YAML)")->required();
  cmd->add_option("--log", o->log, "log file (project format or CARMEN)")->required();
  cmd->add_option("--out", o->out, "output folder: poses.txt, pose_grid.png, metrics.json")
      ->required();
  cmd->add_option("--scans", o->scans,
                  "FIRST:LAST, the scans to localize (0-based, inclusive; default all)")
      ->type_name("FIRST:LAST");
  cmd->add_option("--every", o->every, "localize every N-th of the selected scans")
      ->transform(whole_range(1, 1'000'000))
      ->capture_default_str();
  cmd->add_option("--beams", o->beams, "readings a scan, spread evenly over it (0: all)")
      ->transform(whole_range(0, 100'000))
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
