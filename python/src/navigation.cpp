// Localization in a known map from no prior, in Python: found, tracked, lost, found again.
#include "bindings.hpp"
#include "intgrid/navigation/known_map_localizer.hpp"

namespace intgrid::python {

void bind_navigation(py::module_& m) {
  using localization::SequenceOptions;
  using navigation::KnownMapLocalizer;
  using navigation::KnownMapLocalizerConfig;
  using navigation::LocalizerStep;

  py::class_<SequenceOptions> sequence(
      m, "SequenceOptions",
      "How global localization fuses a log's scans as they come (globloc --track's).");
  def_fields_init<SequenceOptions>(sequence);
  sequence.def_readwrite("beams", &SequenceOptions::beams, "screening readings a scan (0: all)")
      .def_readwrite("verify_beams", &SequenceOptions::verify_beams,
                     "verification readings a scan (0: all)")
      .def_readwrite("max_scans", &SequenceOptions::max_scans, "scans fused at most")
      .def_readwrite("step_position", &SequenceOptions::step_position,
                     "m odometry moves the sensor before the next scan is fused")
      .def_readwrite("step_heading", &SequenceOptions::step_heading, "or rad it turns it");

  py::class_<KnownMapLocalizerConfig::Lost> lost(
      m, "LostCriterion",
      "When the tracked scans stop fitting the map: `scans` matched scans in a row whose fit is "
      "under fit_share of the median fit of the last `recent` that fitted.");
  def_fields_init<KnownMapLocalizerConfig::Lost>(lost);
  lost.def_readwrite("fit_share", &KnownMapLocalizerConfig::Lost::fit_share)
      .def_readwrite("scans", &KnownMapLocalizerConfig::Lost::scans)
      .def_readwrite("recent", &KnownMapLocalizerConfig::Lost::recent);

  py::class_<KnownMapLocalizerConfig> config(
      m, "KnownMapLocalizerConfig",
      "Settings of KnownMapLocalizer (the `localize` defaults); global_ is the C++ `global`.");
  def_fields_init<KnownMapLocalizerConfig>(config);
  config
      .def_readwrite("tracking", &KnownMapLocalizerConfig::tracking,
                     "a SubmapSlamConfig: the tracking's (its cell must be the map's)")
      .def_readwrite("global_", &KnownMapLocalizerConfig::global,
                     "a GlobalLocConfig: the pose grid's")
      .def_readwrite("sequence", &KnownMapLocalizerConfig::sequence, "a SequenceOptions")
      .def_readwrite("lost", &KnownMapLocalizerConfig::lost, "a LostCriterion")
      .def_readwrite("verify_every", &KnownMapLocalizerConfig::verify_every,
                     "m of travel between global localization's checks of the tracked pose")
      .def_readwrite("contest_scans", &KnownMapLocalizerConfig::contest_scans,
                     "matched scans an answer elsewhere is tracked beside the pose");

  py::class_<LocalizerStep>(m, "LocalizerStep", "One scan's outcome (KnownMapLocalizer).")
      .def_property_readonly(
          "state", [](const LocalizerStep& s) { return navigation::state_name(s.state); },
          "'locating', 'tracking', 'lost' or 'recovering'")
      .def_readonly("pose", &LocalizerStep::pose,
                    "The robot's Pose2 in the map's frame while tracking, else None.")
      .def_readonly("fix", &LocalizerStep::fix, "tracking and lost: the MapFix")
      .def_readonly("fused_scans", &LocalizerStep::fused_scans,
                    "locating and recovering: the scans fused so far")
      .def_readonly("verified", &LocalizerStep::verified,
                    "tracking: the pose was given or confirmed by global localization")
      .def_readonly("refixed", &LocalizerStep::refixed,
                    "a global answer won a contest against the tracked pose here")
      .def("__repr__", [](const py::object& self) { return fields_repr(self); });

  py::class_<KnownMapLocalizer>(
      m, "KnownMapLocalizer",
      "Localization in a known map scan after scan: the robot found by global localization "
      "(or from `initial`), tracked by the submaps SLAM's localization event, declared lost "
      "when the scans stop fitting the map, found again.")
      .def(py::init([](const core::ProbabilityGrid& map, const KnownMapLocalizerConfig& cfg,
                       const py::object& arithmetic, std::optional<core::Pose2> initial,
                       double occupied, double free) {
             const core::Arithmetic a = arithmetic_of(arithmetic);
             py::gil_scoped_release release;
             return std::make_unique<KnownMapLocalizer>(map, occupied, free, cfg, a, initial);
           }),
           "map"_a, "config"_a = KnownMapLocalizerConfig{}, "arithmetic"_a = "int",
           "initial"_a = py::none(), "occupied_threshold"_a = 0.65, "free_threshold"_a = 0.196,
           "map: a ProbabilityGrid (a RosMap's grid, with its thresholds); config.tracking.cell "
           "must be its cell; initial: the robot's pose at the first scan, if known.")
      .def("localize", &KnownMapLocalizer::localize, py::call_guard<py::gil_scoped_release>(),
           "The next scan's LocalizerStep.", "scan"_a);
}

}  // namespace intgrid::python
