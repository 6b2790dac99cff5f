// intgrid's poses, scans, logs and grids in Python.
#include "bindings.hpp"

namespace intgrid::python {

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

}  // namespace intgrid::python
