#include "cli/slam_sweeps.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "intgrid/core/map_distance.hpp"
#include "intgrid/figures/figure_layout.hpp"
#include "intgrid/figures/gnuplot.hpp"
#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/image_io.hpp"
#include "intgrid/io/text_io.hpp"
#include "intgrid/simulation/simulator.hpp"
#include "intgrid/slam/log_run.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace intgrid::cli {
namespace {

constexpr double kOccupied = 0.5;       // built and true cells above this are obstacles
constexpr double kSpeed = 0.45;         // m/s, at the simulator's 5 scans/s: 9 cm a scan
constexpr int kWorldPixelsPerCell = 4;  // slam_world.png
constexpr int kMapPixelsPerCell = 2;    // slam_maps.png
constexpr io::Rgb kTruthColor{30, 160, 30};
constexpr io::Rgb kOdometryColor{150, 150, 150};
constexpr io::Rgb kSlamColor{220, 30, 30};

const char* arith_name(core::Arithmetic a) {
  return a == core::Arithmetic::integer ? "int" : "float";
}

// ---------------------------------------------------------------------------------------------
// The runs

enum class Sweep { lambda, xi, depth };

struct RunSpec {
  Sweep sweep = Sweep::lambda;
  int lambda = 1;
  int xi = 1;
  int window_cells = slam::GridSlamConfig{}.window.cells;
  int window_headings = slam::GridSlamConfig{}.window.headings;
  std::size_t scans = 0;  // the first scans of the log
  core::Arithmetic arithmetic = core::Arithmetic::integer;

  std::size_t pose_cells() const {
    return static_cast<std::size_t>(window_cells) * static_cast<std::size_t>(window_cells) *
           static_cast<std::size_t>(window_headings);
  }
  bool same_point(const RunSpec& o) const {
    return lambda == o.lambda && xi == o.xi && window_cells == o.window_cells &&
           window_headings == o.window_headings && scans == o.scans;
  }
};

struct RunResult {
  RunSpec spec;
  double seconds = 0.0;
  std::size_t localizations = 0;
  std::size_t mappings = 0;
  double e_sigma = 0.0;
  core::ObstacleDistance e_d;          // to the true occupied cells' squares
  core::ObstacleDistance e_d_centres;  // to their centres
  slam::TrajectoryError ate;
  double int_over_float = std::numeric_limits<double>::quiet_NaN();
  std::vector<core::Pose2> trajectory;
  core::ProbabilityGrid
      map;            // the built map read on the world's grid (P = 1/2 where it has no cell)
  std::string error;  // why the run stopped, if it did
};

struct World {
  simulation::Simulation sim;
  std::vector<slam::TimedPose> truth;  // scan_poses(sim.truth)
  slam::TrajectoryError odometry_ate;
};

World make_world(std::uint64_t seed, std::size_t scans) {
  const simulation::Floorplan floor =
      simulation::make_floorplan(simulation::FloorplanConfig{}, seed);
  simulation::SimulationConfig c;
  c.trajectory.scans = scans;
  // 9 cm a scan, not the default 10 cm: the SLAM frame's pose grid has 10 cm steps from the first
  // pose, so a robot moving one cell a scan along the corridor would sit exactly on the grid and
  // any estimate that collapses to one pose-grid cell would show no error at all.
  c.trajectory.speed = kSpeed;
  c.route = floor.corridor_loop;
  c.sensor = simulation::lidar_sensor();
  World w{simulation::simulate(floor.grid, c, seed), {}, {}};
  w.truth = slam::scan_poses(w.sim.truth);
  w.odometry_ate = slam::absolute_trajectory_error(slam::scan_poses(w.sim.log), w.truth);
  return w;
}

core::Log first_scans(const core::Log& log, std::size_t n) {
  core::Log out;
  n = std::min(n, log.scans.size());
  out.scans.assign(log.scans.begin(), log.scans.begin() + static_cast<std::ptrdiff_t>(n));
  for (const core::OdometryRecord& r : log.odometry)
    if (!out.scans.empty() && r.t <= out.scans.back().t + 1e-9) out.odometry.push_back(r);
  return out;
}

// The map on the world's grid, each world cell reading the built cell holding its centre.
core::ProbabilityGrid on_grid(const core::ProbabilityGrid& built, const core::GridGeometry& g) {
  core::ProbabilityGrid out(g, 0.5);
  const core::GridGeometry& b = built.geometry;
  for (int iy = 0; iy < g.height; ++iy)
    for (int ix = 0; ix < g.width; ++ix) {
      const int bx = b.cell_x(g.centre_x(ix)), by = b.cell_y(g.centre_y(iy));
      if (b.contains(bx, by)) out.at(ix, iy) = built.at(bx, by);
    }
  return out;
}

RunResult run_one(const World& world, const slam::GridSlamConfig& base, const RunSpec& spec,
                  const core::Progress& progress) {
  slam::GridSlamConfig config = base;
  config.schedule.lambda = spec.lambda;
  config.schedule.xi = spec.xi;
  config.window.cells = spec.window_cells;
  config.window.headings = spec.window_headings;
  const core::Log log = first_scans(world.sim.log, spec.scans);

  RunResult r;
  r.spec = spec;
  r.map = core::ProbabilityGrid(world.sim.world.geometry, 0.5);
  const auto start = std::chrono::steady_clock::now();
  slam::SlamRun run;
  try {
    run = slam::run_grid_slam(log, config, spec.arithmetic, progress);
  } catch (const std::runtime_error& e) {
    // A run that loses the robot (the pose window at the map's edge, Pi all zero) is a result of
    // the sweep, not the end of it: its row holds NaN.
    r.error = e.what();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    r.seconds = r.e_sigma = r.e_d.mean = r.e_d.max = r.e_d_centres.mean = r.ate.rmse = r.ate.max =
        r.ate.mean_heading = nan;
    return r;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.localizations = run.localizations;
  r.mappings = run.mappings;
  r.e_sigma = run.mean_sigma();
  r.ate = slam::absolute_trajectory_error(run.trajectory, world.truth);
  const core::ProbabilityGrid built = slam::slam_map_probabilities(run);
  r.e_d = core::distance_to_nearest_obstacle(built, kOccupied, world.sim.world, kOccupied);
  r.e_d_centres = core::distance_to_nearest_obstacle(built, kOccupied, world.sim.world, kOccupied,
                                                     core::ObstacleExtent::centre);
  for (const slam::TimedPose& p : run.trajectory) r.trajectory.push_back(p.pose);
  r.map = on_grid(built, world.sim.world.geometry);
  return r;
}

struct Plan {
  slam::GridSlamConfig base;  // lambda: the xi sweep's; xi: the lambda sweep's; the window: both's
  std::vector<int> lambdas, xis, windows;
  std::size_t scans = 0, depth_scans = 0;

  // The xi sweep's point xi is the lambda sweep's point base.lambda.
  bool xi_borrows(int xi) const {
    return xi == base.schedule.xi &&
           std::find(lambdas.begin(), lambdas.end(), base.schedule.lambda) != lambdas.end();
  }
};

Plan make_plan(const SlamSweepOptions& o) {
  Plan p;
  p.base = o.config;
  p.scans = o.scans ? o.scans : o.quick ? kSlamSweepQuickScans : kSlamSweepScans;
  p.depth_scans = std::min(p.scans, o.quick ? p.scans : kSlamSweepDepthScans);
  if (o.quick) {
    p.lambdas = {1, 3};
    p.xis = {1, 3};
    p.windows = {3, 5};
  } else {
    p.lambdas = {1, 2, 3, 6, 9, 15};
    p.xis = {1, 3, 6, 9, 15};
    p.windows = {3, 5, 9, 17, 33};
  }
  return p;
}

std::vector<RunSpec> make_specs(const Plan& p) {
  std::vector<RunSpec> specs;
  const auto both = [&](RunSpec s) {
    for (const core::Arithmetic a : {core::Arithmetic::integer, core::Arithmetic::floating}) {
      s.arithmetic = a;
      specs.push_back(s);
    }
  };
  const slam::GridSlamConfig& b = p.base;
  for (const int lambda : p.lambdas)
    both({Sweep::lambda, lambda, b.schedule.xi, b.window.cells, b.window.headings, p.scans});
  for (const int xi : p.xis)
    if (!p.xi_borrows(xi))
      both({Sweep::xi, b.schedule.lambda, xi, b.window.cells, b.window.headings, p.scans});
  for (const int w : p.windows)
    both({Sweep::depth, b.schedule.lambda, b.schedule.xi, w, w, p.depth_scans});
  return specs;
}

void pair_ratios(std::vector<RunResult>& results) {
  for (RunResult& a : results)
    for (const RunResult& b : results)
      if (a.spec.sweep == b.spec.sweep && a.spec.same_point(b.spec) &&
          a.spec.arithmetic != b.spec.arithmetic) {
        const RunResult& i = a.spec.arithmetic == core::Arithmetic::integer ? a : b;
        const RunResult& f = a.spec.arithmetic == core::Arithmetic::integer ? b : a;
        a.int_over_float = i.seconds / f.seconds;
      }
}

// The runs of one sweep, in order; the xi sweep borrows the lambda sweep's runs of its point.
std::vector<const RunResult*> sweep_rows(const std::vector<RunResult>& results, Sweep sweep,
                                         const Plan& plan) {
  std::vector<const RunResult*> rows;
  if (sweep != Sweep::xi) {
    for (const RunResult& r : results)
      if (r.spec.sweep == sweep) rows.push_back(&r);
    return rows;
  }
  for (const int xi : plan.xis)
    for (const RunResult& r : results)
      if (plan.xi_borrows(xi)
              ? r.spec.sweep == Sweep::lambda && r.spec.lambda == plan.base.schedule.lambda
              : r.spec.sweep == Sweep::xi && r.spec.xi == xi)
        rows.push_back(&r);
  return rows;
}

// The two arithmetics' runs of each point of a sweep.
struct Point {
  const RunResult* integer = nullptr;
  const RunResult* floating = nullptr;
};

std::vector<Point> sweep_points(const std::vector<const RunResult*>& rows) {
  std::vector<Point> points;
  for (const RunResult* r : rows) {
    auto it = std::find_if(points.begin(), points.end(), [&](const Point& p) {
      return (p.integer ? p.integer : p.floating)->spec.same_point(r->spec);
    });
    if (it == points.end()) it = points.insert(points.end(), Point{});
    (r->spec.arithmetic == core::Arithmetic::integer ? it->integer : it->floating) = r;
  }
  return points;
}

// ---------------------------------------------------------------------------------------------
// CSVs

constexpr const char* kCsvHeader =
    "lambda,xi,window_cells,window_headings,pose_cells,arith,scans,localizations,mappings,"
    "seconds,ms_per_scan,int_over_float_seconds,e_sigma_m,e_d_m,e_d_max_m,e_d_centres_m,"
    "map_occupied_cells,"
    "ate_rmse_m,ate_max_m,ate_heading_deg";

void write_csv(const std::filesystem::path& file, const std::vector<const RunResult*>& rows) {
  io::write_file_atomically(file, [&](std::ostream& out) {
    out << kCsvHeader << '\n';
    for (const RunResult* r : rows) {
      const RunSpec& s = r->spec;
      out << io::printed(
          "%d,%d,%d,%d,%zu,%s,%zu,%zu,%zu,%.6f,%.4f,%.4f,%.6g,%.6g,%.6g,%.6g,%zu,%.6g,%.6g,%.4f\n",
          s.lambda, s.xi, s.window_cells, s.window_headings, s.pose_cells(),
          arith_name(s.arithmetic), s.scans, r->localizations, r->mappings, r->seconds,
          1000.0 * r->seconds / static_cast<double>(s.scans), r->int_over_float, r->e_sigma,
          r->e_d.mean, r->e_d.max, r->e_d_centres.mean, r->e_d.cells, r->ate.rmse, r->ate.max,
          r->ate.mean_heading * 180.0 / M_PI);
    }
  });
}

// ---------------------------------------------------------------------------------------------
// Pictures of the world and of the maps

core::GridGeometry pixel_geometry(const core::GridGeometry& g, int pixels_per_cell) {
  return {g.width * pixels_per_cell, g.height * pixels_per_cell, g.resolution / pixels_per_cell,
          g.origin_x, g.origin_y};
}

// A two-pixel line: the polyline and its copy one pixel right and one pixel up.
void draw_thick_polyline(io::RgbImage& image, const core::GridGeometry& pixels,
                         const std::vector<core::Pose2>& poses, io::Rgb color) {
  for (const auto& [dx, dy] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}) {
    std::vector<core::Pose2> shifted = poses;
    for (core::Pose2& p : shifted) {
      p.x += dx * pixels.resolution;
      p.y += dy * pixels.resolution;
    }
    io::draw_polyline_world(image, pixels, shifted, color);
  }
}

std::vector<core::Pose2> poses_of(const core::Log& log) {
  std::vector<core::Pose2> out;
  for (const core::Scan& s : log.scans) out.push_back(s.robot);
  return out;
}

void write_world_png(const std::filesystem::path& file, const World& world, const RunResult& run,
                     const slam::GridSlamConfig& config, std::uint64_t seed) {
  const core::ProbabilityGrid& g = world.sim.world;
  io::RgbImage image =
      io::render_probability_grid(g, io::ProbabilityScale::grey, kWorldPixelsPerCell);
  const core::GridGeometry pixels = pixel_geometry(g.geometry, kWorldPixelsPerCell);
  draw_thick_polyline(image, pixels, poses_of(world.sim.log), kOdometryColor);
  draw_thick_polyline(image, pixels, poses_of(world.sim.truth), kTruthColor);
  draw_thick_polyline(image, pixels, run.trajectory, kSlamColor);
  const core::Pose2& start = world.sim.truth.scans.front().robot;
  io::draw_marker_world(image, pixels, start.x, start.y, 5, kTruthColor);
  const io::RgbImage figure = figures::compose_figure(
      io::printed("SLAM on a simulated floor: %zu scans, seed %llu", run.spec.scans,
                  static_cast<unsigned long long>(seed)),
      {{{io::printed("%.0f x %.0f m, %g cm cells", g.geometry.width * g.geometry.resolution,
                     g.geometry.height * g.geometry.resolution, 100 * g.geometry.resolution),
         image}}},
      io::ProbabilityScale::grey,
      {io::printed(
           "green: true trajectory (dot: start); grey: odometry; red: integer SLAM, lambda = %d, "
           "xi = %d",
           run.spec.lambda, run.spec.xi),
       io::printed(
           "ATE RMSE: odometry %.1f cm, integer SLAM %.1f cm; E(sigma) %.1f cm, E(d) %.1f cm",
           100 * world.odometry_ate.rmse, 100 * run.ate.rmse, 100 * run.e_sigma,
           100 * run.e_d.mean),
       io::printed(
           "LiDAR 361 beams over 180 deg, 8 m, sigma 1 cm; SLAM %g cm cells, pose grid %d x %d x "
           "%d of %d headings a turn",
           100 * config.cell, run.spec.window_cells, run.spec.window_cells,
           run.spec.window_headings, config.headings)});
  io::write_png(file, figure);
}

void write_maps_png(const std::filesystem::path& file, const std::vector<RunResult>& results,
                    const Plan& plan) {
  const auto panel = [&](const RunResult& r, const std::string& name) {
    return figures::Panel{
        io::printed("%s\nE(sigma) %.1f cm, E(d) %.1f cm", name.c_str(), 100 * r.e_sigma,
                    100 * r.e_d.mean),
        io::render_probability_grid(r.map, io::ProbabilityScale::grey, kMapPixelsPerCell)};
  };
  std::vector<std::vector<figures::Panel>> rows(2);
  for (const RunResult& r : results) {
    if (r.spec.arithmetic != core::Arithmetic::integer) continue;
    if (r.spec.sweep == Sweep::lambda && r.spec.lambda != 2)
      rows[0].push_back(panel(r, io::printed("lambda = %d", r.spec.lambda)));
    if (r.spec.sweep == Sweep::xi) rows[1].push_back(panel(r, io::printed("xi = %d", r.spec.xi)));
  }
  if (rows[1].empty()) rows.pop_back();
  const io::RgbImage figure = figures::compose_figure(
      io::printed("Maps built by the integer SLAM (thesis figure 3.10), %zu scans", plan.scans),
      rows, io::ProbabilityScale::grey,
      {"top: localization every lambda-th scan (mapping every scan); bottom: mapping every xi-th "
       "scan (localization every scan)",
       "E(d): mean distance from the map's cells with P > 0.5 to the nearest wall of the world"});
  io::write_png(file, figure);
}

// ---------------------------------------------------------------------------------------------
// gnuplot

struct Labels {
  std::string lambda, xi, sigma;
};

std::string datablock(const char* name, const std::vector<Point>& points, const char* columns,
                      double (*x)(const RunSpec&), double (*y)(const RunResult&),
                      double (*z)(const RunResult&), double (*w)(const RunResult&)) {
  std::string out = io::printed("$%s << EOD\n# %s\n", name, columns);
  for (const Point& p : points) {
    if (!p.integer || !p.floating) continue;
    out += io::printed("%.9g", x(p.integer->spec));
    for (const auto f : {y, z, w})
      if (f) out += io::printed(" %.9g %.9g", f(*p.integer), f(*p.floating));
    out += '\n';
  }
  return out + "EOD\n";
}

std::string plot_script(const std::vector<Point>& lambda, const std::vector<Point>& xi,
                        const std::vector<Point>& depth, const std::string& title, bool cairo,
                        int fixed_lambda, int fixed_xi, const std::filesystem::path& lambda_png,
                        const std::filesystem::path& xi_png,
                        const std::filesystem::path& depth_png) {
  const Labels l = cairo ? Labels{"λ", "ξ", "σ"} : Labels{"lambda", "xi", "sigma"};
  const auto cm = [](const RunResult& r) { return 100.0 * r.e_sigma; };
  std::string s;
  s += datablock(
      "lambda", lambda, "lambda e_sigma_cm(int float) seconds(int float)",
      [](const RunSpec& x) { return double(x.lambda); }, cm,
      [](const RunResult& r) { return r.seconds; }, nullptr);
  s += datablock(
      "xi", xi, "xi e_d_cm(int float) e_sigma_cm(int float) seconds(int float)",
      [](const RunSpec& x) { return double(x.xi); },
      [](const RunResult& r) { return 100.0 * r.e_d.mean; }, cm,
      [](const RunResult& r) { return r.seconds; });
  s += datablock(
      "depth", depth, "pose_cells ms_per_scan(int float) ratio(int float)",
      [](const RunSpec& x) { return double(x.pose_cells()); },
      [](const RunResult& r) { return 1000.0 * r.seconds / double(r.spec.scans); },
      [](const RunResult& r) { return r.int_over_float; }, nullptr);
  const std::string lines =
      "set grid\nset key below\nset style data linespoints\nset pointsize 1.3\nset yrange [0:*]\n";
  const std::string plot_pair =
      "using 1:%d title 'integer (U_gamma, S_eps)' lw 2 pt 7 lc rgb '#d01c1c', '' using 1:%d "
      "title 'double' lw 2 pt 5 lc rgb '#1c4cd0'\n";

  s += figures::gp_terminal_line(cairo, 1300, 520);
  s += "set output " + figures::gp_quoted(lambda_png.string()) + "\n" + lines;
  s += "set multiplot layout 1,2 title " +
       figures::gp_quoted(title + ": localization every " + l.lambda + "-th scan (" + l.xi +
                          io::printed(" = %d)", fixed_xi)) +
       "\n";
  s += "set xlabel " + figures::gp_quoted(l.lambda + " (scans between localizations)") + "\n";
  s += "set ylabel " + figures::gp_quoted("E(" + l.sigma + "), mean pose standard deviation (cm)") +
       "\n";
  s += "plot $lambda " + io::printed(plot_pair.c_str(), 2, 3);
  s += "set ylabel 'run time (s)'\n";
  s += "plot $lambda " + io::printed(plot_pair.c_str(), 4, 5);
  s += "unset multiplot\nunset output\nreset\n";

  s += figures::gp_terminal_line(cairo, 1800, 520);
  s += "set output " + figures::gp_quoted(xi_png.string()) + "\n" + lines;
  s += "set multiplot layout 1,3 title " +
       figures::gp_quoted(title + ": mapping every " + l.xi + "-th scan (" + l.lambda +
                          io::printed(" = %d)", fixed_lambda)) +
       "\n";
  s += "set xlabel " + figures::gp_quoted(l.xi + " (scans between mappings)") + "\n";
  s += "set ylabel 'E(d), map obstacles to true walls (cm)'\n";
  s += "plot $xi " + io::printed(plot_pair.c_str(), 2, 3);
  s += "set ylabel " + figures::gp_quoted("E(" + l.sigma + "), mean pose standard deviation (cm)") +
       "\n";
  s += "plot $xi " + io::printed(plot_pair.c_str(), 4, 5);
  s += "set ylabel 'run time (s)'\n";
  s += "plot $xi " + io::printed(plot_pair.c_str(), 6, 7);
  s += "unset multiplot\nunset output\nreset\n";

  s += figures::gp_terminal_line(cairo, 1300, 520);
  s += "set output " + figures::gp_quoted(depth_png.string()) + "\n" + lines;
  s += "set multiplot layout 1,2 title " +
       figures::gp_quoted(title + ": run time against the pose grid's size (thesis figure 3.14)") +
       "\n";
  s += "set logscale x 2\nset format x '%g'\nset xlabel 'pose-grid cells (window_cells^2 x "
       "window_headings)'\n";
  s += "set yrange [*:*]\nset logscale y\nset ylabel 'run time per scan (ms)'\n";
  s += "plot $depth " + io::printed(plot_pair.c_str(), 2, 3);
  s += "unset logscale y\nset ylabel 'integer time / double time'\nset yrange [0:*]\n";
  s += "plot $depth using 1:4 notitle lw 2 pt 7 lc rgb '#303030'\n";
  s += "unset multiplot\nunset output\n";
  return s;
}

// Plots the sweeps with gnuplot into PNGs; false (and nothing written) if gnuplot is missing.
bool write_plots(const SlamSweepOptions& o, const std::vector<Point>& lambda,
                 const std::vector<Point>& xi, const std::vector<Point>& depth,
                 const std::string& title) {
  const figures::GnuplotProbe probe = figures::probe_gnuplot(o.gnuplot);
  if (!probe.found) return false;
  io::AtomicFile lambda_png(o.out / "slam_lambda.png"), xi_png(o.out / "slam_xi.png"),
      depth_png(o.out / "slam_depth.png");
  return figures::draw_pngs(
      o.gnuplot,
      plot_script(lambda, xi, depth, title, probe.cairo, o.config.schedule.lambda,
                  o.config.schedule.xi, lambda_png.temporary_path(), xi_png.temporary_path(),
                  depth_png.temporary_path()),
      o.out / "slam_plots.gp", {&lambda_png, &xi_png, &depth_png});
}

// ---------------------------------------------------------------------------------------------
// The summary table

void print_table(const char* title, const char* variable, const std::vector<Point>& points,
                 int (*value)(const RunSpec&)) {
  std::printf("\n%s\n", title);
  std::printf("%10s | %-15s | %-15s | %-15s | %-17s | %s\n", variable, "E(sigma) cm", "E(d) cm",
              "ATE RMSE cm", "time s", "int/float");
  std::printf("%10s | %7s %7s | %7s %7s | %7s %7s | %8s %8s |\n", "", "int", "float", "int",
              "float", "int", "float", "int", "float");
  for (const Point& p : points) {
    if (!p.integer || !p.floating) continue;
    const RunResult &i = *p.integer, &f = *p.floating;
    std::printf("%10d | %7.2f %7.2f | %7.2f %7.2f | %7.2f %7.2f | %8.3f %8.3f | %.2f\n",
                value(i.spec), 100 * i.e_sigma, 100 * f.e_sigma, 100 * i.e_d.mean, 100 * f.e_d.mean,
                100 * i.ate.rmse, 100 * f.ate.rmse, i.seconds, f.seconds, i.int_over_float);
  }
}

}  // namespace

slam::GridSlamConfig default_sweep_config() {
  slam::GridSlamConfig c;
  c.cell = 0.1;
  c.headings = 256;
  c.window.headings = 21;  // +-14.8 degrees
  // The thesis's pose grid: every pose weighed at every localization, so that the size sweep
  // measures the cost of the grid (figure 3.14), not of the poses the motion model reaches.
  c.window.pose_prune = 0.0;
  // The simulated floor's readings are independent given the map, so its beams need little
  // tempering: at the real log's 16 its ATE doubles (docs/results.md).
  c.beam.tempering = 3;
  return c;
}

void run_slam_sweeps(const SlamSweepOptions& o) {
  const auto wall_start = std::chrono::steady_clock::now();
  const Plan plan = make_plan(o);
  if (plan.scans < 2) throw std::invalid_argument("--scans must be at least 2");
  check_slam_options(plan.base);
  const World world = make_world(o.seed, plan.scans);
  const std::vector<RunSpec> specs = make_specs(plan);

  // A short untimed run of each arithmetic first, so that the first timed run does not pay alone
  // for the process's first use of the allocator, the page tables and the caches. What the
  // configuration check cannot see, the map's size, it finds before anything is written.
  for (const core::Arithmetic a : {core::Arithmetic::integer, core::Arithmetic::floating}) {
    try {
      slam::run_grid_slam(first_scans(world.sim.log, 5), plan.base, a);
    } catch (const std::invalid_argument& e) {
      bad_option("--cell", "a map of " + option_number(plan.base.cell) +
                               " m cells over the simulated floor: " + e.what());
    }
  }
  std::filesystem::create_directories(o.out);

  std::vector<RunResult> results;
  {
    std::size_t total = 0, done = 0;
    for (const RunSpec& s : specs) total += s.scans;
    TerminalProgress progress("slam-sweeps: SLAM runs");
    for (const RunSpec& s : specs) {
      results.push_back(run_one(world, plan.base, s,
                                [&](std::size_t d, std::size_t) { progress(done + d, total); }));
      done += s.scans;
    }
  }
  pair_ratios(results);

  const std::vector<const RunResult*> lambda_rows = sweep_rows(results, Sweep::lambda, plan);
  const std::vector<const RunResult*> xi_rows = sweep_rows(results, Sweep::xi, plan);
  const std::vector<const RunResult*> depth_rows = sweep_rows(results, Sweep::depth, plan);
  write_csv(o.out / "slam_lambda.csv", lambda_rows);
  write_csv(o.out / "slam_xi.csv", xi_rows);
  write_csv(o.out / "slam_depth.csv", depth_rows);
  const auto base_run = std::find_if(lambda_rows.begin(), lambda_rows.end(), [&](auto* r) {
    return r->spec.lambda == plan.base.schedule.lambda &&
           r->spec.arithmetic == core::Arithmetic::integer;
  });
  write_world_png(o.out / "slam_world.png", world,
                  **(base_run == lambda_rows.end() ? lambda_rows.begin() : base_run), plan.base,
                  o.seed);
  write_maps_png(o.out / "slam_maps.png", results, plan);

  const std::vector<Point> lambda = sweep_points(lambda_rows), xi = sweep_points(xi_rows),
                           depth = sweep_points(depth_rows);
  const std::string title =
      io::printed("Grid SLAM, simulated floor, %zu scans, %g cm cells, seed %llu", plan.scans,
                  100 * plan.base.cell, static_cast<unsigned long long>(o.seed));
  const bool plotted = write_plots(o, lambda, xi, depth, title);

  const slam::GridSlamConfig& b = plan.base;
  std::printf(
      "simulated floor 20 x 15 m, 10 cm cells, seed %llu: %zu scans along the corridor loop at "
      "%g m/s; odometry ATE RMSE %.2f cm (max %.2f cm)\n",
      static_cast<unsigned long long>(o.seed), plan.scans, kSpeed, 100 * world.odometry_ate.rmse,
      100 * world.odometry_ate.max);
  std::printf("SLAM: %g cm cells, %d headings a turn, %d beams a localization\n", 100 * b.cell,
              b.headings, b.beam.beams);
  const std::string window =
      io::printed("pose grid %d x %d x %d", b.window.cells, b.window.cells, b.window.headings);
  print_table(io::printed("lambda sweep (xi = %d, %s):", b.schedule.xi, window.c_str()).c_str(),
              "lambda", lambda, [](const RunSpec& s) { return s.lambda; });
  print_table(io::printed("xi sweep (lambda = %d, %s):", b.schedule.lambda, window.c_str()).c_str(),
              "xi", xi, [](const RunSpec& s) { return s.xi; });
  std::printf("\npose-grid size sweep (lambda = %d, xi = %d, first %zu scans):\n",
              b.schedule.lambda, b.schedule.xi, plan.depth_scans);
  std::printf("%8s %10s | %-21s | %-21s | %s\n", "window", "pose cells", "ms per scan int float",
              "ATE RMSE cm int float", "int/float");
  for (const Point& p : depth) {
    if (!p.integer || !p.floating) continue;
    const RunResult &i = *p.integer, &f = *p.floating;
    const double scans = static_cast<double>(i.spec.scans);
    std::printf(
        "%8s %10zu | %10.2f %10.2f | %10.2f %10.2f | %.2f\n",
        io::printed("%dx%dx%d", i.spec.window_cells, i.spec.window_cells, i.spec.window_headings)
            .c_str(),
        i.spec.pose_cells(), 1000 * i.seconds / scans, 1000 * f.seconds / scans, 100 * i.ate.rmse,
        100 * f.ate.rmse, i.int_over_float);
  }
  for (const RunResult& r : results)
    if (!r.error.empty())
      std::printf("run lambda %d, xi %d, pose grid %d x %d x %d, %s failed: %s\n", r.spec.lambda,
                  r.spec.xi, r.spec.window_cells, r.spec.window_cells, r.spec.window_headings,
                  arith_name(r.spec.arithmetic), r.error.c_str());
  std::printf(
      "\nwrote %s/slam_lambda.csv, slam_xi.csv, slam_depth.csv, slam_world.png, "
      "slam_maps.png%s\n",
      o.out.string().c_str(), plotted ? ", slam_lambda.png, slam_xi.png, slam_depth.png" : "");
  if (!plotted) figures::print_plots_skipped(o.gnuplot);
  std::printf("wall time %.1f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
}

void add_slam_sweeps_figure(CLI::App& figure) {
  auto o = std::make_shared<SlamSweepOptions>();
  CLI::App* cmd = figure.add_subcommand(
      "slam-sweeps", "thesis 3.6: the SLAM against lambda, xi and the pose grid's size");
  cmd->add_option("--out", o->out, "output folder")->required();
  cmd->add_option("--seed", o->seed, "seed of the floor, trajectory and noise")
      ->transform(seed_number())
      ->capture_default_str();
  cmd->add_option("--scans", o->scans,
                  io::printed("scans of the simulated run (default %zu, %zu with --quick)",
                              kSlamSweepScans, kSlamSweepQuickScans))
      ->transform(whole_range(2, 100000));
  cmd->add_flag("--quick", o->quick, "few scans and sweep points (for tests)");
  cmd->add_option("--gnuplot", o->gnuplot, "the gnuplot program")->capture_default_str();
  add_slam_options(*cmd, o->config);
  cmd->footer(
      "E(sigma), E(d), ATE and run time of integer and double SLAM on a simulated floor with 10 cm "
      "cells; CSVs, gnuplot plots, maps. The SLAM options set every run but what a sweep varies: "
      "--lambda is the xi sweep's, --xi "
      "the lambda sweep's, --window-cells and --window-headings both's (the size sweep sets them "
      "equal, 3 to 33). Defaults for 10 cm cells: 256 headings a turn (1.4 degrees, a cell at 4 "
      "m).");
  cmd->callback([o] { run_slam_sweeps(*o); });
}

}  // namespace intgrid::cli
