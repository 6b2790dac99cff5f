// `intgrid simulate`: a seeded simulated run (docs/algorithms.md 8) written as a log with noisy
// odometry, the same scans with the true poses (a reference log), the world map and a picture.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/output_folder_option.hpp"
#include "intgrid/io/image_io.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/io/map_io.hpp"
#include "intgrid/io/text_io.hpp"
#include "intgrid/simulation/simulator.hpp"

namespace intgrid::cli {
namespace {

constexpr const char* kDefaultOdometryNoise = "0.01,0.002,0.01,0.002";
// The picture's longer side aims at this many pixels (1 to 8 pixels a cell).
constexpr int kPictureSidePx = 1000;

struct SimulateArgs {
  std::filesystem::path out;
  std::optional<std::filesystem::path> world;
  bool floorplan = false;
  std::optional<std::filesystem::path> trajectory;
  std::uint64_t seed = 1;
  std::optional<long long> scans;
  std::string sensor = "lidar";
  std::optional<long long> beams;
  std::optional<double> fov;
  std::optional<double> max_range;
  double noise = 0.01;
  double dropout = 0.0;
  double contamination = 0.0;
  long long obstacles = 0;
  std::optional<double> large_obstacle;
  std::string odometry_noise = kDefaultOdometryNoise;
  std::optional<double> cell;
  double speed = 0.5;
  double period = 0.2;
};

// The simulator's fields, as its checks name them -> the options that set them.
const FieldFlags& simulation_flags() {
  static const FieldFlags flags = {{"trajectory.scans", "--scans"},
                                   {"trajectory.speed", "--speed"},
                                   {"trajectory.scan_period", "--period"},
                                   {"sensor.beams", "--beams"},
                                   {"sensor.max_range", "--max-range"},
                                   {"sensor.cone_fov", "--fov"},
                                   {"noise.sigma", "--noise"},
                                   {"noise.dropout", "--dropout"},
                                   {"noise.contamination", "--contamination"},
                                   {"odometry.alpha1", "--odometry-noise"},
                                   {"odometry.alpha2", "--odometry-noise"},
                                   {"odometry.alpha3", "--odometry-noise"},
                                   {"odometry.alpha4", "--odometry-noise"},
                                   {"obstacles.count", "--obstacles"},
                                   {"obstacles.large_distance", "--large-obstacle"},
                                   {"true_poses", "--trajectory"}};
  return flags;
}

// "A1,A2,A3,A4": four finite numbers >= 0.
simulation::OdometryNoiseConfig parse_odometry_noise(const std::string& text) {
  std::vector<double> values;
  std::istringstream in(text);
  for (std::string field; std::getline(in, field, ',');) {
    char* end = nullptr;
    const double v = std::strtod(field.c_str(), &end);
    // Past 1 the odometry wanders without bound (1e300 put it 1e148 m away, where no reader
    // follows).
    if (field.empty() || end != field.c_str() + field.size() || !(v >= 0.0 && v <= 1.0))
      bad_option("--odometry-noise",
                 "must be four numbers in [0, 1] separated by commas "
                 "(A1,A2,A3,A4), got '" +
                     text + "'");
    values.push_back(v);
  }
  if (values.size() != 4 || text.back() == ',')
    bad_option("--odometry-noise",
               "must be four numbers in [0, 1] separated by commas "
               "(A1,A2,A3,A4), got '" +
                   text + "'");
  return {values[0], values[1], values[2], values[3]};
}

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

simulation::SensorConfig sensor_from(const SimulateArgs& a) {
  const bool lidar = a.sensor == "lidar";
  const long long beams = a.beams.value_or(lidar ? 361 : 16);
  const double fov = a.fov.value_or(lidar ? 180.0 : 30.0);
  if (lidar && !(fov > 0.0 && fov <= 360.0))
    bad_option("--fov", "must be in (0, 360] degrees for a lidar, got " + option_number(fov));
  if (!lidar && !(fov > 0.0 && fov < 180.0))
    bad_option("--fov", "must be in (0, 180) degrees for a cone, got " + option_number(fov));
  const double max_range = a.max_range.value_or(lidar ? 8.0 : 5.0);
  const auto n = static_cast<std::size_t>(beams);
  return lidar ? simulation::lidar_sensor(n, radians(fov), max_range)
               : simulation::cone_ring_sensor(n, radians(fov), max_range);
}

// The true poses of a reference log's scans, the first `scans` of them if given.
std::vector<core::Pose2> reference_poses(const std::filesystem::path& file,
                                         std::optional<long long> scans) {
  const core::Log log = io::read_log(file);
  if (log.scans.empty())
    throw io::InputError(file, 0, "scans", "the log holds no scan, so no pose to follow");
  std::vector<core::Pose2> poses;
  for (const core::Scan& scan : log.scans) poses.push_back(scan.robot);
  if (scans) {
    if (static_cast<std::size_t>(*scans) > poses.size())
      bad_option("--scans", std::to_string(*scans) + " exceeds the " +
                                std::to_string(poses.size()) + " scans of --trajectory " +
                                file.string());
    poses.resize(static_cast<std::size_t>(*scans));
  }
  return poses;
}

// "floorplan.door: must be at least 3 cells wide" -> "its door must be at least 3 cells wide".
std::string floorplan_problem(const std::string& what) {
  const std::string prefix = "floorplan.";
  const std::size_t colon = what.find(": ");
  if (what.rfind(prefix, 0) != 0 || colon == std::string::npos) return what;
  std::string field = what.substr(prefix.size(), colon - prefix.size());
  std::replace(field.begin(), field.end(), '_', ' ');
  return "its " + field + " " + what.substr(colon + 2);
}

void write_picture(const std::filesystem::path& file, const simulation::Simulation& sim) {
  const core::GridGeometry& g = sim.world.geometry;
  const int ppc = std::clamp(kPictureSidePx / std::max(g.width, g.height), 1, 8);
  io::RgbImage image = io::render_probability_grid(sim.world, io::ProbabilityScale::grey, ppc);
  core::GridGeometry scaled = g;
  scaled.width *= ppc;
  scaled.height *= ppc;
  scaled.resolution /= ppc;
  const io::Rgb obstacle{240, 140, 0};
  for (int iy = 0; iy < g.height; ++iy)
    for (int ix = 0; ix < g.width; ++ix)
      if (sim.sensed_world.at(ix, iy) != sim.world.at(ix, iy))
        for (int dy = 0; dy < ppc; ++dy)
          for (int dx = 0; dx < ppc; ++dx)
            image.set(ix * ppc + dx, (g.height - 1 - iy) * ppc + dy, obstacle);
  std::vector<core::Pose2> odometry, truth;
  for (const core::Scan& s : sim.log.scans) odometry.push_back(s.robot);
  for (const core::Scan& s : sim.truth.scans) truth.push_back(s.robot);
  io::draw_polyline_world(image, scaled, odometry, {70, 110, 230});
  const io::Rgb red{220, 30, 30};
  io::draw_polyline_world(image, scaled, truth, red);
  for (const core::Pose2& p : truth)
    io::draw_marker_world(image, scaled, p.x, p.y, ppc > 2 ? 1 : 0, red);
  if (!truth.empty())
    io::draw_marker_world(image, scaled, truth[0].x, truth[0].y, 3, {20, 160, 40});
  io::write_png(file, image);
}

void run_simulate(const SimulateArgs& a) {
  if (a.world && a.cell)
    bad_option("--cell", "sets the floorplan's cell size; a --world map has its own resolution");
  const double cell = a.cell.value_or(simulation::FloorplanConfig{}.cell);
  const std::uint64_t seed = a.seed;

  simulation::SimulationConfig config;
  config.sensor = sensor_from(a);
  config.noise = {a.noise, a.dropout, a.contamination};
  config.odometry = parse_odometry_noise(a.odometry_noise);
  config.obstacles.count = static_cast<std::size_t>(a.obstacles);
  config.obstacles.large_distance = a.large_obstacle;
  config.trajectory.speed = a.speed;
  config.trajectory.scan_period = a.period;
  if (a.scans) config.trajectory.scans = static_cast<std::size_t>(*a.scans);

  // The world, read or built, before anything is written.
  io::RosMap world;
  std::string world_name = "floorplan";
  if (a.world) {
    world = io::read_ros_map(*a.world);
    world_name = a.world->string();
    const bool any_free = std::any_of(world.grid.cells.begin(), world.grid.cells.end(),
                                      [&](double p) { return p < world.free_thresh; });
    if (!any_free)
      throw io::InputError(*a.world, 0, "image",
                           "the map has no free cell (P < free_thresh " +
                               io::format_number(world.free_thresh) +
                               "): nowhere for the robot to be");
    config.sensor.occupied_threshold = world.occupied_thresh;
    config.trajectory.free_threshold = world.free_thresh;
  } else {
    simulation::FloorplanConfig floorplan;
    floorplan.cell = cell;
    simulation::Floorplan plan;
    try {
      plan = simulation::make_floorplan(floorplan, seed);
    } catch (const std::invalid_argument& e) {
      bad_option("--cell", option_number(cell) +
                               " m does not suit the floorplan: " + floorplan_problem(e.what()));
    }
    world.grid = std::move(plan.grid);
    config.route = std::move(plan.corridor_loop);
  }
  if (a.trajectory) config.true_poses = reference_poses(*a.trajectory, a.scans);

  const simulation::Simulation sim = naming_flags(
      simulation_flags(), [&] { return simulation::simulate(world.grid, config, seed); });

  io::OutputFolder out = open_output_folder(a.out);
  io::write_log(out.file("sim.log"), sim.log);
  io::write_log(out.file("truth.log"), sim.truth);
  io::RosMap written = world;
  written.grid = sim.world;
  written.negate = false;
  io::write_ros_map(out.file("world.yaml"), written);
  write_picture(out.file("world.png"), sim);
  out.commit();

  std::size_t readings = 0, no_return = 0;
  for (const core::Scan& s : sim.log.scans) {
    readings += s.ranges.size();
    no_return += static_cast<std::size_t>(std::count(s.ranges.begin(), s.ranges.end(), 0.0));
  }
  const core::Pose2 &last_odometry = sim.log.scans.back().robot,
                    &last_true = sim.truth.scans.back().robot;
  print_json({{"scans", sim.log.scans.size()},
              {"seed", seed},
              {"world", world_name},
              {"sensor", a.sensor},
              {"beams", config.sensor.beams},
              {"readings", readings},
              {"no_return", no_return},
              {"obstacles", sim.obstacles.size()},
              {"odometry_final_error_m",
               std::hypot(last_odometry.x - last_true.x, last_odometry.y - last_true.y)},
              {"files",
               {{"log", (a.out / "sim.log").string()},
                {"truth", (a.out / "truth.log").string()},
                {"map", (a.out / "world.yaml").string()},
                {"map_image", (a.out / "world.pgm").string()},
                {"picture", (a.out / "world.png").string()}}}});
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto a = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "a seeded simulated run: a log, its true poses, the world map and a picture");
  cmd->footer(
      "Writes DIR/sim.log (scans with noisy odometry), DIR/truth.log (the same scans with the "
      "true poses), DIR/world.yaml + world.pgm (the map, without the unmodelled obstacles) and "
      "DIR/world.png (true path red, odometry blue, start green, unmodelled obstacles orange). "
      "The world is a procedural office floor (20 x 15 m: rooms, a corridor loop, doors, "
      "furniture; the robot drives the corridor loop) unless --world gives a ROS map, where the "
      "robot goes between random waypoints keeping 0.3 m from anything not free. Readings that "
      "hit nothing within --max-range are 0 (no return). The same seed gives the same files, "
      "byte for byte.");
  cmd->add_option("--out", a->out, "output folder")->required();
  CLI::Option* world = cmd->add_option(
      "--world", a->world,
      "world map (ROS map_server YAML); its occupied_thresh stops rays, cells below its "
      "free_thresh are free");
  cmd->add_flag("--floorplan", a->floorplan,
                "world: the procedural floorplan, built from the seed (the default)")
      ->excludes(world);
  cmd->add_option("--trajectory", a->trajectory,
                  "true poses: those of this reference log's scans instead of a generated path");
  cmd->add_option("--seed", a->seed, "seed of everything random")
      ->transform(seed_number())
      ->capture_default_str();
  cmd->add_option("--scans", a->scans,
                  "number of scans (default 400; with --trajectory all of its scans)")
      ->transform(whole_range(1, 10'000'000));
  cmd->add_option("--speed", a->speed, "robot speed (m/s); turn rate 1 rad/s")
      ->check(positive())
      ->capture_default_str();
  cmd->add_option("--period", a->period, "time between scans (s)")
      ->check(positive())
      ->capture_default_str();
  cmd->add_option("--sensor", a->sensor,
                  "lidar (one ray a beam) or cone (a ring of cones, each reading the nearest hit "
                  "within its FOV)")
      ->transform(one_of({"lidar", "cone"}))
      ->type_name("lidar|cone")
      ->capture_default_str();
  cmd->add_option("--beams", a->beams, "beams of the lidar (default 361) or cones (default 16)")
      ->transform(whole_range(1, 100'000));
  cmd->add_option("--fov", a->fov,
                  "degrees: the lidar's span (default 180; 360 = all round) or each cone's FOV "
                  "(default 30)")
      ->check(real_range(0.0, 360.0, true, false));
  // The log readers refuse a range limit past kMaxRangeLimitMetres: so does the simulator,
  // rather than write a log nothing reads.
  cmd->add_option("--max-range", a->max_range, "sensor range (m; default lidar 8, cone 5)")
      ->check(real_range(0.0, io::kMaxRangeLimitMetres, true, false));
  cmd->add_option("--noise", a->noise, "standard deviation of the Gaussian range noise (m)")
      ->check(non_negative())
      ->capture_default_str();
  cmd->add_option("--dropout", a->dropout, "probability that a reading is 0 (no return)")
      ->check(probability())
      ->capture_default_str();
  cmd->add_option("--contamination", a->contamination,
                  "probability that a reading is replaced by a uniform range in (0, max range)")
      ->check(probability())
      ->capture_default_str();
  cmd->add_option("--obstacles", a->obstacles,
                  "small unmodelled obstacles (discs of 0.2 to 0.4 m) in free space, at least "
                  "0.5 m from the true path: seen by the sensor, absent from the map")
      ->transform(whole_range(0, 1'000'000))
      ->capture_default_str();
  cmd->add_option("--large-obstacle", a->large_obstacle,
                  "also one unmodelled disc of 1 m this far (m) straight ahead of the first pose")
      ->check(non_negative());
  cmd->add_option(
         "--odometry-noise", a->odometry_noise,
         "alphas of the odometry motion model (Probabilistic Robotics, table 5.6): variances "
         "rot1 A1 rot1^2 + A2 trans^2, trans A3 trans^2 + A4 (rot1^2 + rot2^2), rot2 "
         "A1 rot2^2 + A2 trans^2; 0,0,0,0 = exact odometry")
      ->type_name("A1,A2,A3,A4")
      ->capture_default_str();
  cmd->add_option("--cell", a->cell, "cell size of the floorplan (m; default 0.1)")
      ->check(positive());
  cmd->callback([a] { run_simulate(*a); });
}

}  // namespace intgrid::cli
