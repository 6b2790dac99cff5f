// The readers and writers in Python (intgrid.io).
#include "bindings.hpp"

namespace intgrid::python {

void bind_io(py::module_& m) {
  py::module_ io_module =
      m.def_submodule("io", "Logs and ROS maps; bad input raises io.InputError.");
  // Registered so that `import intgrid.io` and `from intgrid.io import ...` work.
  py::module_::import("sys").attr("modules")["intgrid.io"] = io_module;

  static py::exception<io::InputError> input_error(io_module, "InputError", PyExc_ValueError);
  input_error.doc() =
      "Bad input file (a ValueError): attributes file, line (0: none), field, "
      "message.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const io::InputError& e) {
      py::object error = py::reinterpret_borrow<py::object>(input_error)(e.what());
      error.attr("file") = e.file().string();
      error.attr("line") = e.line();
      error.attr("field") = e.field();
      error.attr("message") = e.message();
      PyErr_SetObject(input_error.ptr(), error.ptr());
    }
  });

  io_module.def(
      "read_log", [](const std::filesystem::path& file) { return io::read_log(file); },
      "Reads a log in the project format or CARMEN's (chosen by its first record).", "path"_a);
  io_module.def("read_intgrid_log", &io::read_intgrid_log, "path"_a);
  io_module.def(
      "read_carmen_log",
      [](const std::filesystem::path& file, std::optional<double> max_range) {
        return io::read_carmen_log(file, max_range);
      },
      "Reads a CARMEN log; max_range None takes the sensor's range from the log.", "path"_a,
      "max_range"_a = py::none());
  io_module.def("write_log", &io::write_log, "Writes a log in the project format.", "path"_a,
                "log"_a);

  py::class_<io::RosMap>(io_module, "RosMap",
                         "A ROS map_server map: grid (row 0 = bottom) and thresholds.")
      .def(py::init([](const core::ProbabilityGrid& grid, double occupied_thresh,
                       double free_thresh, bool negate) {
             return io::RosMap{grid, occupied_thresh, free_thresh, negate};
           }),
           "grid"_a, "occupied_thresh"_a = 0.65, "free_thresh"_a = 0.196, "negate"_a = false)
      .def_readwrite("grid", &io::RosMap::grid)
      .def_readwrite("occupied_thresh", &io::RosMap::occupied_thresh)
      .def_readwrite("free_thresh", &io::RosMap::free_thresh)
      .def_readwrite("negate", &io::RosMap::negate)
      .def_property_readonly(
          "cells", [](const io::RosMap& map) { return to_numpy(map.grid); }, "grid.cells")
      .def_property_readonly("geometry", [](const io::RosMap& map) { return map.grid.geometry; })
      .def("__repr__", [](const io::RosMap& map) {
        return "RosMap(" + std::to_string(map.grid.geometry.width) + " x " +
               std::to_string(map.grid.geometry.height) +
               ", occupied_thresh=" + number(map.occupied_thresh) +
               ", free_thresh=" + number(map.free_thresh) + ")";
      });

  io_module.def("read_ros_map", &io::read_ros_map, "Reads a map_server YAML and its PGM.",
                "path"_a);
  io_module.def("write_ros_map", &io::write_ros_map, "path"_a, "map"_a);
  io_module.def(
      "write_ros_map",
      [](const std::filesystem::path& yaml, const core::ProbabilityGrid& grid,
         double occupied_thresh, double free_thresh, bool negate) {
        io::write_ros_map(yaml, io::RosMap{grid, occupied_thresh, free_thresh, negate});
      },
      "path"_a, "grid"_a, "occupied_thresh"_a = 0.65, "free_thresh"_a = 0.196, "negate"_a = false);
  io_module.def(
      "write_ros_map",
      [](const std::filesystem::path& yaml, const CArray<double>& cells,
         const core::GridGeometry& geometry, double occupied_thresh, double free_thresh,
         bool negate) {
        io::write_ros_map(yaml, io::RosMap{probability_grid(cells, geometry), occupied_thresh,
                                           free_thresh, negate});
      },
      "Writes the YAML and, beside it, a PGM of the same stem (a RosMap, a ProbabilityGrid, or "
      "a P(occupied) array (height, width) with its GridGeometry).",
      "path"_a, "cells"_a, "geometry"_a, "occupied_thresh"_a = 0.65, "free_thresh"_a = 0.196,
      "negate"_a = false);
  io_module.def("probability_to_pixel", &io::probability_to_pixel,
                "The PGM pixel of P(occupied) p.", "p"_a, "negate"_a = false);
}

}  // namespace intgrid::python
