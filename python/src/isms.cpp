// The sensor models and the ISMs in Python.
#include "bindings.hpp"

namespace intgrid::python {

void bind_isms(py::module_& m) {
  py::class_<core::RangeSensor> range_sensor(
      m, "RangeSensor",
      "A range sensor as the engines and the localization model it: sigma, the range noise of a "
      "reading (m), and max_range, past which readings are not used (m). The `sensor` of "
      "SubmapSlamConfig, GridSlamConfig and GlobalLocConfig.");
  def_fields_init<core::RangeSensor>(range_sensor);
  range_sensor.def_readwrite("sigma", &core::RangeSensor::sigma, "range noise (m)")
      .def_readwrite("max_range", &core::RangeSensor::max_range,
                     "readings at or past it unused (m)")
      .def(
          "check", [](const core::RangeSensor& s) { core::check_range_sensor(s, "sensor"); },
          "Raises ValueError naming a bad field.");

  py::class_<core::GaussianBeamModel>(m, "GaussianBeamModel",
                                      "Narrow-FOV Gaussian model: sigma(d) = sigma0 (1 + k_d d).")
      .def(py::init<double, double>(), "sigma0"_a = 0.03, "k_d"_a = 0.0)
      .def_readwrite("sigma0", &core::GaussianBeamModel::sigma0, "metres")
      .def_readwrite("k_d", &core::GaussianBeamModel::k_d, "per metre")
      .def("sigma", &core::GaussianBeamModel::sigma, "d"_a)
      .def("log_density", &core::GaussianBeamModel::log_density, "ln p(z | d)", "z"_a, "d"_a)
      .def("density", &core::GaussianBeamModel::density, "p(z | d)", "z"_a, "d"_a)
      .def(
          "check", [](const core::GaussianBeamModel& model) { core::check_model(model); },
          "Raises ValueError naming a bad parameter.")
      .def("__repr__", [](const core::GaussianBeamModel& model) {
        return "GaussianBeamModel(sigma0=" + number(model.sigma0) + ", k_d=" + number(model.k_d) +
               ")";
      });

  m.def(
      "narrow_ism",
      [](const core::GaussianBeamModel& model, double z, double cell, std::size_t cells) {
        core::check_model(model);
        check_finite(z, "z");
        check_positive(cell, "cell");
        if (cells < 1 || cells > 100'000'000) value_error("cells must be 1..10^8");
        py::array_t<double> out(static_cast<py::ssize_t>(cells));
        core::narrow_ism(model, z, cell,
                         std::span<double>(out.mutable_data(), static_cast<std::size_t>(cells)));
        return out;
      },
      "The exact narrow ISM P(o_k | z) for the line-of-sight cells k = 1..cells at distance "
      "k * cell (element k - 1), every prior 1/2.",
      "model"_a, "z"_a, "cell"_a, "cells"_a);
  m.def(
      "predicted_argmax_cell",
      [](const core::GaussianBeamModel& model, double z, double cell, std::size_t cells) {
        core::check_model(model);
        check_finite(z, "z");
        check_positive(cell, "cell");
        if (cells < 1) value_error("cells must be at least 1");
        return core::predicted_argmax_cell(model, z, cell, cells);
      },
      "The 1-based cell of the narrow ISM's maximum by Theorem 1.", "model"_a, "z"_a, "cell"_a,
      "cells"_a);
  m.def(
      "ism_cells_for_reading",
      [](const core::GaussianBeamModel& model, double z, double cell) {
        core::check_model(model);
        check_finite(z, "z");
        check_positive(cell, "cell");
        return core::ism_cells_for_reading(model, z, cell);
      },
      "Cells a reading's ISM is computed over in mapping (to z + 8 sigma(z)).", "model"_a, "z"_a,
      "cell"_a);
  m.def("narrow_pmax", &core::narrow_pmax,
        "Pmax of the narrow ISM for a cell size and sigma, the reading `offset` cells past a "
        "cell centre.",
        "cell"_a, "sigma"_a, "offset"_a = 0.0);
  m.def(
      "narrow_pmax_worst_case",
      [](double cell, double sigma) {
        const core::WorstCasePmax w = core::narrow_pmax_worst_case(cell, sigma);
        return py::make_tuple(w.pmax, w.offset);
      },
      "(pmax, offset): the smallest Pmax over the reading's position in a cell.", "cell"_a,
      "sigma"_a);
  m.def("smallest_cell_for_pmax", &core::smallest_cell_for_pmax,
        "The smallest cell size whose ISM reaches pmax.", "sigma"_a, "pmax"_a,
        "worst_case"_a = false);

  py::class_<core::ConeSensorModel>(m, "ConeSensorModel",
                                    "Large-FOV model: sigma = sigma0 (1 + k_d d)(1 + k_theta "
                                    "theta)(1 + k_size/size)/(1 + k_size).")
      .def(py::init<double, double, double, double>(), "sigma0"_a = 0.02, "k_d"_a = 0.05,
           "k_theta"_a = 0.5, "k_size"_a = 0.5)
      .def_readwrite("sigma0", &core::ConeSensorModel::sigma0)
      .def_readwrite("k_d", &core::ConeSensorModel::k_d)
      .def_readwrite("k_theta", &core::ConeSensorModel::k_theta)
      .def_readwrite("k_size", &core::ConeSensorModel::k_size)
      .def("sigma", &core::ConeSensorModel::sigma, "d"_a, "theta"_a, "size"_a)
      .def("check", [](const core::ConeSensorModel& model) { core::check_model(model); })
      .def("__repr__", [](const py::object& self) { return fields_repr(self); });

  py::class_<core::SectoralGrid>(m, "SectoralGrid",
                                 "Polar grid of a cone sensor: rings 1..rings at r * cell, bins "
                                 "0..bins-1 across the FOV (bin 0 clockwise), sectors.")
      .def(py::init<double, int, int, int, double>(), "fov"_a = 0.5235987755982988, "rings"_a = 40,
           "bins"_a = 16, "sectors"_a = 4, "cell"_a = 0.05)
      .def_readwrite("fov", &core::SectoralGrid::fov, "radians")
      .def_readwrite("rings", &core::SectoralGrid::rings)
      .def_readwrite("bins", &core::SectoralGrid::bins)
      .def_readwrite("sectors", &core::SectoralGrid::sectors)
      .def_readwrite("cell", &core::SectoralGrid::cell, "metres")
      .def("cells", &core::SectoralGrid::cells)
      .def("bins_per_sector", &core::SectoralGrid::bins_per_sector)
      .def("sector_of_bin", &core::SectoralGrid::sector_of_bin, "bin"_a)
      .def("bin_centre", &core::SectoralGrid::bin_centre, "bin"_a)
      .def("sector_centre", &core::SectoralGrid::sector_centre, "sector"_a)
      .def("sector_theta", &core::SectoralGrid::sector_theta, "sector"_a)
      .def("ring_distance", &core::SectoralGrid::ring_distance, "ring"_a)
      .def("check", &core::check_sectoral_grid, "Raises ValueError naming a bad field.")
      .def("__repr__", [](const py::object& self) { return fields_repr(self); });

  m.def(
      "sectoral_ism",
      [](const core::ConeSensorModel& model, const core::SectoralGrid& grid, double z) {
        core::check_model(model);
        core::check_sectoral_grid(grid);
        check_finite(z, "z");
        py::array_t<double> out(std::vector<py::ssize_t>{grid.rings, grid.bins});
        {
          py::gil_scoped_release release;
          core::sectoral_ism(model, grid, z, std::span<double>(out.mutable_data(), grid.cells()));
        }
        return out;
      },
      "The exact large-FOV ISM over the polar grid: array (rings, bins), [r - 1, a] = P(o | z) "
      "of ring r, bin a.",
      "model"_a, "grid"_a, "z"_a);
}

}  // namespace intgrid::python
