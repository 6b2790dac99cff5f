// The Python module `intgrid`: the ISMs, S_eps fusion, mapping with known poses, global
// localization of one scan, SLAM scan by scan, and the readers and writers (intgrid.io).
//
// Grids cross the boundary as copies in numpy arrays of shape (height, width): element [iy, ix] is
// cell (ix, iy) of the C++ grid, so row 0 is the BOTTOM row of the map (y grows with the row), the
// opposite of an image. C++ std::invalid_argument arrives as ValueError, io::InputError as
// intgrid.io.InputError (a ValueError), std::runtime_error as RuntimeError.
#include <pybind11/pybind11.h>

#include "bindings.hpp"

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
  bind_navigation(m);
}
