// Range mapping of a sensor's polar ISM onto a world cartesian grid (thesis 2.6.2) and
// multi-sensor fusion of the resulting grids (2.6.3). A narrow-FOV sensor is the polar
// grid of one bin whose width is the beam's.
#pragma once

#include <cstddef>
#include <span>
#include <stdexcept>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/footprint.hpp"
#include "intgrid/core/grid.hpp"
#include "intgrid/core/sectoral_ism.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/types.hpp"

namespace intgrid::core {

// Calls visit(cell_index, ring, bin) for every world cell whose centre falls in bin
// 0..bins-1 of the sensor's FOV (bin 0 on the clockwise edge) at ring
// round(distance / cell) in 1..rings. Every cell falls in at most one polar cell.
template <class Visit>
void for_each_polar_cell(const GridGeometry& world, const Pose2& sensor, const SectoralGrid& polar,
                         Visit&& visit) {
  const double bin_width = polar.fov / polar.bins;
  const double first = sensor.theta - 0.5 * polar.fov;
  Vec2 from = unit_vector(first);
  for (int bin = 0; bin < polar.bins; ++bin) {
    const Vec2 to = unit_vector(first + (bin + 1) * bin_width);
    for_each_footprint_cell(
        world, {sensor.x, sensor.y}, from, to, polar.cell, static_cast<std::size_t>(polar.rings),
        [&](std::size_t index, std::size_t k) { visit(index, static_cast<int>(k), bin); });
    from = to;
  }
}

// The mono-sensor grid: each world cell inside the FOV takes the value of the polar cell
// its centre falls in (values ring-major, as sectoral_ism returns them); the others keep
// `outside` (1/2, or index 0).
template <class T>
Grid<T> map_polar(const GridGeometry& world, const Pose2& sensor, const SectoralGrid& polar,
                  std::span<const T> values, T outside) {
  if (values.size() != polar.cells())
    fail<std::invalid_argument>("map_polar: values differ in size from the polar grid");
  Grid<T> grid(world, outside);
  for_each_polar_cell(world, sensor, polar, [&](std::size_t index, int ring, int bin) {
    grid.cells[index] =
        values[static_cast<std::size_t>(ring - 1) * static_cast<std::size_t>(polar.bins) +
               static_cast<std::size_t>(bin)];
  });
  return grid;
}

// Bayesian fusion of two grids of one geometry, cell by cell: F(p, q) for probabilities,
// saturating addition for S_eps indices.
inline ProbabilityGrid fuse_grids(const ProbabilityGrid& a, const ProbabilityGrid& b) {
  if (a.cells.size() != b.cells.size()) fail<std::invalid_argument>("fuse_grids: sizes differ");
  ProbabilityGrid out = a;
  fuse_probabilities(a.cells, b.cells, out.cells);
  return out;
}
template <class Index>
Grid<Index> fuse_grids(const Grid<Index>& a, const Grid<Index>& b, int max_index) {
  if (a.cells.size() != b.cells.size()) fail<std::invalid_argument>("fuse_grids: sizes differ");
  Grid<Index> out = a;
  fuse_indices<Index>(a.cells, b.cells, out.cells, max_index);
  return out;
}

}  // namespace intgrid::core
