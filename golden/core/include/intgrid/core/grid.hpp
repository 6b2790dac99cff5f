// A 2D cartesian grid over the world plane. Cell (0, 0) is the lower-left cell;
// x grows with the column, y with the row (the ROS map_server convention once
// the image rows are flipped).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "intgrid/core/failure.hpp"

namespace intgrid::core {

struct GridGeometry {
  int width = 0;
  int height = 0;
  double resolution = 0.0;  // metres per cell
  double origin_x = 0.0;    // world position of the lower-left corner of cell (0, 0)
  double origin_y = 0.0;

  std::size_t size() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  bool contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < width && iy < height; }
  std::size_t index(int ix, int iy) const {
    return static_cast<std::size_t>(iy) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(ix);
  }
  // World coordinates of a cell centre.
  double centre_x(int ix) const { return origin_x + (ix + 0.5) * resolution; }
  double centre_y(int iy) const { return origin_y + (iy + 0.5) * resolution; }
  // Cell holding a world point (may lie outside the grid).
  int cell_x(double x) const { return static_cast<int>(std::floor((x - origin_x) / resolution)); }
  int cell_y(double y) const { return static_cast<int>(std::floor((y - origin_y) / resolution)); }
};

// Throws std::invalid_argument unless the geometry describes a usable grid whose
// cell count fits in memory indices.
inline void check_geometry(const GridGeometry& g) {
  if (!(g.resolution > 0.0) || !std::isfinite(g.resolution))
    fail<std::invalid_argument>("grid resolution must be a positive finite number");
  if (g.width <= 0 || g.height <= 0) fail<std::invalid_argument>("grid size must be positive");
  if (!std::isfinite(g.origin_x) || !std::isfinite(g.origin_y))
    fail<std::invalid_argument>("grid origin must be finite");
  // 2^32, or what a 32-bit size_t can count.
  constexpr std::uint64_t kMaxCells =
      std::min<std::uint64_t>(std::uint64_t{1} << 32, std::numeric_limits<std::size_t>::max());
  if (static_cast<std::uint64_t>(g.width) * static_cast<std::uint64_t>(g.height) > kMaxCells)
    fail<std::invalid_argument>("grid has more than 2^32 cells");
}

template <class T>
struct Grid {
  GridGeometry geometry;
  std::vector<T> cells;

  Grid() = default;
  Grid(const GridGeometry& g, T fill) : geometry(g) {
    check_geometry(g);
    cells.assign(g.size(), fill);
  }
  T& at(int ix, int iy) { return cells[geometry.index(ix, iy)]; }
  const T& at(int ix, int iy) const { return cells[geometry.index(ix, iy)]; }
};

// Occupancy probabilities, P(occupied) per cell.
using ProbabilityGrid = Grid<double>;

}  // namespace intgrid::core
