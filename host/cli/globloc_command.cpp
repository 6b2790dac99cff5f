// `intgrid globloc`: global localization of a log's scans in a known map, each from no prior.
#include <map>
#include <memory>
#include <numbers>
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
  static const FieldFlags flags = {
      {"pose_res", "--pose-cell"},      {"headings", "--headings"},
      {"sensor.sigma", "--sigma"},      {"sensor.max_range", "--max-range"},
      {"seps_levels", "--levels"},      {"veto_levels", "--veto-levels"},
      {"memory_limit", "--max-memory"}, {"refine_levels", "--refine-levels"},
      {"max_scans", "--track"},         {"step_position", "--track-step"},
      {"step_heading", "--track-step"}};
  return flags;
}

const FieldFlags& pose_search_flags() {
  static const FieldFlags flags = {{"hypotheses", "--hypotheses"},
                                   {"verified", "--verified"},
                                   {"ambiguity_levels", "--ambiguity-levels"},
                                   {"threads", "--threads"}};
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
  cmd.add_option("--sigma", c.sensor.sigma, "range noise of the readings (m)")
      ->check(positive())
      ->capture_default_str();
  cmd.add_option("--max-range", c.sensor.max_range, "readings at or past this are not used (m)")
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
  cmd.add_option("--refine-levels", c.refine_levels,
                 "pog: levels of the hypotheses' refinement on the map's own cells, each halving "
                 "the position and heading steps (0: verify on the pose lattice)")
      ->transform(whole_range(0, 8))
      ->capture_default_str();
  cmd.add_option("--grazing-hits", c.grazing_hits,
                 "pog: the refinement reads a reading whose ray enters a wall before its range, "
                 "and which ends within a cell of it, as a hit at its range (a wall met at a "
                 "grazing angle)")
      ->capture_default_str();
  add_max_memory_option(cmd, c.memory_limit);
}

void add_globloc_command(CLI::App& app) {
  auto o = std::make_shared<GlobLocJobOptions>();
  CLI::App* cmd = app.add_subcommand(
      "globloc",
      "global localization: each scan of a log on its own in a known map, from no prior");
  cmd->footer(
      "Thesis chapter 4. Writes DIR/poses.txt (t x y theta score ambiguous, then x y theta score "
      "of each further hypothesis), pose_grid.png (the first "
      "scan's pose grid, max over headings, estimate marked) and metrics.json (with a reference: "
      "the share of scans within --tolerance of the reference pose, and the misses).");
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
  cmd->add_option("--beams", o->sequence.beams,
                  "readings a scan that score every pose cell, spread evenly over it (0: all)")
      ->transform(whole_range(0, 100'000))
      ->capture_default_str();
  cmd->add_option("--verify-beams", o->sequence.verify_beams,
                  "pog: readings a scan that rescore the best hypotheses (0: all, the whole scan)")
      ->transform(whole_range(0, 100'000))
      ->capture_default_str();
  cmd->add_option("--hypotheses", o->search.hypotheses,
                  "pog: the K best hypotheses, written after the estimate in poses.txt")
      ->transform(whole_range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--verified", o->search.verified,
                  "pog: the best hypotheses of the screening that the verification rescores")
      ->transform(whole_range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--ambiguity-levels", o->search.ambiguity_levels,
                  "pog: a scan is ambiguous when a second hypothesis (1 m or 30 degrees away) "
                  "scores within this many S_eps levels a verification reading of the best")
      ->check(non_negative())
      ->capture_default_str();
  o->search.threads = 0;
  cmd->add_option("--threads", o->search.threads,
                  "pog: threads scoring one scan's pose grid (0: every core); the same result "
                  "for any count")
      ->transform(whole_range(0, 256))
      ->capture_default_str();
  cmd->add_option("--track", o->track,
                  "pog: localize from a sequence: from each selected scan, fuse up to N scans "
                  "with odometry until the answer is unambiguous (0: each scan on its own)")
      ->transform(whole_range(0, 1000))
      ->capture_default_str();
  cmd->add_option_function<std::vector<double>>(
         "--track-step",
         [o](const std::vector<double>& v) {
           o->sequence.step_position = v[0];
           o->sequence.step_heading = v[1] * std::numbers::pi / 180.0;
         },
         "with --track: fuse a scan once odometry moved the sensor METRES or turned it DEGREES "
         "since the scan fused before")
      ->expected(2)
      ->type_name("METRES DEGREES")
      ->check(non_negative())
      ->default_str("0.5 15");
  add_global_method_option(*cmd, o->method);
  add_global_loc_options(*cmd, o->config);
  cmd->add_option("--reference", o->reference,
                  "reference log: the share of scans within the tolerance of its pose at the "
                  "same time, in metrics.json");
  cmd->add_option("--reference-trajectory", o->reference_trajectory,
                  "reference poses as t x y theta lines (intgrid slam's trajectory.txt), instead "
                  "of --reference");
  cmd->add_option_function<std::vector<double>>(
         "--tolerance",
         [o](const std::vector<double>& v) {
           o->position_tolerance = v[0];
           o->heading_tolerance = v[1] * std::numbers::pi / 180.0;
         },
         "a scan is found within METRES and DEGREES of its reference pose")
      ->expected(2)
      ->type_name("METRES DEGREES")
      ->check(positive())
      ->default_str("0.5 15");
  cmd->callback([o] {
    const GlobLocJobResult r = run_globloc_job(*o);
    print_json(r.metrics);
  });
}

}  // namespace intgrid::cli
