// `intgrid slam`: the event-driven integer grid SLAM on a log.
#include <cstdio>
#include <memory>
#include <vector>

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "cli/slam_job.hpp"

namespace intgrid::cli {

const FieldFlags& slam_flags() {
  static const FieldFlags flags = {{"cell", "--cell"},
                                   {"headings", "--headings"},
                                   {"schedule.lambda", "--lambda"},
                                   {"schedule.xi", "--xi"},
                                   {"beam.sigma", "--sigma"},
                                   {"beam.likelihood_floor", "--floor"},
                                   {"beam.beams", "--beams"},
                                   {"beam.tempering", "--tempering"},
                                   {"beam.max_range", "--max-range"},
                                   {"motion", "--motion-noise"},
                                   {"window.cells", "--window-cells"},
                                   {"window.headings", "--window-headings"},
                                   {"window.pose_cutoff", "--pose-cutoff"},
                                   {"window.pose_prune", "--pose-prune"},
                                   {"map.empty_divisor", "--empty-divisor"}};
  return flags;
}

void check_slam_options(const slam::SlamConfig& c) {
  naming_flags(slam_flags(), [&] { slam::check_slam_config(c); });
}

void add_slam_options(CLI::App& cmd, slam::SlamConfig& c) {
  cmd.add_option("--cell,--res", c.cell, "map cell and pose-grid step (m, whole millimetres)")
      ->check(positive())
      ->capture_default_str();
  cmd.add_option("--lambda", c.schedule.lambda, "localize every lambda-th scan")
      ->transform(whole_at_least(1))
      ->capture_default_str();
  cmd.add_option("--xi", c.schedule.xi, "map every xi-th scan")
      ->transform(whole_at_least(1))
      ->capture_default_str();
  cmd.add_option("--beams", c.beam.beams, "readings per localization, spread over the scan")
      ->transform(whole_range(1, 1'000'000))
      ->capture_default_str();
  cmd.add_option("--tempering", c.beam.tempering,
                 "localization uses the beams' joint likelihood to the power 1 / tempering")
      ->transform(whole_range(1, 1000))
      ->capture_default_str();
  cmd.add_option("--empty-divisor", c.map.empty_divisor,
                 "a reading's empty evidence is divided by this before it is fused")
      ->transform(whole_range(1, 127))
      ->capture_default_str();
  cmd.add_option("--headings", c.headings, "heading bins per turn (a power of two)")
      ->transform(whole_range(8, 65536))
      ->capture_default_str();
  cmd.add_option("--window-cells", c.window.cells, "pose-grid cells per side in x and y (odd)")
      ->transform(whole_range(1, 255))
      ->capture_default_str();
  cmd.add_option("--window-headings", c.window.headings, "pose-grid heading bins (odd)")
      ->transform(whole_range(1, 255))
      ->capture_default_str();
  cmd.add_option("--sigma", c.beam.sigma, "range noise of the beam model (m)")
      ->check(positive())
      ->capture_default_str();
  cmd.add_option("--max-range", c.beam.max_range, "readings at or past this are not used (m)")
      ->check(positive())
      ->capture_default_str();
  cmd.add_option("--floor", c.beam.likelihood_floor,
                 "likelihood of a reading the map cannot explain")
      ->check(real_range(0.0, 1.0, true, true))
      ->capture_default_str();
  cmd.add_option_function<std::vector<double>>(
         "--motion-noise",
         [&c](const std::vector<double>& v) {
           c.motion.xy0 = v[0];
           c.motion.xy_per_m = v[1];
           c.motion.xy_per_rad = v[2];
           c.motion.theta0 = v[3];
           c.motion.theta_per_m = v[4];
           c.motion.theta_per_rad = v[5];
         },
         "motion model spread: XY0 (m), XY_PER_M, XY_PER_RAD (m), THETA0 (rad), THETA_PER_M "
         "(rad), THETA_PER_RAD")
      ->expected(6)
      ->delimiter(',')
      ->check(non_negative())
      ->type_name("X,X,X,X,X,X");
  cmd.add_option("--pose-cutoff", c.window.pose_cutoff,
                 "mapping skips poses less probable than this")
      ->check(real_range(0.0, 1.0, true, false))
      ->capture_default_str();
  cmd.add_option("--pose-prune", c.window.pose_prune,
                 "a localization drops the poses it leaves less probable than this")
      ->check(real_range(0.0, 1.0, false, true))
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
