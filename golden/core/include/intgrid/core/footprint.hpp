// Range mapping of a beam's polar cells onto a cartesian grid (thesis 2.6):
// every grid cell whose centre falls inside the beam's angular footprint takes
// the line-of-sight cell k = round(rho / s) of its distance rho to the sensor.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "intgrid/core/grid.hpp"

namespace intgrid::core {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};
inline double cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}
inline double dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
inline Vec2 unit_vector(double angle) {
  return {std::cos(angle), std::sin(angle)};
}

// A band of grid rows, first to last: insertion restricted to it touches its cells only, so the
// bands of one grid can be filled apart (by threads) and give the cells whole rows would.
struct RowBand {
  int first = 0;
  int last = std::numeric_limits<int>::max();
};

// Calls visit(cell_index, k) once for every grid cell of the rows `rows` whose centre c satisfies
//   cross(from, c - sensor) >= 0 and cross(to, c - sensor) < 0 (the half-open
//   angular interval [from, to), `to` counter-clockwise of `from` by less than pi),
//   and 1 <= round(|c - sensor| / cell) = k <= cells.
// Adjacent beams share a boundary vector, so every cell falls in exactly one.
// The interval of vx satisfying side * (d.x * vy - d.y * vx) >= 0 for one row,
// widened to [lo, hi]: the half-plane left (side 1) or right (side -1) of d.
inline void clip_to_half_plane(Vec2 d, double vy, double side, double& lo, double& hi) {
  const double a = -side * d.y, b = side * d.x * vy;  // a * vx + b >= 0
  if (a > 0.0)
    lo = std::max(lo, -b / a);
  else if (a < 0.0)
    hi = std::min(hi, -b / a);
  else if (b < 0.0)
    hi = lo - 1.0;  // the row lies wholly outside
}

template <class Visit>
void for_each_footprint_cell(const GridGeometry& grid, Vec2 sensor, Vec2 from, Vec2 to, double cell,
                             std::size_t cells, Visit&& visit, RowBand rows = {}) {
  const Vec2 mid{from.x + to.x, from.y + to.y};
  const double reach = (static_cast<double>(cells) + 0.5) * cell;
  const double reach_sq = reach * reach;
  const double inv_cell = 1.0 / cell;
  // The sector lies in the triangle sensor, sensor + far from, sensor + far to,
  // with far the reach over the cosine of the half angle: its rows bound the loop.
  const double far = reach / std::sqrt(std::max(0.5 * (1.0 + dot(from, to)), 1e-12));
  const double y_lo = sensor.y + far * std::min({0.0, from.y, to.y});
  const double y_hi = sensor.y + far * std::max({0.0, from.y, to.y});
  const int row_lo = std::max({0, grid.cell_y(y_lo) - 1, rows.first});
  const int row_hi = std::min({grid.height - 1, grid.cell_y(y_hi) + 1, rows.last});
  for (int iy = row_lo; iy <= row_hi; ++iy) {
    const double vy = grid.centre_y(iy) - sensor.y;
    if (vy * vy >= reach_sq) continue;
    // The row's candidate cells: those whose centres lie in the intersection of
    // the disc and the three half-planes, widened by a hair against rounding;
    // the exact test below decides, with the same arithmetic for every beam.
    const double half_chord = std::sqrt(reach_sq - vy * vy);
    double lo = -half_chord, hi = half_chord;
    clip_to_half_plane(from, vy, 1.0, lo, hi);
    clip_to_half_plane(to, vy, -1.0, lo, hi);
    clip_to_half_plane({-mid.y, mid.x}, vy, -1.0, lo, hi);
    const double hair = 1e-9 * reach;
    const double first = std::ceil((sensor.x + lo - hair - grid.origin_x) / grid.resolution - 0.5);
    const double last = std::floor((sensor.x + hi + hair - grid.origin_x) / grid.resolution - 0.5);
    if (first > last) continue;
    const int col_lo = static_cast<int>(std::max(first, 0.0));
    const int col_hi = static_cast<int>(std::min(last, grid.width - 1.0));
    for (int ix = col_lo; ix <= col_hi; ++ix) {
      const Vec2 v{grid.centre_x(ix) - sensor.x, vy};
      if (cross(from, v) < 0.0 || cross(to, v) >= 0.0 || dot(mid, v) <= 0.0) continue;
      const double rho_sq = v.x * v.x + v.y * v.y;
      if (rho_sq >= reach_sq) continue;
      const auto k = static_cast<std::size_t>(std::sqrt(rho_sq) * inv_cell + 0.5);
      if (k >= 1 && k <= cells) visit(grid.index(ix, iy), k);
    }
  }
}

}  // namespace intgrid::core
