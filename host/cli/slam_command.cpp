// `intgrid slam`: SLAM on a log, by the submap SLAM with loop closure (--engine submaps, the
// default) or the thesis's event-driven grid SLAM (--engine grid).
#include <cstddef>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
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
                                   {"sensor.sigma", "--sigma"},
                                   {"beam.likelihood_floor", "--floor"},
                                   {"beam.beams", "--beams"},
                                   {"beam.tempering", "--tempering"},
                                   {"sensor.max_range", "--max-range"},
                                   {"motion", "--motion-noise"},
                                   {"window.cells", "--window-cells"},
                                   {"window.headings", "--window-headings"},
                                   {"window.pose_cutoff", "--pose-cutoff"},
                                   {"window.pose_prune", "--pose-prune"},
                                   {"map.empty_divisor", "--empty-divisor"}};
  return flags;
}

void check_slam_options(const slam::GridSlamConfig& c) {
  naming_flags(slam_flags(), [&] { slam::check_grid_slam_config(c); });
}

const FieldFlags& submap_slam_flags() {
  static const FieldFlags flags = {
      {"cell", "--cell"},
      {"headings", "--headings"},
      {"sensor.sigma", "--sigma"},
      {"sensor.max_range", "--max-range"},
      {"map.seps_bits", "--bits"},
      {"map.seps_levels", "--levels"},
      {"map.empty_divisor", "--empty-divisor"},
      {"submaps.scans", "--submap-scans"},
      {"submaps.handover_scans", "--submap-handover"},
      {"filter.distance", "--filter-distance"},
      {"filter.degrees", "--filter-degrees"},
      {"filter.seconds", "--filter-seconds"},
      {"tracking.window", "--tracking-window"},
      {"tracking.window_degrees", "--tracking-degrees"},
      {"tracking.wide_below", "--wide-below"},
      {"tracking.wide_window", "--wide-window"},
      {"tracking.wide_degrees", "--wide-degrees"},
      {"tracking.prior_xy", "--prior-xy"},
      {"tracking.prior_xy_per_m", "--prior-xy-per-m"},
      {"tracking.prior_degrees", "--prior-degrees"},
      {"tracking.prior_degrees_per_degree", "--prior-degrees-per-degree"},
      {"tracking.min_hits", "--min-hits"},
      {"loops.every", "--loop-every"},
      {"loops.max_distance", "--loop-distance"},
      {"loops.submaps", "--loop-submaps"},
      {"loops.window", "--loop-window"},
      {"loops.window_degrees", "--loop-degrees"},
      {"loops.min_score", "--loop-min-score"},
      {"loops.drift", "--loop-drift"},
      {"loops.switch_off", "--loop-switch-off"},
      {"loops.sigma_xy", "--loop-sigma-xy"},
      {"loops.sigma_degrees", "--loop-sigma-degrees"},
      {"graph.local_sigma_xy", "--local-sigma-xy"},
      {"graph.local_sigma_degrees", "--local-sigma-degrees"},
      {"graph.odometry_sigma_xy", "--odometry-sigma-xy"},
      {"graph.odometry_sigma_degrees", "--odometry-sigma-degrees"},
      {"graph.optimize_every", "--optimize-every"},
      {"graph.iterations", "--graph-iterations"},
      {"graph.huber", "--huber"}};
  return flags;
}

void check_submap_slam_options(const slam::SubmapSlamConfig& c) {
  naming_flags(submap_slam_flags(), [&] { slam::check_submap_slam_config(c); });
}

namespace {

// The settings both engines have, with one meaning and each engine its own default, under the
// member paths of GridSlamConfig and SubmapSlamConfig: each set only if given.
struct SharedSlamSettings {
  std::optional<double> cell;
  std::optional<int> headings;
  struct {
    std::optional<double> sigma, max_range;
  } sensor;
  struct {
    std::optional<int> empty_divisor;
  } map;
};

// The options of those settings, bound to `s`: an engine's config, or SharedSlamSettings.
template <class Settings>
std::vector<CLI::Option*> add_shared_slam_options(CLI::App& cmd, Settings& s) {
  return {
      cmd.add_option("--cell,--res", s.cell,
                     "map cell (m, whole millimetres; the grid engine's pose-grid step too)")
          ->check(positive()),
      cmd.add_option("--empty-divisor", s.map.empty_divisor,
                     "a reading's empty evidence is divided by this before it is fused")
          ->transform(whole_range(1, 127)),
      cmd.add_option("--headings", s.headings, "heading steps per turn (a power of two)")
          ->transform(whole_range(8, 65536)),
      cmd.add_option("--sigma", s.sensor.sigma, "range noise of the beam model (m)")
          ->check(positive()),
      cmd.add_option("--max-range", s.sensor.max_range, "readings at or past this are not used (m)")
          ->check(positive())};
}

// Each engine's defaults of those settings, in the options' order.
template <class Config>
std::vector<std::string> shared_slam_defaults(const Config& c) {
  return {option_number(c.cell), std::to_string(c.map.empty_divisor), std::to_string(c.headings),
          option_number(c.sensor.sigma), option_number(c.sensor.max_range)};
}

// The given ones into the config of the engine that runs.
template <class Config>
void apply_shared_slam_settings(const SharedSlamSettings& s, Config& c) {
  if (s.cell) c.cell = *s.cell;
  if (s.headings) c.headings = *s.headings;
  if (s.sensor.sigma) c.sensor.sigma = *s.sensor.sigma;
  if (s.sensor.max_range) c.sensor.max_range = *s.sensor.max_range;
  if (s.map.empty_divisor) c.map.empty_divisor = *s.map.empty_divisor;
}

// The grid engine's own options.
void add_grid_slam_options(CLI::App& cmd, slam::GridSlamConfig& c) {
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
  cmd.add_option("--window-cells", c.window.cells, "pose-grid cells per side in x and y (odd)")
      ->transform(whole_range(1, 255))
      ->capture_default_str();
  cmd.add_option("--window-headings", c.window.headings, "pose-grid heading bins (odd)")
      ->transform(whole_range(1, 255))
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

}  // namespace

void add_slam_options(CLI::App& cmd, slam::GridSlamConfig& c) {
  for (CLI::Option* opt : add_shared_slam_options(cmd, c)) opt->capture_default_str();
  add_grid_slam_options(cmd, c);
}

namespace {

const char* const kBothGroup = "Both engines (each with its own default)";
const char* const kGridGroup = "The grid engine (--engine grid)";

// The submaps engine's own options, grouped by concern; returns them.
std::vector<CLI::Option*> add_submap_options(CLI::App& cmd, slam::SubmapSlamConfig& c) {
  std::vector<CLI::Option*> added;
  std::string group;
  const auto add = [&](const std::string& name, auto& field, const std::string& help,
                       const CLI::Validator& validator) {
    CLI::Option* opt = cmd.add_option(name, field, help)->capture_default_str()->group(group);
    if constexpr (std::is_integral_v<std::remove_reference_t<decltype(field)>>)
      opt->transform(validator);
    else
      opt->check(validator);
    added.push_back(opt);
  };
  group = "Submaps engine: the submaps' S_eps grids";
  add("--submap-scans", c.submaps.scans,
      "nodes a submap takes before the next starts (each ends with twice as many)",
      whole_at_least(1));
  added.push_back(cmd.add_option("--submap-rematch", c.submaps.rematch,
                                 "once a submap is complete, match its first --submap-scans nodes "
                                 "again against it (true|false)")
                      ->capture_default_str()
                      ->group(group));
  add("--submap-handover", c.submaps.handover_scans,
      "nodes the newer submap must hold before it can take over as the target from an older one "
      "the scans have moved on from (0: never)",
      whole_at_least(0));
  add("--bits,--seps-bits", c.map.seps_bits, "S_eps index width of the submaps' cells",
      whole_at_least(1));
  add("--levels,--seps-levels", c.map.seps_levels, "one reading's strongest occupied index",
      whole_at_least(1));
  group = "Submaps engine: motion filter (a scan becomes a node once the pose moved this far)";
  add("--filter-distance", c.filter.distance, "metres since the last node", non_negative());
  add("--filter-degrees", c.filter.degrees, "degrees since the last node", non_negative());
  add("--filter-seconds", c.filter.seconds, "seconds since the last node", non_negative());
  group = "Submaps engine: tracking (every scan matched against its submap)";
  add("--tracking-window", c.tracking.window, "translations searched: +- this (m)", non_negative());
  add("--tracking-degrees", c.tracking.window_degrees, "headings searched: +- this (degrees)",
      non_negative());
  add("--wide-below", c.tracking.wide_below,
      "a match scoring under this fraction of the best possible is searched again in the wide "
      "window",
      probability());
  add("--wide-window", c.tracking.wide_window, "the wide window's translations: +- this (m)",
      non_negative());
  add("--wide-degrees", c.tracking.wide_degrees, "the wide window's headings: +- this (degrees)",
      non_negative());
  add("--prior-xy", c.tracking.prior_xy,
      "moving this far from the odometry costs the full score (m; 0: no prior)", non_negative());
  add("--prior-xy-per-m", c.tracking.prior_xy_per_m,
      "--prior-xy grows by this many metres per metre of odometry translation", non_negative());
  add("--prior-degrees", c.tracking.prior_degrees,
      "turning this far from the odometry costs the full score (degrees; 0: no prior)",
      non_negative());
  add("--prior-degrees-per-degree", c.tracking.prior_degrees_per_degree,
      "--prior-degrees grows by this many degrees per degree of odometry rotation", non_negative());
  add("--min-hits", c.tracking.min_hits, "scans with fewer hits follow the odometry",
      whole_at_least(1));
  group = "Submaps engine: loop closure (nodes matched against finished submaps)";
  add("--loop-every", c.loops.every, "a search every this many nodes", whole_at_least(1));
  add("--loop-distance", c.loops.max_distance,
      "submaps whose middle node lies this near the node's estimate are candidates (m)",
      non_negative());
  add("--loop-submaps", c.loops.submaps, "of the candidates, the nearest this many are searched",
      whole_at_least(1));
  add("--loop-window", c.loops.window,
      "translations searched: at most +- this around the estimate (m); less where the drift check "
      "reaches less",
      non_negative());
  add("--loop-degrees", c.loops.window_degrees, "headings searched: +- this (degrees)",
      non_negative());
  add("--loop-min-score", c.loops.min_score,
      "a closure scores at least this fraction of what the submap's own scans score in it",
      real_range(0, 1, true));
  add("--loop-drift", c.loops.drift,
      "a closure moves a node at most the tracking window plus this many m per m travelled since "
      "the trajectory last met the submap",
      real_range(0, 1, false));
  add("--loop-switch-off", c.loops.switch_off,
      "after each optimization a closure off by more than this many of its sigmas is switched "
      "off (and on again once back within)",
      positive());
  add("--loop-sigma-xy", c.loops.sigma_xy, "a closure's spread in the graph (m)", positive());
  add("--loop-sigma-degrees", c.loops.sigma_degrees, "a closure's spread in the graph (degrees)",
      positive());
  group = "Submaps engine: pose graph";
  add("--local-sigma-xy", c.graph.local_sigma_xy, "a node's spread in its submaps (m)", positive());
  add("--local-sigma-degrees", c.graph.local_sigma_degrees,
      "a node's spread in its submaps (degrees)", positive());
  add("--odometry-sigma-xy", c.graph.odometry_sigma_xy, "one node to the next: spread (m)",
      positive());
  add("--odometry-sigma-degrees", c.graph.odometry_sigma_degrees,
      "one node to the next: spread (degrees)", positive());
  add("--optimize-every", c.graph.optimize_every,
      "nodes between optimizations that have new loop closures", whole_at_least(1));
  add("--graph-iterations", c.graph.iterations, "iterations of an optimization", whole_at_least(1));
  add("--huber", c.graph.huber, "the robust loss's Huber width (sigmas)", positive());
  group = "Submaps engine: threads";
  add("--threads", c.threads,
      "threads the loop-closure searches, a finished submap's matches and each scan's match run "
      "on (0: every core); the same result for any count",
      whole_range(0, 256));
  return added;
}

// OptionError for the first option of `others` that was given: it belongs to the other engine.
void refuse_other_engine(const std::vector<CLI::Option*>& others, const char* other,
                         const SlamJobOptions& o, bool engine_given) {
  for (const CLI::Option* opt : others)
    if (opt->count() > 0)
      bad_option(opt->get_name(), std::string("a setting of --engine ") + other +
                                      ", not of --engine " + engine_name(o.engine) +
                                      (engine_given ? "" : " (the default)"));
}

}  // namespace

void add_slam_command(CLI::App& app) {
  auto o = std::make_shared<SlamJobOptions>();
  CLI::App* cmd = app.add_subcommand(
      "slam", "SLAM on a log: submaps with loop closure, or the event-driven grid SLAM");
  cmd->add_option("--log", o->log, "log file (project format or CARMEN)")->required();
  cmd->add_option("--out", o->out,
                  "output folder: trajectory.txt, map.yaml, map.pgm, map.png, metrics.json")
      ->required();
  cmd->add_option("--reference", o->reference,
                  "reference log: adds the trajectory error (ATE) to metrics.json");
  cmd->add_option("--relations", o->relations,
                  "benchmark relations file (t1 t2 x y z roll pitch yaw a line): scores the SLAM "
                  "and the raw odometry, in metrics.json and one line each on stderr");
  cmd->add_option("--tum", o->tum, "also write the SLAM trajectory here in the TUM format");
  add_max_memory_option(*cmd, o->max_memory_bytes);
  add_arithmetic_option(*cmd, o->arithmetic,
                        "int: S_eps indices (and the grid engine's U_gamma); float: double")
      ->default_str("int");
  CLI::Option* engine =
      add_choice_option(*cmd, "--engine", o->engine,
                        {{"submaps", SlamEngine::submaps}, {"grid", SlamEngine::grid}},
                        "submaps: submap SLAM with loop closure; grid: the event-driven grid "
                        "SLAM (thesis chapter 3)")
          ->default_str(engine_name(o->engine));

  auto shared = std::make_shared<SharedSlamSettings>();
  const std::vector<CLI::Option*> shared_options = add_shared_slam_options(*cmd, *shared);
  const std::vector<std::string> submaps_defaults = shared_slam_defaults(o->submap_config),
                                 grid_defaults = shared_slam_defaults(o->grid_config);
  for (std::size_t i = 0; i < shared_options.size(); ++i)
    shared_options[i]
        ->description(shared_options[i]->get_description() + " (default: submaps " +
                      submaps_defaults[i] + ", grid " + grid_defaults[i] + ")")
        ->group(kBothGroup);
  const std::size_t before = cmd->get_options().size();
  add_grid_slam_options(*cmd, o->grid_config);
  std::vector<CLI::Option*> grid_only = cmd->get_options();
  grid_only.erase(grid_only.begin(), grid_only.begin() + static_cast<std::ptrdiff_t>(before));
  for (CLI::Option* opt : grid_only) opt->group(kGridGroup);
  o->submap_config.threads = 0;  // the command uses every core unless told otherwise
  const std::vector<CLI::Option*> submaps_only = add_submap_options(*cmd, o->submap_config);

  cmd->callback([o, engine, shared, grid_only, submaps_only] {
    const bool engine_given = engine->count() > 0;
    if (o->engine == SlamEngine::grid) {
      refuse_other_engine(submaps_only, "submaps", *o, engine_given);
      apply_shared_slam_settings(*shared, o->grid_config);
    } else {
      refuse_other_engine(grid_only, "grid", *o, engine_given);
      apply_shared_slam_settings(*shared, o->submap_config);
    }
    const SlamJobResult r = run_slam_job(*o);
    print_json(r.metrics);
    // The summaries go to stderr, so that stdout stays one JSON document.
    std::fprintf(stderr, "slam (%s): %s\n", engine_name(r.engine), slam_summary(r).c_str());
    if (r.relations) {
      std::fprintf(stderr, "%s\n", relation_summary("relations", *r.relations).c_str());
      std::fprintf(stderr, "%s\n",
                   relation_summary("odometry relations", *r.odometry_relations).c_str());
    }
  });
}

}  // namespace intgrid::cli
