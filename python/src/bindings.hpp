// What the Python module's bindings share (one file a part of the module, python/src/*.cpp):
// conversions between grids and numpy arrays, field checks that raise ValueError, and the
// choices given as strings.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/mapping.hpp"
#include "intgrid/core/narrow_ism.hpp"
#include "intgrid/core/range_sensor.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/core/scan_insertion.hpp"
#include "intgrid/core/sectoral_ism.hpp"
#include "intgrid/core/sensor_model.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/core/ugamma.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/io/map_io.hpp"
#include "intgrid/localization/global_localization.hpp"
#include "intgrid/slam/grid_slam.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"
#include "intgrid/slam/log_run.hpp"
#include "intgrid/slam/map_localizer.hpp"
#include "intgrid/slam/submap_slam.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace intgrid::python {

namespace py = pybind11;
using namespace py::literals;

[[noreturn]] inline void value_error(const std::string& message) {
  throw py::value_error(message);
}

template <class T>
using CArray = py::array_t<T, py::array::c_style | py::array::forcecast>;

// A copy of a grid's cells as a (height, width) array: [iy, ix] is cell (ix, iy).
template <class T>
py::array_t<T> to_numpy(const core::Grid<T>& grid) {
  py::array_t<T> out(std::vector<py::ssize_t>{grid.geometry.height, grid.geometry.width});
  std::copy(grid.cells.begin(), grid.cells.end(), out.mutable_data());
  return out;
}

template <class T>
py::array_t<T> to_numpy(const std::vector<T>& values) {
  py::array_t<T> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

// A grid from a (height, width) array and its geometry.
template <class T, class Array>
core::Grid<T> to_grid(const Array& cells, const core::GridGeometry& geometry) {
  core::check_geometry(geometry);
  if (cells.ndim() != 2 || cells.shape(0) != geometry.height || cells.shape(1) != geometry.width)
    value_error("cells: expected an array of shape (height, width) = (" +
                std::to_string(geometry.height) + ", " + std::to_string(geometry.width) +
                ") for this geometry");
  core::Grid<T> grid;
  grid.geometry = geometry;
  grid.cells.assign(cells.data(), cells.data() + cells.size());
  return grid;
}

inline core::ProbabilityGrid probability_grid(const CArray<double>& cells,
                                              const core::GridGeometry& geometry) {
  return to_grid<double>(cells, geometry);
}

// Index arrays: any integer dtype, every value within the cell type's range.
template <class Index>
core::Grid<Index> index_grid(const py::array& cells, const core::GridGeometry& geometry) {
  if (cells.dtype().kind() != 'i' && cells.dtype().kind() != 'u')
    throw py::type_error("cells: expected an integer array");
  const auto wide = CArray<std::int64_t>::ensure(cells);
  if (!wide) throw py::type_error("cells: cannot be read as an integer array");
  core::Grid<std::int64_t> checked = to_grid<std::int64_t>(wide, geometry);
  core::Grid<Index> grid;
  grid.geometry = geometry;
  grid.cells.reserve(checked.cells.size());
  for (const std::int64_t v : checked.cells) {
    if (v < std::numeric_limits<Index>::min() || v > std::numeric_limits<Index>::max())
      value_error("cells: value " + std::to_string(v) + " does not fit the grid's cell type");
    grid.cells.push_back(static_cast<Index>(v));
  }
  return grid;
}

inline std::string number(double v) {
  return py::repr(py::float_(v)).cast<std::string>();
}

// "Name(a=1, b=2)" over the public data attributes of an object, for the configuration structs.
inline std::string fields_repr(const py::object& self) {
  std::string out = py::type::handle_of(self).attr("__name__").cast<std::string>() + "(";
  bool first = true;
  for (const py::handle name : py::module_::import("builtins").attr("dir")(self)) {
    const auto key = name.cast<std::string>();
    if (key.empty() || key[0] == '_') continue;
    const py::object value = self.attr(name);
    if (PyCallable_Check(value.ptr())) continue;
    out += (first ? "" : ", ") + key + "=" + py::repr(value).cast<std::string>();
    first = false;
  }
  return out + ")";
}

// T(**fields): a default T with the named fields set; an unknown name is a TypeError.
template <class T, class Class>
void def_fields_init(Class& cls) {
  cls.def(
      py::init([](const py::kwargs& fields) {
        py::object self = py::cast(T{});
        for (const auto& [name, value] : fields) {
          if (!py::hasattr(self, name))
            throw py::type_error(std::string(py::str(py::type::handle_of(self).attr("__name__"))) +
                                 " has no field '" + std::string(py::str(name)) + "'");
          py::setattr(self, name, value);
        }
        return self.cast<T>();
      }),
      "A default configuration with the given fields set.");
  cls.def("__repr__", [](const py::object& self) { return fields_repr(self); });
}

inline core::Arithmetic arithmetic_of(const py::object& arithmetic) {
  if (py::isinstance<py::str>(arithmetic)) {
    const auto s = arithmetic.cast<std::string>();
    if (s == "int" || s == "integer") return core::Arithmetic::integer;
    if (s == "float" || s == "floating" || s == "double") return core::Arithmetic::floating;
    value_error("arithmetic must be 'int' or 'float', got '" + s + "'");
  }
  return arithmetic.cast<core::Arithmetic>();
}

inline localization::GlobalMethod method_of(const py::object& method) {
  if (py::isinstance<py::str>(method)) {
    const auto s = method.cast<std::string>();
    if (s == "pog" || s == "pose_grid" || s == "pose-grid")
      return localization::GlobalMethod::pose_grid;
    if (s == "markov") return localization::GlobalMethod::markov;
    if (s == "markov-mixture" || s == "markov_mixture")
      return localization::GlobalMethod::markov_mixture;
    if (s == "likelihood-field" || s == "likelihood_field")
      return localization::GlobalMethod::likelihood_field;
    value_error("method must be 'pog', 'markov', 'markov-mixture' or 'likelihood-field', got '" +
                s + "'");
  }
  return method.cast<localization::GlobalMethod>();
}

inline core::VetoBound veto_of(const std::string& veto) {
  if (veto == "claim" || veto == "strongest_claim") return core::VetoBound::strongest_claim;
  if (veto == "none") return core::VetoBound::none;
  value_error("veto must be 'claim' or 'none', got '" + veto + "'");
}

inline void check_finite(double v, const char* name) {
  if (!std::isfinite(v)) value_error(std::string(name) + " must be finite, got " + number(v));
}

inline void check_positive(double v, const char* name) {
  if (!(v > 0.0) || !std::isfinite(v))
    value_error(std::string(name) + " must be a positive finite number, got " + number(v));
}

inline void check_index(int i, int n, const char* name) {
  if (i < 0 || i >= n)
    throw py::index_error(std::string(name) + " " + std::to_string(i) + " outside 0.." +
                          std::to_string(n - 1));
}

// --- Poses, scans, logs, grids ----------------------------------------------------------------

inline std::string pose_repr(const core::Pose2& p) {
  return "Pose2(x=" + number(p.x) + ", y=" + number(p.y) + ", theta=" + number(p.theta) + ")";
}

// The module's parts, in the order PYBIND11_MODULE binds them (a part's default arguments may
// name the types of an earlier one).
void bind_types(py::module_& m);
void bind_isms(py::module_& m);
void bind_seps(py::module_& m);
void bind_mapping(py::module_& m);
void bind_io(py::module_& m);
void bind_localization(py::module_& m);
void bind_slam(py::module_& m);
void bind_navigation(py::module_& m);

}  // namespace intgrid::python
