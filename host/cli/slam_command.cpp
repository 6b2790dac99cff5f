// `intgrid slam`: the event-driven integer grid SLAM on a log.
#include <cstdio>
#include <memory>
#include <vector>

#include "cli/commands.hpp"
#include "cli/slam_job.hpp"

namespace intgrid::cli {

void add_slam_options(CLI::App& cmd, slam::SlamConfig& c) {
  cmd.add_option("--res", c.cell, "map cell and pose-grid step (m, whole millimetres)")
      ->capture_default_str();
  cmd.add_option("--lambda", c.lambda, "localize every lambda-th scan")->capture_default_str();
  cmd.add_option("--xi", c.xi, "map every xi-th scan")->capture_default_str();
  cmd.add_option("--beams", c.beams, "readings per localization, spread over the scan")
      ->capture_default_str();
  cmd.add_option("--tempering", c.tempering,
                 "localization uses the beams' joint likelihood to the power 1 / tempering")
      ->capture_default_str();
  cmd.add_option("--empty-divisor", c.empty_divisor,
                 "a reading's empty evidence is divided by this before it is fused")
      ->capture_default_str();
  cmd.add_option("--headings", c.headings, "heading bins per turn (a power of two)")
      ->capture_default_str();
  cmd.add_option("--window-cells", c.window_cells, "pose-grid cells per side in x and y (odd)")
      ->capture_default_str();
  cmd.add_option("--window-headings", c.window_headings, "pose-grid heading bins (odd)")
      ->capture_default_str();
  cmd.add_option("--sigma", c.sigma, "range noise of the beam model (m)")->capture_default_str();
  cmd.add_option("--max-range", c.max_range, "readings at or past this are not used (m)")
      ->capture_default_str();
  cmd.add_option("--floor", c.likelihood_floor, "likelihood of a reading the map cannot explain")
      ->capture_default_str();
  cmd.add_option_function<std::vector<double>>(
         "--motion-noise",
         [&c](const std::vector<double>& v) {
           c.motion_xy0 = v[0];
           c.motion_xy_per_m = v[1];
           c.motion_xy_per_rad = v[2];
           c.motion_theta0 = v[3];
           c.motion_theta_per_m = v[4];
           c.motion_theta_per_rad = v[5];
         },
         "motion model spread: XY0 (m), XY_PER_M, XY_PER_RAD (m), THETA0 (rad), THETA_PER_M "
         "(rad), THETA_PER_RAD")
      ->expected(6)
      ->delimiter(',');
  cmd.add_option("--pose-cutoff", c.pose_cutoff, "mapping skips poses less probable than this")
      ->capture_default_str();
  cmd.add_option("--pose-prune", c.pose_prune,
                 "a localization drops the poses it leaves less probable than this")
      ->capture_default_str();
}

void add_slam_command(CLI::App& app) {
  auto o = std::make_shared<SlamJobOptions>();
  CLI::App* cmd = app.add_subcommand("slam", "event-driven grid SLAM on a log (thesis chapter 3)");
  cmd->add_option("--log", o->log, "log file (project format or CARMEN)")->required();
  cmd->add_option("--out", o->out,
                  "output folder: trajectory.txt, map.yaml, map.pgm, map.png, metrics.json")
      ->required();
  cmd->add_option("--reference", o->reference,
                  "reference log: adds the trajectory error (ATE) to metrics.json");
  add_arithmetic_option(*cmd, o->arithmetic, "int: U_gamma and S_eps indices; float: double")
      ->default_str("int");
  add_slam_options(*cmd, o->config);
  cmd->callback([o] {
    const SlamJobResult r = run_slam_job(*o);
    print_json(r.metrics);
  });
}

}  // namespace intgrid::cli
