// The SLAMs in Python, scan by scan.
#include "bindings.hpp"

namespace intgrid::python {
namespace {

// Poses with times as an (n, 4) array: t, x, y, theta.
py::array_t<double> timed_poses_to_numpy(const std::vector<slam::TimedPose>& poses) {
  py::array_t<double> out(std::vector<py::ssize_t>{static_cast<py::ssize_t>(poses.size()), 4});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const auto r = static_cast<py::ssize_t>(i);
    a(r, 0) = poses[i].t;
    a(r, 1) = poses[i].pose.x;
    a(r, 2) = poses[i].pose.y;
    a(r, 3) = poses[i].pose.theta;
  }
  return out;
}

std::vector<slam::TimedPose> timed_poses_of(const py::object& poses) {
  if (py::isinstance<core::Log>(poses)) return slam::scan_poses(poses.cast<const core::Log&>());
  const auto a = CArray<double>::ensure(poses);
  if (!a) throw py::type_error("poses: expected an (n, 4) array of t, x, y, theta or a Log");
  if (a.ndim() != 2 || a.shape(1) != 4)
    value_error("poses: expected an (n, 4) array of t, x, y, theta or a Log");
  std::vector<slam::TimedPose> out(static_cast<std::size_t>(a.shape(0)));
  const auto v = a.unchecked<2>();
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto r = static_cast<py::ssize_t>(i);
    out[i] = {v(r, 0), {v(r, 1), v(r, 2), v(r, 3)}};
  }
  return out;
}

py::tuple grid_tuple(const core::Grid<std::int8_t>& grid) {
  return py::make_tuple(to_numpy(grid), grid.geometry);
}
py::tuple grid_tuple(const core::ProbabilityGrid& grid) {
  return py::make_tuple(to_numpy(grid), grid.geometry);
}

// The submaps engine, the `slam` command's default (SubmapSlamConfig's groups as nested classes).
void bind_submap_slam(py::module_& m) {
  using slam::SubmapSlamConfig;
  py::class_<SubmapSlamConfig> config(
      m, "SubmapSlamConfig",
      "Options of a run of the submaps SLAM (the `slam` command's default engine), nested by "
      "concern. SubmapSlamConfig(cell=0.05, ...) sets top-level fields; nested ones are set in "
      "place: config.loops.min_score = 0.7.");
  def_fields_init<SubmapSlamConfig>(config);

  py::class_<SubmapSlamConfig::Map> map(config, "Map", "The submaps' S_eps grids.");
  def_fields_init<SubmapSlamConfig::Map>(map);
  map.def_readwrite("seps_bits", &SubmapSlamConfig::Map::seps_bits)
      .def_readwrite("seps_levels", &SubmapSlamConfig::Map::seps_levels)
      .def_readwrite("empty_divisor", &SubmapSlamConfig::Map::empty_divisor);

  py::class_<SubmapSlamConfig::Submaps> submaps(config, "Submaps", "How submaps grow.");
  def_fields_init<SubmapSlamConfig::Submaps>(submaps);
  submaps
      .def_readwrite("scans", &SubmapSlamConfig::Submaps::scans,
                     "nodes a submap takes before the next starts")
      .def_readwrite("rematch", &SubmapSlamConfig::Submaps::rematch,
                     "once complete, match its first `scans` nodes again against it")
      .def_readwrite("handover_scans", &SubmapSlamConfig::Submaps::handover_scans,
                     "nodes the newer submap must hold before it can take over as the target "
                     "(0: never)");

  py::class_<SubmapSlamConfig::MotionFilter> filter(
      config, "MotionFilter", "A scan becomes a node once the pose moved this far.");
  def_fields_init<SubmapSlamConfig::MotionFilter>(filter);
  filter.def_readwrite("distance", &SubmapSlamConfig::MotionFilter::distance, "m")
      .def_readwrite("degrees", &SubmapSlamConfig::MotionFilter::degrees)
      .def_readwrite("seconds", &SubmapSlamConfig::MotionFilter::seconds);

  using Tracking = SubmapSlamConfig::Tracking;
  py::class_<Tracking> tracking(config, "Tracking", "Scan-to-submap matching of every scan.");
  def_fields_init<Tracking>(tracking);
  tracking.def_readwrite("window", &Tracking::window, "m")
      .def_readwrite("window_degrees", &Tracking::window_degrees)
      .def_readwrite("wide_below", &Tracking::wide_below)
      .def_readwrite("wide_window", &Tracking::wide_window, "m")
      .def_readwrite("wide_degrees", &Tracking::wide_degrees)
      .def_readwrite("prior_xy", &Tracking::prior_xy, "m")
      .def_readwrite("prior_xy_per_m", &Tracking::prior_xy_per_m)
      .def_readwrite("prior_degrees", &Tracking::prior_degrees)
      .def_readwrite("prior_degrees_per_degree", &Tracking::prior_degrees_per_degree)
      .def_readwrite("min_hits", &Tracking::min_hits);

  using LoopClosure = SubmapSlamConfig::LoopClosure;
  py::class_<LoopClosure> loops(config, "LoopClosure",
                                "Matching of nodes against finished submaps.");
  def_fields_init<LoopClosure>(loops);
  loops.def_readwrite("every", &LoopClosure::every)
      .def_readwrite("max_distance", &LoopClosure::max_distance, "m")
      .def_readwrite("submaps", &LoopClosure::submaps)
      .def_readwrite("window", &LoopClosure::window, "m")
      .def_readwrite("window_degrees", &LoopClosure::window_degrees)
      .def_readwrite("min_score", &LoopClosure::min_score)
      .def_readwrite("drift", &LoopClosure::drift, "m per m")
      .def_readwrite("sigma_xy", &LoopClosure::sigma_xy, "m")
      .def_readwrite("sigma_degrees", &LoopClosure::sigma_degrees)
      .def_readwrite("switch_off", &LoopClosure::switch_off, "sigmas");

  using Graph = SubmapSlamConfig::Graph;
  py::class_<Graph> graph(config, "Graph", "The pose graph.");
  def_fields_init<Graph>(graph);
  graph.def_readwrite("local_sigma_xy", &Graph::local_sigma_xy, "m")
      .def_readwrite("local_sigma_degrees", &Graph::local_sigma_degrees)
      .def_readwrite("odometry_sigma_xy", &Graph::odometry_sigma_xy, "m")
      .def_readwrite("odometry_sigma_degrees", &Graph::odometry_sigma_degrees)
      .def_readwrite("optimize_every", &Graph::optimize_every)
      .def_readwrite("iterations", &Graph::iterations)
      .def_readwrite("huber", &Graph::huber, "sigmas");

  config.def_readwrite("cell", &SubmapSlamConfig::cell, "submap cell (m)")
      .def_readwrite("headings", &SubmapSlamConfig::headings,
                     "heading steps per turn of the match lattice")
      .def_readwrite("threads", &SubmapSlamConfig::threads,
                     "threads of the searches, both ends (0: every core); the same result")
      .def_readwrite("sensor", &SubmapSlamConfig::sensor, "a RangeSensor")
      .def_readwrite("map", &SubmapSlamConfig::map)
      .def_readwrite("submaps", &SubmapSlamConfig::submaps)
      .def_readwrite("filter", &SubmapSlamConfig::filter)
      .def_readwrite("tracking", &SubmapSlamConfig::tracking)
      .def_readwrite("loops", &SubmapSlamConfig::loops)
      .def_readwrite("graph", &SubmapSlamConfig::graph)
      .def("check", &slam::check_submap_slam_config, "Raises ValueError naming a bad field.");

  using slam::SubmapSlamStats;
  py::class_<SubmapSlamStats>(m, "SubmapSlamStats", "What a submaps SLAM run did.")
      .def_readonly("scans", &SubmapSlamStats::scans)
      .def_readonly("nodes", &SubmapSlamStats::nodes)
      .def_readonly("submaps", &SubmapSlamStats::submaps)
      .def_readonly("wide_searches", &SubmapSlamStats::wide_searches)
      .def_readonly("handovers", &SubmapSlamStats::handovers)
      .def_readonly("unmatched_scans", &SubmapSlamStats::unmatched_scans)
      .def_readonly("loop_searches", &SubmapSlamStats::loop_searches)
      .def_readonly("loop_closures", &SubmapSlamStats::loop_closures)
      .def_readonly("rejected_closures", &SubmapSlamStats::rejected_closures)
      .def_readonly("switched_off_closures", &SubmapSlamStats::switched_off_closures)
      .def_readonly("optimizations", &SubmapSlamStats::optimizations)
      .def_readonly("readings", &SubmapSlamStats::readings)
      .def_readonly("unusable_readings", &SubmapSlamStats::unusable_readings)
      .def_readonly("peak_pyramid_bytes", &SubmapSlamStats::peak_pyramid_bytes)
      .def("__repr__", [](const py::object& self) { return fields_repr(self); });

  using slam::SubmapSlam;
  py::class_<SubmapSlam>(m, "SubmapSlam",
                         "The submaps SLAM scan by scan; the first scan's robot pose is the SLAM "
                         "frame. Call finish() after the last scan.")
      .def(py::init([](const SubmapSlamConfig& cfg, const py::object& arithmetic,
                       const core::Scan& first) {
             const core::Arithmetic a = arithmetic_of(arithmetic);
             py::gil_scoped_release release;
             return std::make_unique<SubmapSlam>(cfg, a, first);
           }),
           "config"_a, "arithmetic"_a, "first"_a)
      .def("insert", &SubmapSlam::insert, py::call_guard<py::gil_scoped_release>(),
           "The next scan (the first one included).", "scan"_a)
      .def("finish", &SubmapSlam::finish, py::call_guard<py::gil_scoped_release>(),
           "Optimizes the graph once more with every closure found.")
      .def("pose", &SubmapSlam::pose, "The last scan's pose, in the log's frame.")
      .def(
          "trajectory", [](const SubmapSlam& s) { return timed_poses_to_numpy(s.trajectory()); },
          "(n, 4) array: t, x, y, theta of every scan so far, as the graph now places them.")
      .def("frame", &SubmapSlam::frame, "The SLAM frame in the log's frame.")
      .def(
          "map", [](const SubmapSlam& s) { return grid_tuple(s.map()); },
          "(S_eps int8 array (height, width), row 0 = bottom; GridGeometry), every node at its "
          "optimized pose, in the SLAM frame.")
      .def("codec", &SubmapSlam::codec, "The map's SepsCodec.")
      .def("stats", &SubmapSlam::stats, "SubmapSlamStats so far.");

  py::class_<slam::MapFix>(m, "MapFix", "One scan's estimate in a known map (MapLocalizer).")
      .def_readonly("pose", &slam::MapFix::pose, "The robot's pose, in the map's frame.")
      .def_readonly("matched", &slam::MapFix::matched, "The scan had enough hits and was matched.")
      .def_readonly("wide", &slam::MapFix::wide, "The wide window was searched.")
      .def_readonly("evidence", &slam::MapFix::evidence,
                    "The narrow match's hits' sum, a share of every hit on the strongest cell.")
      .def_readonly("hits", &slam::MapFix::hits, "The scan's hits at pose.")
      .def_readonly("fit", &slam::MapFix::fit,
                    "The share of the hits within a cell of an occupied map cell at pose.")
      .def("__repr__", [](const py::object& self) { return fields_repr(self); });

  py::class_<slam::MapLocalizer>(
      m, "MapLocalizer",
      "Localization scan after scan in a known map: the submaps SLAM's localization event "
      "against the map, from a given pose at the first scan; no mapping, no loop closure.")
      .def(py::init([](const SubmapSlamConfig& cfg, const py::object& arithmetic,
                       const core::ProbabilityGrid& known, const core::Pose2& initial) {
             const core::Arithmetic a = arithmetic_of(arithmetic);
             py::gil_scoped_release release;
             return std::make_unique<slam::MapLocalizer>(cfg, a, slam::map_indices(known, cfg),
                                                         initial);
           }),
           "config"_a, "arithmetic"_a, "map"_a, "initial"_a,
           "map: a ProbabilityGrid in cells of config.cell (a RosMap's grid); initial: the robot's "
           "pose in the map's frame at the first scan localize takes.")
      .def("localize", &slam::MapLocalizer::localize, py::call_guard<py::gil_scoped_release>(),
           "The next scan's MapFix.", "scan"_a);

  m.def(
      "run_submap_slam",
      [](const core::Log& log, const SubmapSlamConfig& cfg, const py::object& arithmetic) {
        const core::Arithmetic a = arithmetic_of(arithmetic);
        SubmapSlamStats stats;
        slam::SlamRun run;
        {
          py::gil_scoped_release release;
          run = slam::run_submap_slam(log, cfg, a, &stats);
        }
        return py::make_tuple(std::move(run), stats);
      },
      "The submaps SLAM (the `slam` command's default) over a whole log ('int': S_eps submaps, "
      "or 'float'): (SlamRun, SubmapSlamStats).",
      "log"_a, "config"_a = SubmapSlamConfig{}, "arithmetic"_a = "int");
}

}  // namespace

void bind_slam(py::module_& m) {
  using slam::GridSlamConfig;
  py::class_<GridSlamConfig> config(
      m, "GridSlamConfig",
      "Options of a SLAM run, nested by concern (the `slam` defaults). "
      "GridSlamConfig(cell=0.1, ...) sets top-level fields; nested ones are "
      "set in place: config.sensor.sigma = 0.03.");
  def_fields_init<GridSlamConfig>(config);

  py::class_<GridSlamConfig::Schedule> schedule(config, "Schedule",
                                                "Localization every lambda_-th scan, mapping every "
                                                "xi-th.");
  def_fields_init<GridSlamConfig::Schedule>(schedule);
  schedule.def_readwrite("lambda_", &GridSlamConfig::Schedule::lambda, "C++ `lambda`")
      .def_readwrite("xi", &GridSlamConfig::Schedule::xi);

  py::class_<GridSlamConfig::BeamModel> beam(config, "BeamModel",
                                             "The localization event's beam model.");
  def_fields_init<GridSlamConfig::BeamModel>(beam);
  beam.def_readwrite("likelihood_floor", &GridSlamConfig::BeamModel::likelihood_floor)
      .def_readwrite("beams", &GridSlamConfig::BeamModel::beams)
      .def_readwrite("tempering", &GridSlamConfig::BeamModel::tempering);

  py::class_<GridSlamConfig::MotionModel> motion(config, "MotionModel",
                                                 "sigma_xy = xy0 + xy_per_m |t| + xy_per_rad |r|, "
                                                 "sigma_theta alike.");
  def_fields_init<GridSlamConfig::MotionModel>(motion);
  motion.def_readwrite("xy0", &GridSlamConfig::MotionModel::xy0)
      .def_readwrite("xy_per_m", &GridSlamConfig::MotionModel::xy_per_m)
      .def_readwrite("xy_per_rad", &GridSlamConfig::MotionModel::xy_per_rad)
      .def_readwrite("theta0", &GridSlamConfig::MotionModel::theta0)
      .def_readwrite("theta_per_m", &GridSlamConfig::MotionModel::theta_per_m)
      .def_readwrite("theta_per_rad", &GridSlamConfig::MotionModel::theta_per_rad);

  py::class_<GridSlamConfig::PoseWindow> window(config, "PoseWindow",
                                                "The pose grid's window of hypotheses.");
  def_fields_init<GridSlamConfig::PoseWindow>(window);
  window.def_readwrite("cells", &GridSlamConfig::PoseWindow::cells, "per side in x and y (odd)")
      .def_readwrite("headings", &GridSlamConfig::PoseWindow::headings, "heading bins (odd)")
      .def_readwrite("pose_cutoff", &GridSlamConfig::PoseWindow::pose_cutoff)
      .def_readwrite("pose_prune", &GridSlamConfig::PoseWindow::pose_prune);

  py::class_<GridSlamConfig::Map> map(config, "Map", "The S_eps map M.");
  def_fields_init<GridSlamConfig::Map>(map);
  map.def_readwrite("seps_bits", &GridSlamConfig::Map::seps_bits)
      .def_readwrite("seps_levels", &GridSlamConfig::Map::seps_levels)
      .def_readwrite("empty_divisor", &GridSlamConfig::Map::empty_divisor)
      .def_readwrite("margin", &GridSlamConfig::Map::margin, "m");

  py::class_<GridSlamConfig::UGammaOptions> ugamma(config, "UGammaOptions",
                                                   "U_gamma indices of the integer pose grid.");
  def_fields_init<GridSlamConfig::UGammaOptions>(ugamma);
  ugamma.def_readwrite("bits", &GridSlamConfig::UGammaOptions::bits)
      .def_readwrite("steps_per_halving", &GridSlamConfig::UGammaOptions::steps_per_halving);

  config.def_readwrite("cell", &GridSlamConfig::cell, "map cell and pose-grid step (m)")
      .def_readwrite("headings", &GridSlamConfig::headings, "heading bins per turn (power of two)")
      .def_readwrite("schedule", &GridSlamConfig::schedule)
      .def_readwrite("sensor", &GridSlamConfig::sensor, "a RangeSensor")
      .def_readwrite("beam", &GridSlamConfig::beam)
      .def_readwrite("motion", &GridSlamConfig::motion)
      .def_readwrite("window", &GridSlamConfig::window)
      .def_readwrite("map", &GridSlamConfig::map)
      .def_readwrite("ugamma", &GridSlamConfig::ugamma)
      .def("check", &slam::check_grid_slam_config, "Raises ValueError naming a bad field.");

  m.def(
      "odometry_reach",
      [](const std::vector<core::Scan>& scans) { return slam::odometry_reach(scans); },
      "The farthest robot pose of the scans from the first one's (m): the reach_m of "
      "run_grid_slam.",
      "scans"_a);

  using slam::GridSlam;
  py::class_<GridSlam>(m, "GridSlam",
                       "SLAM scan by scan. The map is sized for odometry within reach_m of the "
                       "first scan's robot pose, which is the SLAM frame.")
      .def(py::init([](const GridSlamConfig& cfg, const py::object& arithmetic,
                       const core::Scan& first, double reach_m) {
             const core::Arithmetic a = arithmetic_of(arithmetic);
             py::gil_scoped_release release;
             return std::make_unique<GridSlam>(cfg, a, first, reach_m);
           }),
           "config"_a, "arithmetic"_a, "first"_a, "reach_m"_a)
      .def("insert", &GridSlam::insert, py::call_guard<py::gil_scoped_release>(),
           "The next scan (the first one included): motion, then localization and mapping.",
           "scan"_a)
      .def("pose", &GridSlam::pose, "The estimate (mean of the pose grid) in the log's frame.")
      .def("sigma", &GridSlam::sigma, "Its positional standard deviation (m).")
      .def("frame", &GridSlam::frame, "The SLAM frame in the log's frame.")
      .def(
          "map", [](const GridSlam& s) { return grid_tuple(s.map()); },
          "(S_eps int8 array (height, width), row 0 = bottom; GridGeometry), in the SLAM frame.")
      .def("codec", &GridSlam::codec, "The map's SepsCodec.")
      .def(
          "map_probabilities", [](const GridSlam& s) { return grid_tuple(s.map_probabilities()); },
          "(P(occupied) float64 array, GridGeometry) on an axis-aligned grid of the log's frame.")
      .def_property_readonly("scans", &GridSlam::scans)
      .def_property_readonly("localizations", &GridSlam::localizations)
      .def_property_readonly("mappings", &GridSlam::mappings)
      .def_property_readonly("skipped_scans", &GridSlam::skipped_scans)
      .def_property_readonly("readings", &GridSlam::readings)
      .def_property_readonly("unusable_readings", &GridSlam::unusable_readings);

  using slam::SlamRun;
  py::class_<SlamRun>(m, "SlamRun", "A SLAM run over a whole log.")
      .def_property_readonly(
          "trajectory", [](const SlamRun& r) { return timed_poses_to_numpy(r.trajectory); },
          "(n, 4) array: t, x, y, theta per scan, in the log's frame")
      .def_property_readonly(
          "sigma", [](const SlamRun& r) { return to_numpy(r.sigma); },
          "positional standard deviation per scan (m)")
      .def_property_readonly(
          "map", [](const SlamRun& r) { return grid_tuple(r.map); },
          "(S_eps int8 array (height, width), row 0 = bottom; GridGeometry), in the SLAM frame")
      .def_readonly("codec", &SlamRun::codec)
      .def_readonly("frame", &SlamRun::frame, "the SLAM frame in the log's frame")
      .def_readonly("scans", &SlamRun::scans)
      .def_readonly("localizations", &SlamRun::localizations)
      .def_readonly("mappings", &SlamRun::mappings)
      .def_readonly("skipped_scans", &SlamRun::skipped_scans)
      .def_readonly("readings", &SlamRun::readings)
      .def_readonly("unusable_readings", &SlamRun::unusable_readings)
      .def("mean_sigma", &SlamRun::mean_sigma, "E(sigma) over the scans (m).")
      .def(
          "map_probabilities",
          [](const SlamRun& r) { return grid_tuple(slam::slam_map_probabilities(r)); },
          "(P(occupied) float64 array, GridGeometry) on an axis-aligned grid of the log's frame.");

  m.def(
      "run_grid_slam",
      [](const core::Log& log, const GridSlamConfig& cfg, const py::object& arithmetic) {
        const core::Arithmetic a = arithmetic_of(arithmetic);
        py::gil_scoped_release release;
        return slam::run_grid_slam(log, cfg, a);
      },
      "SLAM over a whole log ('int': U_gamma pose grid, or 'float').", "log"_a,
      "config"_a = GridSlamConfig{}, "arithmetic"_a = "int");

  bind_submap_slam(m);

  py::class_<slam::TrajectoryError>(m, "TrajectoryError")
      .def_readonly("matched", &slam::TrajectoryError::matched)
      .def_readonly("rmse", &slam::TrajectoryError::rmse, "m, position only")
      .def_readonly("max", &slam::TrajectoryError::max, "m")
      .def_readonly("mean_heading", &slam::TrajectoryError::mean_heading, "rad")
      .def("__repr__", [](const py::object& self) { return fields_repr(self); });
  m.def(
      "absolute_trajectory_error",
      [](const py::object& estimate, const py::object& reference) {
        return slam::absolute_trajectory_error(timed_poses_of(estimate), timed_poses_of(reference));
      },
      "ATE over the poses sharing a time (within 1 ms); each an (n, 4) array t, x, y, theta "
      "(SlamRun.trajectory) or a Log (its scans' robot poses).",
      "estimate"_a, "reference"_a);
  m.def(
      "scan_poses",
      [](const core::Log& log) { return timed_poses_to_numpy(slam::scan_poses(log)); },
      "The (n, 4) array t, x, y, theta of a log's scans' robot poses.", "log"_a);
}

}  // namespace intgrid::python
