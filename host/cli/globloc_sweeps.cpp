#include "cli/globloc_sweeps.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <exception>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cli/commands.hpp"
#include "cli/globloc_job.hpp"
#include "cli/progress.hpp"
#include "intgrid/core/parallel.hpp"
#include "intgrid/figures/gnuplot.hpp"
#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/map_io.hpp"
#include "intgrid/io/text_io.hpp"
#include "intgrid/simulation/simulator.hpp"

namespace intgrid::cli {
namespace {

using Clock = std::chrono::steady_clock;

// GlobalTrialConditions' fields -> the options of globloc-sweeps that set them.
const FieldFlags& trial_condition_flags() {
  static const FieldFlags flags = {{"readings", "--beams"},
                                   {"fov", "--fov"},
                                   {"max_range", "--sensor-range"},
                                   {"noise", "--noise"}};
  return flags;
}

constexpr const auto& kMethods = kGlobalMethods;
constexpr std::size_t kMethodCount = std::size(kGlobalMethods);
// Seed streams: the true poses (per trial, shared by every sweep point), then the sweeps'.
constexpr std::uint64_t kPoseStream = 0;
constexpr std::uint64_t kSweepStream = 1;

enum class Sweep { readings, noise, contamination, obstacles, large_obstacle };

struct SweepSpec {
  Sweep sweep;
  const char* name;      // file stem and table title
  const char* variable;  // CSV column and x label
  std::vector<double> values;
};

std::vector<SweepSpec> make_sweeps(bool quick) {
  if (quick)
    return {{Sweep::readings, "readings", "readings", {5, 60}},
            {Sweep::noise, "noise", "noise_m", {0.01, 0.2}},
            {Sweep::contamination, "contamination", "contamination", {0.0, 0.5}},
            {Sweep::obstacles, "obstacles", "obstacles", {0, 55}},
            {Sweep::large_obstacle, "large_obstacle", "distance_m", {1.0, 4.0}}};
  return {{Sweep::readings, "readings", "readings", {5, 10, 20, 30, 60, 90, 120}},
          {Sweep::noise, "noise", "noise_m", {0.01, 0.02, 0.03, 0.05, 0.1, 0.15, 0.2}},
          {Sweep::contamination, "contamination", "contamination", {0.0, 0.1, 0.2, 0.3, 0.4, 0.5}},
          {Sweep::obstacles, "obstacles", "obstacles", {0, 5, 15, 25, 35, 45, 55}},
          {Sweep::large_obstacle, "large_obstacle", "distance_m", {1.0, 1.5, 2.0, 3.0, 4.0, 6.0}}};
}

experiments::GlobalTrialConditions conditions_at(experiments::GlobalTrialConditions c, Sweep sweep,
                                                 double value) {
  switch (sweep) {
    case Sweep::readings:
      c.readings = static_cast<std::size_t>(value);
      break;
    case Sweep::noise:
      c.noise = value;
      break;
    case Sweep::contamination:
      c.contamination = value;
      break;
    case Sweep::obstacles:
      c.obstacles = static_cast<std::size_t>(value);
      break;
    case Sweep::large_obstacle:
      c.large_obstacle = value;
      break;
  }
  return c;
}

struct MethodOutcome {
  experiments::GlobalTrialError error;
  double seconds = 0.0;
};

struct TrialResult {
  std::size_t readings = 0;  // usable readings
  std::array<MethodOutcome, kMethodCount> methods{};
  std::string error;  // the trial could not be set up (e.g. the obstacles do not fit)
};

struct Item {
  std::size_t sweep = 0, value = 0, trial = 0;
};

struct Aggregate {
  std::size_t trials = 0, successes = 0, failed_setups = 0;
  double mean_readings = 0.0;
  std::array<std::size_t, kMethodCount> success{};
  std::array<double, kMethodCount> position{}, heading{}, median_position{}, seconds{};
};

Aggregate aggregate(const std::vector<TrialResult>& results, std::size_t begin, std::size_t n) {
  Aggregate a;
  std::array<std::vector<double>, kMethodCount> positions;
  for (std::size_t t = begin; t < begin + n; ++t) {
    const TrialResult& r = results[t];
    if (!r.error.empty()) {
      ++a.failed_setups;
      continue;
    }
    ++a.trials;
    a.mean_readings += static_cast<double>(r.readings);
    for (std::size_t m = 0; m < kMethodCount; ++m) {
      const MethodOutcome& o = r.methods[m];
      a.success[m] += o.error.success ? 1 : 0;
      a.position[m] += o.error.position;
      a.heading[m] += o.error.heading;
      a.seconds[m] += o.seconds;
      positions[m].push_back(o.error.position);
    }
  }
  if (a.trials == 0) return a;
  const double n_trials = static_cast<double>(a.trials);
  a.mean_readings /= n_trials;
  for (std::size_t m = 0; m < kMethodCount; ++m) {
    a.position[m] /= n_trials;
    a.heading[m] /= n_trials;
    a.seconds[m] /= n_trials;
    std::vector<double>& p = positions[m];
    std::nth_element(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(p.size() / 2), p.end());
    a.median_position[m] = p[p.size() / 2];
  }
  return a;
}

std::string value_text(Sweep sweep, double v) {
  return sweep == Sweep::readings || sweep == Sweep::obstacles ? io::printed("%.0f", v)
                                                               : io::printed("%g", v);
}

constexpr double kDeg = 180.0 / std::numbers::pi;

void write_csv(const std::filesystem::path& file, const SweepSpec& s,
               const std::vector<Aggregate>& points) {
  io::write_file_atomically(file, [&](std::ostream& out) {
    out << s.variable
        << ",method,trials,failed_setups,mean_readings,successes,success_rate,"
           "mean_position_error_m,median_position_error_m,mean_heading_error_deg\n";
    for (std::size_t v = 0; v < points.size(); ++v)
      for (std::size_t m = 0; m < kMethodCount; ++m) {
        const Aggregate& a = points[v];
        const double n = static_cast<double>(std::max<std::size_t>(a.trials, 1));
        out << value_text(s.sweep, s.values[v]) << ',' << global_method_name(kMethods[m]) << ','
            << a.trials << ',' << a.failed_setups << ',' << io::printed("%.6g", a.mean_readings)
            << ',' << a.success[m] << ','
            << io::printed("%.6g", static_cast<double>(a.success[m]) / n) << ','
            << io::printed("%.6g,%.6g,%.6g", a.position[m], a.median_position[m],
                           a.heading[m] * kDeg)
            << '\n';
      }
  });
}

const char* kColors[kMethodCount] = {"#d01c1c", "#1c4cd0", "#20a040", "#a040c0"};
const char* kPointTypes[kMethodCount] = {"7", "5", "9", "11"};

std::string plot_script(const SweepSpec& s, const std::vector<Aggregate>& points,
                        const std::string& title, const std::string& xlabel, bool cairo,
                        const std::filesystem::path& png) {
  std::string out = "$data << EOD\n# x then per method: success_% position_m heading_deg\n";
  for (std::size_t v = 0; v < points.size(); ++v) {
    const Aggregate& a = points[v];
    out += io::printed("%.9g", s.sweep == Sweep::contamination ? 100.0 * s.values[v] : s.values[v]);
    const double n = static_cast<double>(std::max<std::size_t>(a.trials, 1));
    for (std::size_t m = 0; m < kMethodCount; ++m)
      out += io::printed(" %.9g %.9g %.9g", 100.0 * static_cast<double>(a.success[m]) / n,
                         a.position[m], a.heading[m] * kDeg);
    out += '\n';
  }
  out += "EOD\n";
  out += figures::gp_terminal_line(cairo, 1800, 540);
  out += "set output " + figures::gp_quoted(png.string()) + "\n";
  out += "set grid\nset key below\nset style data linespoints\nset pointsize 1.2\n";
  out += "set multiplot layout 1,3 title " + figures::gp_quoted(title) + "\n";
  out += "set xlabel " + figures::gp_quoted(xlabel) + "\n";
  const char* ylabels[3] = {"success rate (%)", "mean position error (m)",
                            "mean heading error (degrees)"};
  for (int panel = 0; panel < 3; ++panel) {
    out += "set ylabel " + figures::gp_quoted(ylabels[panel]) + "\n";
    out += panel == 0 ? "set yrange [0:105]\n" : "set yrange [0:*]\n";
    out += "plot ";
    for (std::size_t m = 0; m < kMethodCount; ++m)
      out += io::printed("%s$data using 1:%zu title '%s' lw 2 pt %s lc rgb '%s'", m ? ", " : "",
                         2 + 3 * m + static_cast<std::size_t>(panel),
                         global_method_name(kMethods[m]), kPointTypes[m], kColors[m]);
    out += "\n";
  }
  out += "unset multiplot\nunset output\n";
  return out;
}

const char* x_label(Sweep sweep) {
  switch (sweep) {
    case Sweep::readings:
      return "readings per scan";
    case Sweep::noise:
      return "sensor noise sigma (m)";
    case Sweep::contamination:
      return "uniformly contaminated readings (%)";
    case Sweep::obstacles:
      return "small unmodelled obstacles (0.2 to 0.4 m discs) within range";
    case Sweep::large_obstacle:
      return "distance to a 1 m unmodelled disc straight ahead (m)";
  }
  return "";
}

// One PNG per sweep; false (and nothing written) if gnuplot is missing.
bool write_plots(const GlobLocSweepOptions& o, const std::vector<SweepSpec>& sweeps,
                 const std::vector<std::vector<Aggregate>>& points, const std::string& title) {
  const figures::GnuplotProbe probe = figures::probe_gnuplot(o.gnuplot);
  if (!probe.found) return false;
  for (std::size_t s = 0; s < sweeps.size(); ++s) {
    io::AtomicFile png(o.out / ("globloc_" + std::string(sweeps[s].name) + ".png"));
    if (!figures::draw_pngs(o.gnuplot,
                            plot_script(sweeps[s], points[s], title, x_label(sweeps[s].sweep),
                                        probe.cairo, png.temporary_path()),
                            o.out / "globloc_plots.gp", {&png}))
      return false;
  }
  return true;
}

void print_table(const SweepSpec& s, const std::vector<Aggregate>& points) {
  std::printf("\n%s sweep: success %% / mean position error m / mean heading error deg\n", s.name);
  std::printf("%13s |", s.variable);
  for (const localization::GlobalMethod m : kMethods) std::printf(" %-23s|", global_method_name(m));
  std::printf("\n");
  for (std::size_t v = 0; v < points.size(); ++v) {
    const Aggregate& a = points[v];
    const double n = static_cast<double>(std::max<std::size_t>(a.trials, 1));
    std::printf("%13s |", value_text(s.sweep, s.values[v]).c_str());
    for (std::size_t m = 0; m < kMethodCount; ++m)
      std::printf(" %5.1f %8.3f %8.2f |", 100.0 * static_cast<double>(a.success[m]) / n,
                  a.position[m], a.heading[m] * kDeg);
    if (a.failed_setups) std::printf(" (%zu trials not set up)", a.failed_setups);
    std::printf("\n");
  }
}

}  // namespace

void run_globloc_sweeps(const GlobLocSweepOptions& o) {
  const auto wall_start = Clock::now();
  if (o.trials == 0) bad_option("--trials", "must be at least 1");
  check_global_loc_options(o.config);
  naming_flags(trial_condition_flags(),
               [&] { experiments::check_global_trial_conditions(o.conditions); });
  if (!(o.clearance >= 0.0) || !std::isfinite(o.clearance))
    bad_option("--clearance",
               "must be a finite distance >= 0 (m), got " + option_number(o.clearance));
  const io::RosMap map = io::read_ros_map(o.map);
  if (o.config.pose_res < map.grid.geometry.resolution)
    throw io::InputError(
        o.map, 0, "resolution",
        io::printed("the pose-grid step --pose-cell %g m is finer than the map's %g m",
                    o.config.pose_res, map.grid.geometry.resolution));
  std::optional<experiments::GlobalTrialWorld> world;
  try {
    world.emplace(map.grid, map.occupied_thresh, map.free_thresh, o.clearance);
  } catch (const std::invalid_argument& e) {
    if (std::string_view(e.what()).find("from every non-free cell") != std::string_view::npos)
      bad_option("--clearance", std::string(e.what()) + " in " + o.map.string());
    throw io::InputError(o.map, 0, "image", e.what());
  }
  std::filesystem::create_directories(o.out);

  std::vector<SweepSpec> sweeps = make_sweeps(o.quick);
  if (!o.only.empty())
    std::erase_if(sweeps, [&](const SweepSpec& s) {
      return std::find(o.only.begin(), o.only.end(), s.name) == o.only.end();
    });
  // The localizers' model sigma: the configured one, or in the noise sweep the sensor's noise
  // (the localizer knows its sensor) unless fixed. One LocalizationMap per sigma, shared
  // read-only by every thread.
  const auto sigma_at = [&](const SweepSpec& sweep, double value) {
    return sweep.sweep == Sweep::noise && !o.fixed_sigma ? value : o.config.sensor.sigma;
  };
  std::vector<std::pair<double, std::unique_ptr<localization::LocalizationMap>>> maps;
  const auto map_start = Clock::now();
  for (const SweepSpec& sweep : sweeps)
    for (const double value : sweep.values) {
      const double sigma = sigma_at(sweep, value);
      if (std::any_of(maps.begin(), maps.end(), [&](const auto& m) { return m.first == sigma; }))
        continue;
      localization::GlobalLocConfig config = o.config;
      config.sensor.sigma = sigma;
      try {
        maps.emplace_back(sigma, std::make_unique<localization::LocalizationMap>(
                                     map.grid, map.occupied_thresh, map.free_thresh, config));
      } catch (const std::invalid_argument& e) {
        // The options' refusals (a pose cell too fine for the map, a pose grid above
        // --max-memory) name the option; what is left is the map's.
        const std::string_view what = e.what();
        if (what.starts_with("pose_res") || what.starts_with("memory_limit"))
          rethrow_naming_flags(e, global_loc_flags());
        throw io::InputError(o.map, 0, "image", e.what());
      }
    }
  const double map_seconds = std::chrono::duration<double>(Clock::now() - map_start).count() /
                             static_cast<double>(maps.size());
  const auto map_for = [&](const SweepSpec& sweep,
                           double value) -> const localization::LocalizationMap& {
    const double sigma = sigma_at(sweep, value);
    for (const auto& m : maps)
      if (m.first == sigma) return *m.second;
    throw std::logic_error("no localization map for sigma " + std::to_string(sigma));
  };
  const localization::LocalizationMap* lmap =
      &map_for(sweeps.front(), sweeps.front().values.front());
  std::vector<Item> items;
  for (std::size_t s = 0; s < sweeps.size(); ++s)
    for (std::size_t v = 0; v < sweeps[s].values.size(); ++v)
      for (std::size_t t = 0; t < o.trials; ++t) items.push_back({s, v, t});
  std::vector<TrialResult> results(items.size());

  const auto run_item = [&](const Item& item) {
    TrialResult& r = results[&item - items.data()];
    const SweepSpec& s = sweeps[item.sweep];
    const experiments::GlobalTrialConditions c =
        conditions_at(o.conditions, s.sweep, s.values[item.value]);
    simulation::SimRandom pose_random(
        simulation::derive_seed(simulation::derive_seed(o.seed, kPoseStream), item.trial));
    const core::Pose2 truth = world->random_pose(pose_random);
    // The sweep's identity, not its place in the run: --sweeps gives the same trials.
    const std::uint64_t seed = simulation::derive_seed(
        simulation::derive_seed(
            simulation::derive_seed(simulation::derive_seed(o.seed, kSweepStream),
                                    static_cast<std::uint64_t>(s.sweep)),
            item.value),
        item.trial);
    experiments::GlobalTrial trial;
    try {
      trial = experiments::simulate_global_trial(*world, c, truth, seed);
    } catch (const std::invalid_argument& e) {
      r.error = e.what();
      return;
    }
    r.readings = trial.readings.size();
    const localization::LocalizationMap& localization_map = map_for(s, s.values[item.value]);
    const double position_tolerance = 2.0 * o.config.pose_res;
    const double heading_tolerance = 2.0 * 2.0 * std::numbers::pi / o.config.headings;
    for (std::size_t m = 0; m < kMethodCount; ++m) {
      const auto start = Clock::now();
      const localization::GlobalEstimate e = localization::localize_global(
          localization_map, trial.readings, core::Pose2{}, kMethods[m]);
      r.methods[m].seconds = std::chrono::duration<double>(Clock::now() - start).count();
      r.methods[m].error =
          experiments::global_trial_error(truth, e.robot, position_tolerance, heading_tolerance);
    }
  };

  auto threads = static_cast<unsigned>(core::threads_or_every_core(static_cast<int>(o.threads)));
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, items.size()));
  {
    TerminalProgress progress("globloc-sweeps: trials");
    std::mutex progress_mutex;
    std::atomic<std::size_t> next{0}, done{0};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    const auto worker = [&] {
      for (std::size_t i; (i = next.fetch_add(1)) < items.size();) {
        try {
          run_item(items[i]);
        } catch (...) {
          const std::lock_guard lock(failure_mutex);
          if (!failure) failure = std::current_exception();
          next = items.size();
          return;
        }
        const std::size_t d = done.fetch_add(1) + 1;
        const std::lock_guard lock(progress_mutex);
        progress(d, items.size());
      }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
  }

  std::vector<std::vector<Aggregate>> points(sweeps.size());
  std::size_t begin = 0;
  std::array<double, kMethodCount> seconds{};
  std::size_t timed = 0;
  for (std::size_t s = 0; s < sweeps.size(); ++s)
    for (std::size_t v = 0; v < sweeps[s].values.size(); ++v) {
      points[s].push_back(aggregate(results, begin, o.trials));
      const Aggregate& a = points[s].back();
      for (std::size_t m = 0; m < kMethodCount; ++m)
        seconds[m] += a.seconds[m] * static_cast<double>(a.trials);
      timed += a.trials;
      begin += o.trials;
    }
  for (std::size_t s = 0; s < sweeps.size(); ++s)
    write_csv(o.out / ("globloc_" + std::string(sweeps[s].name) + ".csv"), sweeps[s], points[s]);
  io::write_file_atomically(o.out / "globloc_timing.csv", [&](std::ostream& out) {
    out << "method,localizations,mean_ms,pose_cells,candidate_cells,map_seconds,threads\n";
    for (std::size_t m = 0; m < kMethodCount; ++m)
      out << global_method_name(kMethods[m]) << ',' << timed << ','
          << io::printed("%.4f", timed ? 1000.0 * seconds[m] / static_cast<double>(timed) : 0.0)
          << ',' << lmap->pose_cells() << ',' << lmap->candidate_cells() << ','
          << io::printed("%.4f", map_seconds) << ',' << threads << '\n';
  });

  const core::GridGeometry& g = map.grid.geometry;
  const experiments::GlobalTrialConditions& c = o.conditions;
  const std::string title = io::printed(
      "Global localization, %s (%.0f x %.0f m), pose grid %g m x %d headings, %zu "
      "trials a point, seed %llu; success: within %g m and %.3g deg",
      o.map.filename().string().c_str(), g.width * g.resolution, g.height * g.resolution,
      o.config.pose_res, o.config.headings, o.trials, static_cast<unsigned long long>(o.seed),
      2.0 * o.config.pose_res, 2.0 * 360.0 / o.config.headings);
  const bool plotted = write_plots(o, sweeps, points, title);

  std::printf("%s\n", title.c_str());
  std::printf(
      "map %d x %d cells of %g m; pose grid %d x %d x %d headings (%g m, %.2f deg), %zu pose "
      "cells, %zu candidates; map prepared in %.2f s (%zu such)\n",
      g.width, g.height, g.resolution, lmap->width(), lmap->height(), lmap->headings(),
      o.config.pose_res, 360.0 / o.config.headings, lmap->pose_cells(), lmap->candidate_cells(),
      map_seconds, maps.size());
  std::printf(
      "default condition: %zu readings over %.0f deg reaching %g m, noise %g m, no contamination "
      "or obstacle; true poses uniform over free cells %g m from any non-free cell (%zu cells); "
      "the localizers' sigma %g m%s\n",
      c.readings, c.fov * kDeg, c.max_range, c.noise, o.clearance, world->start_cells(),
      o.config.sensor.sigma, o.fixed_sigma ? "" : ", in the noise sweep the sensor's noise");
  std::printf(
      "success: position error <= %g m (2 pose cells) AND heading error <= %.3g deg (2 heading "
      "bins)\n",
      2.0 * o.config.pose_res, 2.0 * 360.0 / o.config.headings);
  for (std::size_t s = 0; s < sweeps.size(); ++s) print_table(sweeps[s], points[s]);
  std::printf("\nmean time per localization (%zu each, %u threads):", timed, threads);
  for (std::size_t m = 0; m < kMethodCount; ++m)
    std::printf(" %s %.1f ms%s", global_method_name(kMethods[m]),
                timed ? 1000.0 * seconds[m] / static_cast<double>(timed) : 0.0,
                m + 1 < kMethodCount ? "," : "\n");
  std::string names;
  for (const SweepSpec& s : sweeps) names += (names.empty() ? "" : ",") + std::string(s.name);
  std::printf("wrote %s/globloc_{%s}.csv, globloc_timing.csv%s\n", o.out.string().c_str(),
              names.c_str(), plotted ? " and a PNG each" : "");
  if (!plotted) figures::print_plots_skipped(o.gnuplot);
  std::printf("wall time %.1f s\n",
              std::chrono::duration<double>(Clock::now() - wall_start).count());
}

void add_globloc_sweeps_figure(CLI::App& figure) {
  auto o = std::make_shared<GlobLocSweepOptions>();
  CLI::App* cmd = figure.add_subcommand(
      "globloc-sweeps", "thesis 4.5: global localization's success against simulated conditions");
  cmd->footer(
      "Success rate and errors of global localization (pose occupancy grid, Markov, mixture, "
      "likelihood field) against readings, noise, contamination and unmodelled obstacles, "
      "simulated on --map (the map is also the world): DIR/globloc_*.csv, one gnuplot plot a "
      "sweep, globloc_timing.csv, a table. The simulated LiDAR: --beams, --noise, --fov, "
      "--sensor-range; the localizers: --pose-cell, --headings, --sigma, --max-range, --levels, "
      "--veto-levels.");
  cmd->add_option("--map", o->map, "the map, also the simulated world (ROS map_server YAML)")
      ->required();
  cmd->add_option("--out", o->out, "output folder")->capture_default_str();
  cmd->add_option("--trials", o->trials, "random true poses per sweep point")
      ->transform(whole_range(1, 1'000'000))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed of the true poses, obstacles and readings")
      ->transform(seed_number())
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "worker threads (0: every core)")
      ->transform(whole_range(0, 1024))
      ->capture_default_str();
  cmd->add_flag("--quick", o->quick, "two points a sweep (for tests)");
  const std::vector<std::string> sweeps = {"readings", "noise", "contamination", "obstacles",
                                           "large_obstacle"};
  cmd->add_option("--sweeps", o->only, "run only these sweeps, comma-separated (default: all)")
      ->delimiter(',')
      ->transform(one_of(sweeps))
      ->type_name(choice_names(sweeps, "|"));
  cmd->add_option("--gnuplot", o->gnuplot, "the gnuplot program")->capture_default_str();
  add_global_loc_options(*cmd, o->config);
  cmd->add_option("--beams,--readings", o->conditions.readings,
                  "beams of the simulated LiDAR (readings a scan), default condition")
      ->transform(whole_range(1, 100'000))
      ->capture_default_str();
  cmd->add_option("--noise", o->conditions.noise, "sensor noise (m), default condition")
      ->check(non_negative())
      ->capture_default_str();
  cmd->add_option_function<double>(
         "--fov", [o](double deg) { o->conditions.fov = deg * std::numbers::pi / 180.0; },
         "the simulated LiDAR's field of view (degrees, default 360)")
      ->check(real_range(1.0, 360.0));
  cmd->add_option("--sensor-range", o->conditions.max_range,
                  "the simulated LiDAR's range (m); the localizers' is --max-range")
      ->check(positive())
      ->capture_default_str();
  cmd->add_option("--clearance", o->clearance,
                  "true positions at least this far from the map's non-free cells (m)")
      ->check(non_negative())
      ->capture_default_str();
  cmd->add_flag(
      "--fixed-sigma", o->fixed_sigma,
      "keep the localizers' --sigma in the noise sweep too (default: the sensor's noise)");
  cmd->callback([o] { run_globloc_sweeps(*o); });
}

}  // namespace intgrid::cli
