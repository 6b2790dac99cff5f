// Global localization in Python.
#include "bindings.hpp"

namespace intgrid::python {
namespace {

// Runs localize(scores or nullptr) without the GIL: the estimate, or (estimate, scores) with the
// scores as an array (headings, height, width).
template <class Localize>
py::object localize_with(const localization::LocalizationMap& map,
                         localization::GlobalMethod method, bool return_scores,
                         Localize&& localize) {
  localization::PoseScores scores;
  localization::GlobalEstimate estimate;
  {
    py::gil_scoped_release release;
    estimate = localize(return_scores ? &scores : nullptr);
  }
  if (!return_scores) return py::cast(estimate);
  const std::vector<py::ssize_t> shape{map.headings(), map.height(), map.width()};
  py::array values;
  if (method == localization::GlobalMethod::pose_grid) {
    py::array_t<std::int32_t> a(shape);
    std::copy(scores.index_sum.begin(), scores.index_sum.end(), a.mutable_data());
    values = a;
  } else {
    py::array_t<double> a(shape);
    std::copy(scores.posterior.begin(), scores.posterior.end(), a.mutable_data());
    values = a;
  }
  return py::make_tuple(estimate, values);
}

localization::LocalizationMap make_localization_map(const core::ProbabilityGrid& grid,
                                                    double occupied, double free,
                                                    const localization::GlobalLocConfig& config) {
  py::gil_scoped_release release;
  return localization::LocalizationMap(grid, occupied, free, config);
}

}  // namespace

void bind_localization(py::module_& m) {
  py::enum_<localization::GlobalMethod>(m, "GlobalMethod")
      .value("pose_grid", localization::GlobalMethod::pose_grid)
      .value("markov", localization::GlobalMethod::markov)
      .value("markov_mixture", localization::GlobalMethod::markov_mixture)
      .value("likelihood_field", localization::GlobalMethod::likelihood_field);
  py::enum_<localization::PoseCellClass>(m, "PoseCellClass")
      .value("free", localization::PoseCellClass::free)
      .value("unknown", localization::PoseCellClass::unknown)
      .value("occupied", localization::PoseCellClass::occupied);

  using localization::GlobalLocConfig;
  py::class_<GlobalLocConfig> loc_config(
      m, "GlobalLocConfig", "Settings of global localization (the `globloc` defaults).");
  def_fields_init<GlobalLocConfig>(loc_config);
  loc_config.def_readwrite("pose_res", &GlobalLocConfig::pose_res, "pose-grid step (m)")
      .def_readwrite("headings", &GlobalLocConfig::headings)
      .def_readwrite("sensor", &GlobalLocConfig::sensor, "a RangeSensor")
      .def_readwrite("seps_bits", &GlobalLocConfig::seps_bits)
      .def_readwrite("seps_levels", &GlobalLocConfig::seps_levels)
      .def_readwrite("veto_levels", &GlobalLocConfig::veto_levels)
      .def_readwrite("z_hit", &GlobalLocConfig::z_hit)
      .def_readwrite("z_short", &GlobalLocConfig::z_short)
      .def_readwrite("z_max", &GlobalLocConfig::z_max)
      .def_readwrite("z_rand", &GlobalLocConfig::z_rand)
      .def_readwrite("lambda_short", &GlobalLocConfig::lambda_short)
      .def_readwrite("refine_levels", &GlobalLocConfig::refine_levels,
                     "levels of the hypotheses' refinement on the map's cells (0: none)")
      .def_readwrite("grazing_hits", &GlobalLocConfig::grazing_hits,
                     "the refinement reads a reading that ends on a wall its ray entered early "
                     "(a grazing angle) as a hit at its range")
      .def("check", &localization::check_global_loc_config,
           "Raises ValueError naming a bad field.");

  py::class_<localization::RangeReading>(m, "RangeReading", "One reading in the sensor frame.")
      .def(py::init<double, double>(), "range"_a = 0.0, "bearing"_a = 0.0)
      .def_readwrite("range", &localization::RangeReading::range, "m")
      .def_readwrite("bearing", &localization::RangeReading::bearing, "rad from the sensor axis")
      .def("__repr__", [](const localization::RangeReading& r) {
        return "RangeReading(range=" + number(r.range) + ", bearing=" + number(r.bearing) + ")";
      });
  m.def("readings_of", &localization::readings_of,
        "The usable readings of a scan below max_range, `beams` of them spread evenly (0: all).",
        "scan"_a, "beams"_a = 0, "max_range"_a = 30.0);

  using localization::LocalizationMap;
  py::class_<LocalizationMap>(m, "LocalizationMap",
                              "A map prepared for global localization: pose cells of pose_res "
                              "over `headings` heading bins.")
      .def(py::init(&make_localization_map), "grid"_a, "occupied_threshold"_a = 0.65,
           "free_threshold"_a = 0.196, "config"_a = GlobalLocConfig{})
      .def(py::init([](const CArray<double>& cells, const core::GridGeometry& geometry,
                       double occupied, double free, const GlobalLocConfig& config) {
             return make_localization_map(probability_grid(cells, geometry), occupied, free,
                                          config);
           }),
           "cells"_a, "geometry"_a, "occupied_threshold"_a = 0.65, "free_threshold"_a = 0.196,
           "config"_a = GlobalLocConfig{})
      .def(py::init([](const io::RosMap& map, const GlobalLocConfig& config) {
             return make_localization_map(map.grid, map.occupied_thresh, map.free_thresh, config);
           }),
           "map"_a, "config"_a = GlobalLocConfig{})
      .def_property_readonly("config", [](const LocalizationMap& map) { return map.config(); })
      .def_property_readonly("width", &LocalizationMap::width, "pose cells in x")
      .def_property_readonly("height", &LocalizationMap::height, "pose cells in y")
      .def_property_readonly("headings", &LocalizationMap::headings)
      .def_property_readonly("pose_cells", &LocalizationMap::pose_cells)
      .def_property_readonly("candidate_cells", &LocalizationMap::candidate_cells)
      .def_property_readonly("heading_bin", &LocalizationMap::heading_bin, "2 pi / headings")
      .def(
          "pose_of",
          [](const LocalizationMap& map, int i, int j, int k) {
            check_index(i, map.width(), "i");
            check_index(j, map.height(), "j");
            check_index(k, map.headings(), "k");
            return map.pose_of(i, j, k);
          },
          "The sensor pose at the centre of pose cell (i, j), heading bin k.", "i"_a, "j"_a, "k"_a)
      .def(
          "cell_class",
          [](const LocalizationMap& map, int i, int j) {
            check_index(i, map.width(), "i");
            check_index(j, map.height(), "j");
            return map.cell_class(i, j);
          },
          "i"_a, "j"_a)
      .def(
          "first_hit_steps",
          [](const LocalizationMap& map, int i, int j, int d) {
            check_index(i, map.width(), "i");
            check_index(j, map.height(), "j");
            check_index(d, map.headings(), "d");
            return map.first_hit_steps(i, j, d);
          },
          "Steps along direction bin d to the first occupied cell (65535: none).", "i"_a, "j"_a,
          "d"_a)
      .def("distance_to_occupied", &LocalizationMap::distance_to_occupied, "x"_a, "y"_a)
      .def("effective_sigma", &LocalizationMap::effective_sigma, "z"_a);

  py::class_<localization::GlobalEstimate>(m, "GlobalEstimate")
      .def_readonly("sensor", &localization::GlobalEstimate::sensor, "the best cell's sensor pose")
      .def_readonly("robot", &localization::GlobalEstimate::robot,
                    "the sensor pose stepped back by the mounting pose")
      .def_readonly("score", &localization::GlobalEstimate::score,
                    "pose grid: the best index sum; baselines: the best posterior")
      .def_readonly("ties", &localization::GlobalEstimate::ties)
      .def_readonly("readings_used", &localization::GlobalEstimate::readings_used)
      .def_readonly("readings_dropped", &localization::GlobalEstimate::readings_dropped)
      .def("__repr__", [](const localization::GlobalEstimate& e) {
        return "GlobalEstimate(robot=" + pose_repr(e.robot) + ", score=" + number(e.score) +
               ", ties=" + std::to_string(e.ties) + ")";
      });

  m.def(
      "localize",
      [](const LocalizationMap& map, const core::Scan& scan, const py::object& method, int beams,
         bool return_scores) {
        const localization::GlobalMethod how = method_of(method);
        return localize_with(map, how, return_scores, [&](localization::PoseScores* scores) {
          return localization::localize_scan(map, scan, beams, how, scores);
        });
      },
      "Localizes one scan from no prior on the map: `beams` of its readings (0: all), method "
      "'pog', 'markov', 'markov-mixture' or 'likelihood-field'. Returns a GlobalEstimate, or "
      "(estimate, scores (headings, height, width)) with return_scores.",
      "map"_a, "scan"_a, "method"_a = "pog", "beams"_a = 60, "return_scores"_a = false);
  m.def(
      "localize_readings",
      [](const LocalizationMap& map, const std::vector<localization::RangeReading>& readings,
         const core::Pose2& sensor_mount, const py::object& method, bool return_scores) {
        const localization::GlobalMethod how = method_of(method);
        return localize_with(map, how, return_scores, [&](localization::PoseScores* scores) {
          return localization::localize_global(map, readings, sensor_mount, how, scores);
        });
      },
      "Localizes a list of RangeReadings taken with the given sensor mount.", "map"_a, "readings"_a,
      "sensor_mount"_a = core::Pose2{}, "method"_a = "pog", "return_scores"_a = false);
}

}  // namespace intgrid::python
