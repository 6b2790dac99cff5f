// The Python module `intgrid`: the ISMs, S_eps fusion, mapping with known poses, global
// localization of one scan, SLAM scan by scan, and the readers and writers (intgrid.io).
//
// Grids cross the boundary as copies in numpy arrays of shape (height, width): element [iy, ix] is
// cell (ix, iy) of the C++ grid, so row 0 is the BOTTOM row of the map (y grows with the row), the
// opposite of an image. C++ std::invalid_argument arrives as ValueError, io::InputError as
// intgrid.io.InputError (a ValueError), std::runtime_error as RuntimeError.
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
#include "intgrid/slam/submap_slam.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace py = pybind11;
using namespace py::literals;

namespace intgrid::python {
namespace {

// --- Helpers ---------------------------------------------------------------------------------

[[noreturn]] void value_error(const std::string& message) {
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

core::ProbabilityGrid probability_grid(const CArray<double>& cells,
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

std::string number(double v) {
  return py::repr(py::float_(v)).cast<std::string>();
}

// "Name(a=1, b=2)" over the public data attributes of an object, for the configuration structs.
std::string fields_repr(const py::object& self) {
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

core::Arithmetic arithmetic_of(const py::object& arithmetic) {
  if (py::isinstance<py::str>(arithmetic)) {
    const auto s = arithmetic.cast<std::string>();
    if (s == "int" || s == "integer") return core::Arithmetic::integer;
    if (s == "float" || s == "floating" || s == "double") return core::Arithmetic::floating;
    value_error("arithmetic must be 'int' or 'float', got '" + s + "'");
  }
  return arithmetic.cast<core::Arithmetic>();
}

localization::GlobalMethod method_of(const py::object& method) {
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

core::VetoBound veto_of(const std::string& veto) {
  if (veto == "claim" || veto == "strongest_claim") return core::VetoBound::strongest_claim;
  if (veto == "none") return core::VetoBound::none;
  value_error("veto must be 'claim' or 'none', got '" + veto + "'");
}

void check_finite(double v, const char* name) {
  if (!std::isfinite(v)) value_error(std::string(name) + " must be finite, got " + number(v));
}

void check_positive(double v, const char* name) {
  if (!(v > 0.0) || !std::isfinite(v))
    value_error(std::string(name) + " must be a positive finite number, got " + number(v));
}

void check_index(int i, int n, const char* name) {
  if (i < 0 || i >= n)
    throw py::index_error(std::string(name) + " " + std::to_string(i) + " outside 0.." +
                          std::to_string(n - 1));
}

// --- Poses, scans, logs, grids ----------------------------------------------------------------

std::string pose_repr(const core::Pose2& p) {
  return "Pose2(x=" + number(p.x) + ", y=" + number(p.y) + ", theta=" + number(p.theta) + ")";
}

void bind_types(py::module_& m) {
  py::enum_<core::Arithmetic>(m, "Arithmetic", "The two arithmetics: integer indices or double.")
      .value("integer", core::Arithmetic::integer)
      .value("floating", core::Arithmetic::floating);

  py::class_<core::Pose2>(m, "Pose2", "A planar pose: x, y (m), theta (rad, counter-clockwise).")
      .def(py::init<double, double, double>(), "x"_a = 0.0, "y"_a = 0.0, "theta"_a = 0.0)
      .def_readwrite("x", &core::Pose2::x)
      .def_readwrite("y", &core::Pose2::y)
      .def_readwrite("theta", &core::Pose2::theta)
      .def("as_tuple", [](const core::Pose2& p) { return py::make_tuple(p.x, p.y, p.theta); })
      .def("__repr__", &pose_repr);
  m.def("wrap_angle", &core::wrap_angle, "An angle wrapped to (-pi, pi].", "a"_a);
  m.def("compose", &core::compose, "a (+) b: b given in a's frame, in the world frame.", "a"_a,
        "b"_a);
  m.def("relative", &core::relative, "The pose b seen from a (the inverse of compose).", "a"_a,
        "b"_a);

  py::class_<core::Scan>(
      m, "Scan", "One 2D range scan; beam i has bearing angle0 + i * dangle (sensor frame).")
      .def(py::init([](double t, const core::Pose2& robot, const core::Pose2& sensor_mount,
                       double angle0, double dangle, double max_range,
                       const CArray<double>& ranges) {
             if (ranges.ndim() != 1) value_error("ranges must be one-dimensional");
             return core::Scan{t,
                               robot,
                               sensor_mount,
                               angle0,
                               dangle,
                               max_range,
                               std::vector<double>(ranges.data(), ranges.data() + ranges.size())};
           }),
           "t"_a = 0.0, "robot"_a = core::Pose2{}, "sensor_mount"_a = core::Pose2{},
           "angle0"_a = 0.0, "dangle"_a = 0.0, "max_range"_a = 0.0, "ranges"_a = CArray<double>(0))
      .def_readwrite("t", &core::Scan::t, "UNIX time (s)")
      .def_readwrite("robot", &core::Scan::robot, "robot pose when the scan was taken")
      .def_readwrite("sensor_mount", &core::Scan::sensor_mount, "sensor pose in the robot frame")
      .def_readwrite("angle0", &core::Scan::angle0)
      .def_readwrite("dangle", &core::Scan::dangle)
      .def_readwrite("max_range", &core::Scan::max_range)
      .def_property(
          "ranges", [](const core::Scan& s) { return to_numpy(s.ranges); },
          [](core::Scan& s, const CArray<double>& ranges) {
            if (ranges.ndim() != 1) value_error("ranges must be one-dimensional");
            s.ranges.assign(ranges.data(), ranges.data() + ranges.size());
          },
          "the ranges (m) as a new float64 array; assign an array or list to change them")
      .def("sensor_pose", &core::Scan::sensor_pose, "robot (+) sensor_mount")
      .def("bearing", &core::Scan::bearing, "i"_a)
      .def("is_valid_range", &core::Scan::is_valid_range, "r"_a)
      .def("__repr__", [](const core::Scan& s) {
        return "Scan(t=" + number(s.t) + ", robot=" + pose_repr(s.robot) +
               ", beams=" + std::to_string(s.ranges.size()) + ")";
      });

  py::class_<core::OdometryRecord>(m, "OdometryRecord")
      .def(py::init<double, core::Pose2>(), "t"_a = 0.0, "pose"_a = core::Pose2{})
      .def_readwrite("t", &core::OdometryRecord::t)
      .def_readwrite("pose", &core::OdometryRecord::pose);

  py::class_<core::Log>(m, "Log",
                        "A sensor log. scans and odometry are copied in and out as lists.")
      .def(py::init([](std::vector<core::Scan> scans, std::vector<core::OdometryRecord> odometry) {
             return core::Log{std::move(scans), std::move(odometry)};
           }),
           "scans"_a = std::vector<core::Scan>{},
           "odometry"_a = std::vector<core::OdometryRecord>{})
      .def_readwrite("scans", &core::Log::scans)
      .def_readwrite("odometry", &core::Log::odometry)
      .def("__len__", [](const core::Log& log) { return log.scans.size(); })
      .def("__repr__", [](const core::Log& log) {
        return "Log(scans=" + std::to_string(log.scans.size()) +
               ", odometry=" + std::to_string(log.odometry.size()) + ")";
      });

  py::class_<core::GridGeometry>(m, "GridGeometry",
                                 "Cell (0, 0) is the lower-left cell; x grows with the column, "
                                 "y with the row.")
      .def(py::init<int, int, double, double, double>(), "width"_a = 0, "height"_a = 0,
           "resolution"_a = 0.0, "origin_x"_a = 0.0, "origin_y"_a = 0.0)
      .def_readwrite("width", &core::GridGeometry::width)
      .def_readwrite("height", &core::GridGeometry::height)
      .def_readwrite("resolution", &core::GridGeometry::resolution, "metres per cell")
      .def_readwrite("origin_x", &core::GridGeometry::origin_x,
                     "world x of the lower-left corner of cell (0, 0)")
      .def_readwrite("origin_y", &core::GridGeometry::origin_y)
      .def_property_readonly(
          "shape", [](const core::GridGeometry& g) { return py::make_tuple(g.height, g.width); },
          "(height, width): the shape of the grid's arrays")
      .def("size", &core::GridGeometry::size)
      .def("contains", &core::GridGeometry::contains, "ix"_a, "iy"_a)
      .def("centre_x", &core::GridGeometry::centre_x, "ix"_a)
      .def("centre_y", &core::GridGeometry::centre_y, "iy"_a)
      .def("cell_x", &core::GridGeometry::cell_x, "x"_a)
      .def("cell_y", &core::GridGeometry::cell_y, "y"_a)
      .def("check", &core::check_geometry, "Raises ValueError unless the geometry is usable.")
      .def("__eq__",
           [](const core::GridGeometry& a, const core::GridGeometry& b) {
             return a.width == b.width && a.height == b.height && a.resolution == b.resolution &&
                    a.origin_x == b.origin_x && a.origin_y == b.origin_y;
           })
      .def("__repr__", [](const core::GridGeometry& g) {
        return "GridGeometry(width=" + std::to_string(g.width) +
               ", height=" + std::to_string(g.height) + ", resolution=" + number(g.resolution) +
               ", origin_x=" + number(g.origin_x) + ", origin_y=" + number(g.origin_y) + ")";
      });

  py::class_<core::ProbabilityGrid>(m, "ProbabilityGrid",
                                    "P(occupied) per cell. cells: float64 array (height, width), "
                                    "row 0 = bottom row.")
      .def(py::init(&probability_grid), "cells"_a, "geometry"_a)
      .def(py::init([](const core::GridGeometry& geometry, double fill) {
             return core::ProbabilityGrid(geometry, fill);
           }),
           "geometry"_a, "fill"_a = 0.5)
      .def_property_readonly("geometry", [](const core::ProbabilityGrid& g) { return g.geometry; })
      .def_property(
          "cells", [](const core::ProbabilityGrid& g) { return to_numpy(g); },
          [](core::ProbabilityGrid& g, const CArray<double>& cells) {
            g = probability_grid(cells, g.geometry);
          },
          "a new (height, width) float64 array of the cells; [iy, ix] is cell (ix, iy)")
      .def(
          "at",
          [](const core::ProbabilityGrid& g, int ix, int iy) {
            check_index(ix, g.geometry.width, "ix");
            check_index(iy, g.geometry.height, "iy");
            return g.at(ix, iy);
          },
          "ix"_a, "iy"_a)
      .def("__repr__", [](const core::ProbabilityGrid& g) {
        return "ProbabilityGrid(" + std::to_string(g.geometry.width) + " x " +
               std::to_string(g.geometry.height) + " cells of " + number(g.geometry.resolution) +
               " m)";
      });

  py::class_<core::Grid<std::int8_t>>(m, "IndexGrid",
                                      "S_eps indices per cell. cells: int8 array (height, width), "
                                      "row 0 = bottom row.")
      .def(py::init(&index_grid<std::int8_t>), "cells"_a, "geometry"_a)
      .def_property_readonly("geometry",
                             [](const core::Grid<std::int8_t>& g) { return g.geometry; })
      .def_property(
          "cells", [](const core::Grid<std::int8_t>& g) { return to_numpy(g); },
          [](core::Grid<std::int8_t>& g, const py::array& cells) {
            g = index_grid<std::int8_t>(cells, g.geometry);
          },
          "a new (height, width) int8 array of the cells; [iy, ix] is cell (ix, iy)")
      .def(
          "probabilities",
          [](const core::Grid<std::int8_t>& g, const core::SepsCodec& codec) {
            return core::to_probabilities(g, codec);
          },
          "The ProbabilityGrid of p_n per cell.", "codec"_a)
      .def("__repr__", [](const core::Grid<std::int8_t>& g) {
        return "IndexGrid(" + std::to_string(g.geometry.width) + " x " +
               std::to_string(g.geometry.height) + " cells of " + number(g.geometry.resolution) +
               " m)";
      });
}

// --- Sensor models and the ISMs ---------------------------------------------------------------

void bind_isms(py::module_& m) {
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

// --- S_eps and U_gamma -------------------------------------------------------------------------

template <class Index>
py::array_t<Index> fuse_index_arrays(const py::array_t<Index, py::array::c_style>& a,
                                     const py::array_t<Index, py::array::c_style>& b,
                                     int max_index) {
  if (max_index < 1 || max_index > std::numeric_limits<Index>::max())
    value_error("max_index must be 1.." + std::to_string(std::numeric_limits<Index>::max()) +
                " for this dtype, got " + std::to_string(max_index));
  if (a.ndim() != b.ndim() || !std::equal(a.shape(), a.shape() + a.ndim(), b.shape()))
    value_error("fuse_indices: the arrays' shapes differ");
  py::array_t<Index> out(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
  const auto n = static_cast<std::size_t>(a.size());
  core::fuse_indices<Index>(std::span<const Index>(a.data(), n),
                            std::span<const Index>(b.data(), n),
                            std::span<Index>(out.mutable_data(), n), max_index);
  return out;
}

void bind_seps(py::module_& m) {
  m.def("logit", &core::logit, "p"_a);
  m.def("logistic", &core::logistic, "x"_a);
  m.def("max_index_for_bits", &core::max_index_for_bits,
        "2^(bits-1) - 1; raises ValueError unless 2 <= bits <= 16.", "bits"_a);

  py::class_<core::SepsCodec>(m, "SepsCodec",
                              "S_eps indices of `bits` bits: p_n has log-odds n * lambda, "
                              "lambda = logit(1/2 + eps); fusion is saturating addition.")
      .def(py::init<int, double>(), "bits"_a, "eps"_a)
      .def_static("for_confidence", &core::SepsCodec::for_confidence,
                  "eps such that p_max_index equals p_most.", "bits"_a, "p_most"_a)
      .def_static("for_levels", &core::SepsCodec::for_levels, "eps such that p_levels equals pmax.",
                  "bits"_a, "pmax"_a, "levels"_a)
      .def_property_readonly("bits", &core::SepsCodec::bits)
      .def_property_readonly("eps", &core::SepsCodec::eps)
      .def_property_readonly("lambda_", &core::SepsCodec::lambda, "logit(1/2 + eps)")
      .def_property_readonly("max_index", &core::SepsCodec::max_index)
      .def("probability",
           py::vectorize([](const core::SepsCodec* c, int n) { return c->probability(n); }),
           "p_n (vectorized over arrays).", "n"_a)
      .def("quantize_conservative", py::vectorize([](const core::SepsCodec* c, double p) {
             return c->quantize_conservative(p);
           }),
           "The index of largest magnitude never more confident than p (vectorized).", "p"_a)
      .def("quantize_nearest",
           py::vectorize([](const core::SepsCodec* c, double p) { return c->quantize_nearest(p); }),
           "The index nearest p in log-odds (vectorized).", "p"_a)
      .def("fuse",
           py::vectorize([](const core::SepsCodec* c, int a, int b) { return c->fuse(a, b); }),
           "Saturating index addition (vectorized).", "a"_a, "b"_a)
      .def("__repr__", [](const core::SepsCodec& c) {
        return "SepsCodec(bits=" + std::to_string(c.bits()) + ", eps=" + number(c.eps()) + ")";
      });

  m.def("fuse_indices", &fuse_index_arrays<std::int8_t>, "a"_a, "b"_a, "max_index"_a);
  m.def("fuse_indices", &fuse_index_arrays<std::int16_t>,
        "Cell-wise saturating addition of two int8 (or int16) index arrays of one shape: "
        "clip(a + b, -max_index, max_index).",
        "a"_a, "b"_a, "max_index"_a);

  m.def("fuse_probabilities", py::overload_cast<double, double>(&core::fuse_probabilities), "p"_a,
        "q"_a);
  m.def(
      "fuse_probabilities",
      [](const CArray<double>& p, const CArray<double>& q) {
        if (p.ndim() != q.ndim() || !std::equal(p.shape(), p.shape() + p.ndim(), q.shape()))
          value_error("fuse_probabilities: the arrays' shapes differ");
        py::array_t<double> out(std::vector<py::ssize_t>(p.shape(), p.shape() + p.ndim()));
        const auto n = static_cast<std::size_t>(p.size());
        core::fuse_probabilities(std::span<const double>(p.data(), n),
                                 std::span<const double>(q.data(), n),
                                 std::span<double>(out.mutable_data(), n));
        return out;
      },
      "Bayesian fusion pq / (pq + (1-p)(1-q)) of two probabilities or two arrays of one shape.",
      "p"_a, "q"_a);

  py::class_<core::UGamma>(m, "UGamma",
                           "Probabilities as integer exponents u_n = gamma^n, gamma = "
                           "2^(-1/steps_per_halving).")
      .def(py::init<int, int>(), "bits"_a = 16, "steps_per_halving"_a = 16)
      .def_property_readonly("bits", &core::UGamma::bits)
      .def_property_readonly("steps_per_halving", &core::UGamma::steps_per_halving)
      .def_property_readonly("gamma", &core::UGamma::gamma)
      .def_property_readonly("zero", &core::UGamma::zero, "the code of probability 0")
      .def_property_readonly("min_index", &core::UGamma::min_index)
      .def("multiply", &core::UGamma::multiply, "i"_a, "j"_a)
      .def("divide", &core::UGamma::divide, "i"_a, "j"_a)
      .def("add", &core::UGamma::add, "i"_a, "j"_a)
      .def("complement", &core::UGamma::complement, "i"_a)
      .def("fuse", &core::UGamma::fuse, "i"_a, "j"_a)
      .def("from_probability", &core::UGamma::from_probability, "p"_a)
      .def("to_probability", &core::UGamma::to_probability, "i"_a)
      .def("from_log", &core::UGamma::from_log, "ln_u"_a)
      .def("to_log", &core::UGamma::to_log, "i"_a);
}

// --- Mapping with known poses ------------------------------------------------------------------

std::vector<core::Scan> scans_of(const py::object& scans) {
  if (py::isinstance<core::Log>(scans)) return scans.cast<const core::Log&>().scans;
  return scans.cast<std::vector<core::Scan>>();
}

struct MapSettings {
  core::GaussianBeamModel model;
  double cell;
  int bits;
  int levels;
  std::optional<double> eps;
  core::VetoBound veto;
  core::GridGeometry geometry;
};

MapSettings map_settings(const std::vector<core::Scan>& scans, double cell, double sigma,
                         double k_d, int bits, int levels, std::optional<double> eps,
                         const std::string& veto, double margin,
                         const std::optional<core::GridGeometry>& geometry) {
  const core::GaussianBeamModel model{sigma, k_d};
  core::check_model(model);
  check_positive(cell, "cell");
  core::GridGeometry g;
  if (geometry) {
    g = *geometry;
    core::check_geometry(g);
    if (g.resolution != cell)
      value_error("geometry.resolution (" + number(g.resolution) + ") differs from cell (" +
                  number(cell) + ")");
  } else {
    check_finite(margin, "margin");
    g = core::geometry_covering(scans, cell, margin);
  }
  return {model, cell, bits, levels, eps, veto_of(veto), g};
}

// The codec of `intgrid map`: eps given, or p_levels = Pmax of the ISM.
core::SepsCodec map_codec(const MapSettings& s) {
  if (s.eps) return core::SepsCodec(s.bits, *s.eps);
  return core::SepsCodec::for_levels(s.bits, core::narrow_pmax(s.cell, s.model.sigma0), s.levels);
}

template <class Index>
core::Grid<Index> map_with_indices(const std::vector<core::Scan>& scans, const MapSettings& s,
                                   const core::SepsCodec& codec) {
  core::IndexScanInserter<Index> inserter(s.model, s.cell, codec, s.veto);
  core::InsertionStats stats;
  return core::map_indices(scans, inserter, s.geometry, stats);
}

void bind_mapping(py::module_& m) {
  m.def(
      "geometry_covering",
      [](const py::object& scans, double resolution, double margin) {
        return core::geometry_covering(scans_of(scans), resolution, margin);
      },
      "A grid covering every sensor position and valid reading's end point, plus margin (m).",
      "scans"_a, "resolution"_a, "margin"_a = 1.0);

  m.def(
      "map_from_scans",
      [](const py::object& scans_or_log, double cell, const py::object& arithmetic, double sigma,
         double k_d, int bits, int levels, std::optional<double> eps, const std::string& veto,
         double margin, const std::optional<core::GridGeometry>& geometry) {
        const std::vector<core::Scan> scans = scans_of(scans_or_log);
        const core::Arithmetic a = arithmetic_of(arithmetic);
        const MapSettings s =
            map_settings(scans, cell, sigma, k_d, bits, levels, eps, veto, margin, geometry);
        core::ProbabilityGrid grid;
        {
          py::gil_scoped_release release;
          if (a == core::Arithmetic::integer) {
            const core::SepsCodec codec = map_codec(s);
            grid = bits <= 8 ? core::to_probabilities(
                                   map_with_indices<std::int8_t>(scans, s, codec), codec)
                             : core::to_probabilities(
                                   map_with_indices<std::int16_t>(scans, s, codec), codec);
          } else {
            core::InsertionStats stats;
            grid = core::map_probabilities(scans, s.model, s.geometry, stats);
          }
        }
        return py::make_tuple(to_numpy(grid), grid.geometry);
      },
      "Maps scans (a list or a Log) with their own poses, as `intgrid map` does: returns "
      "(P(occupied) float64 array (height, width), row 0 = bottom; GridGeometry). 'int': S_eps "
      "indices of `bits` bits (eps from `levels`, or `eps`), veto 'claim' or 'none'; 'float': "
      "Bayesian fusion in double.",
      "scans"_a, "cell"_a = 0.05, "arithmetic"_a = "int", "sigma"_a = 0.05, "k_d"_a = 0.0,
      "bits"_a = 8, "levels"_a = 16, "eps"_a = py::none(), "veto"_a = "claim", "margin"_a = 1.0,
      "geometry"_a = py::none());

  m.def(
      "map_indices",
      [](const py::object& scans_or_log, double cell, double sigma, double k_d, int bits,
         int levels, std::optional<double> eps, const std::string& veto, double margin,
         const std::optional<core::GridGeometry>& geometry) {
        const std::vector<core::Scan> scans = scans_of(scans_or_log);
        const MapSettings s =
            map_settings(scans, cell, sigma, k_d, bits, levels, eps, veto, margin, geometry);
        const core::SepsCodec codec = map_codec(s);
        py::object cells;
        if (bits <= 8) {
          core::Grid<std::int8_t> grid;
          {
            py::gil_scoped_release release;
            grid = map_with_indices<std::int8_t>(scans, s, codec);
          }
          cells = to_numpy(grid);
        } else {
          core::Grid<std::int16_t> grid;
          {
            py::gil_scoped_release release;
            grid = map_with_indices<std::int16_t>(scans, s, codec);
          }
          cells = to_numpy(grid);
        }
        return py::make_tuple(cells, s.geometry, codec);
      },
      "The integer map itself: (S_eps index array (height, width), int8 for bits <= 8 else "
      "int16, row 0 = bottom; GridGeometry; SepsCodec).",
      "scans"_a, "cell"_a = 0.05, "sigma"_a = 0.05, "k_d"_a = 0.0, "bits"_a = 8, "levels"_a = 16,
      "eps"_a = py::none(), "veto"_a = "claim", "margin"_a = 1.0, "geometry"_a = py::none());
}

// --- Readers and writers (intgrid.io) ---------------------------------------------------------

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

// --- Global localization -----------------------------------------------------------------------

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
      .def_readwrite("sigma", &GlobalLocConfig::sigma, "range noise (m)")
      .def_readwrite("max_range", &GlobalLocConfig::max_range, "readings at or past it unused (m)")
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

// --- SLAM ------------------------------------------------------------------------------------

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

  py::class_<SubmapSlamConfig::Sensor> sensor(config, "Sensor", "The ISM's beam model.");
  def_fields_init<SubmapSlamConfig::Sensor>(sensor);
  sensor.def_readwrite("sigma", &SubmapSlamConfig::Sensor::sigma, "range noise (m)")
      .def_readwrite("max_range", &SubmapSlamConfig::Sensor::max_range,
                     "readings at or past it unused (m)");

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
                     "once complete, match its first `scans` nodes again against it");

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
                     "threads of the back end's searches (0: every core); the same result")
      .def_readwrite("sensor", &SubmapSlamConfig::sensor)
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

void bind_slam(py::module_& m) {
  using slam::GridSlamConfig;
  py::class_<GridSlamConfig> config(
      m, "GridSlamConfig",
      "Options of a SLAM run, nested by concern (the `slam` defaults). "
      "GridSlamConfig(cell=0.1, ...) sets top-level fields; nested ones are "
      "set in place: config.beam.sigma = 0.03.");
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
  beam.def_readwrite("sigma", &GridSlamConfig::BeamModel::sigma, "range noise (m)")
      .def_readwrite("likelihood_floor", &GridSlamConfig::BeamModel::likelihood_floor)
      .def_readwrite("beams", &GridSlamConfig::BeamModel::beams)
      .def_readwrite("tempering", &GridSlamConfig::BeamModel::tempering)
      .def_readwrite("max_range", &GridSlamConfig::BeamModel::max_range, "m");

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

}  // namespace
}  // namespace intgrid::python

PYBIND11_MODULE(intgrid, m) {
  using namespace intgrid::python;
  m.doc() =
      "intgrid: integer-arithmetic occupancy grids. Grids are copied into numpy arrays of shape "
      "(height, width) whose row 0 is the bottom row of the map (cell (ix, iy) at [iy, ix]).";
  bind_types(m);
  bind_isms(m);
  bind_seps(m);
  bind_mapping(m);
  bind_io(m);
  bind_localization(m);
  bind_slam(m);
}
