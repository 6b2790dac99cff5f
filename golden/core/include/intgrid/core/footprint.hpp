// Range mapping of a beam's polar cells onto a cartesian grid (thesis 2.6):
// every grid cell whose centre falls inside the beam's angular footprint takes
// the line-of-sight cell k = round(rho / s) of its distance rho to the sensor.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
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

// |v|^2 as the footprint computes it for a cell centre v from the sensor.
inline double squared_length(Vec2 v) {
  return v.x * v.x + v.y * v.y;
}

// The line-of-sight cell k = round(|v| / cell) of a cell centre at |v|^2 = rho_sq from the
// sensor (inv_cell = 1 / cell), as for_each_footprint_cell computes it: monotone in rho_sq.
inline std::size_t line_of_sight_cell(double rho_sq, double inv_cell) {
  return static_cast<std::size_t>(std::sqrt(rho_sq) * inv_cell + 0.5);
}

// The least rho_sq >= 0 whose line-of-sight cell is k >= 1 or more, exactly: bisection over the
// bit patterns of the non-negative doubles, which they order as their values. Cells closer than
// it have a smaller k, cells at or past it k or more.
inline double least_rho_sq_reaching(std::size_t k, double cell) {
  const double inv_cell = 1.0 / cell;
  const double above = 4.0 * std::pow((static_cast<double>(k) + 1.0) * cell, 2);
  std::uint64_t lo = 0, hi = std::bit_cast<std::uint64_t>(above);  // cell(lo) < k <= cell(hi)
  while (hi - lo > 1) {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    if (line_of_sight_cell(std::bit_cast<double>(mid), inv_cell) >= k)
      hi = mid;
    else
      lo = mid;
  }
  return std::bit_cast<double>(hi);
}

namespace footprint_detail {

// The positions along one grid line (a row, or a column in transposed coordinates) that a
// half-plane side * cross(d, u) >= 0 keeps, u the cell centre's offset from the sensor in the
// line's coordinates (along, across): u.along >= bound (a lower bound), <= bound (an upper bound),
// all of them or none, with bound = across * d.x / d.y. Set up once a footprint, so that a line
// costs one multiplication.
class HalfPlaneSpan {
 public:
  HalfPlaneSpan(Vec2 d, double side)
      : slope_(d.y != 0.0 ? d.x / d.y : 0.0), a_(-side * d.y), b_per_across_(side * d.x) {}
  // Narrows [lo, hi] to the half-plane on the line at `across`.
  void clip(double across, double& lo, double& hi) const {
    if (a_ > 0.0)
      lo = std::max(lo, across * slope_);
    else if (a_ < 0.0)
      hi = std::min(hi, across * slope_);
    else if (b_per_across_ * across < 0.0)
      hi = -std::numeric_limits<double>::infinity();  // the line lies wholly outside
  }

 private:
  double slope_;
  double a_;             // a * along + b >= 0,
  double b_per_across_;  // with b = b_per_across * across
};

inline Vec2 transposed(Vec2 v) {
  return {v.y, v.x};
}

}  // namespace footprint_detail

// Consecutive cells of one grid line: positions first..last along row `line` (positions are
// columns) or, along_rows false, along column `line` (positions are rows).
struct SectorRun {
  bool along_rows = true;
  int line = 0;
  int first = 0;
  int last = -1;
  std::size_t index(const GridGeometry& grid, int position) const {
    return along_rows ? grid.index(position, line) : grid.index(line, position);
  }
  // The centre of the cell at `position`, from the sensor.
  Vec2 offset(const GridGeometry& grid, Vec2 sensor, int position) const {
    return along_rows ? Vec2{grid.centre_x(position) - sensor.x, grid.centre_y(line) - sensor.y}
                      : Vec2{grid.centre_x(line) - sensor.x, grid.centre_y(position) - sensor.y};
  }
};

// Calls run(SectorRun) for the cells of the rows `rows` whose centre c, v = c - sensor, satisfies
//   cross(from, v) >= 0 and cross(to, v) < 0 (the half-open angular interval [from, to), `to`
//   counter-clockwise of `from` by less than pi), dot(from + to, v) > 0,
//   and inner_sq <= |v|^2 < outer_sq (|v|^2 computed as v.x * v.x + v.y * v.y),
// each cell once, as runs along grid lines.
//
// The sector is walked line by line across its length: rows for a sector closer to the x axis,
// columns for one closer to the y axis, so that a line holds as many of its cells as it can. A
// line's candidate cells come from the sector's edges (one multiplication each) and, only where
// the disc ends the line, its chord (a square root); they are widened by a hair against rounding.
// Along a line each comparison above changes at most once, except the inner one, which holds
// outside one interval (an offset that grows with the position, times a constant, less a
// constant: rounding keeps the order); so the exact test decides only the ends of a line's runs,
// and the cells do not depend on the walk.
template <class Run>
void for_each_sector_run(const GridGeometry& grid, Vec2 sensor, Vec2 from, Vec2 to, double inner_sq,
                         double outer_sq, Run&& run, RowBand rows = {}) {
  using footprint_detail::HalfPlaneSpan;
  using footprint_detail::transposed;
  const Vec2 mid{from.x + to.x, from.y + to.y};
  const auto inside_outer = [&](Vec2 v) {
    return cross(from, v) >= 0.0 && cross(to, v) < 0.0 && dot(mid, v) > 0.0 &&
           squared_length(v) < outer_sq;
  };
  const double outer = std::sqrt(outer_sq);
  // The cells lie in the quadrilateral inner from, inner to, far from, far to (the triangle
  // sensor, far from, far to less the one within the inner radius), with far the outer radius over
  // the cosine of the half angle: its rows and columns bound the walk.
  const double far = outer / std::sqrt(std::max(0.5 * (1.0 + dot(from, to)), 1e-12));
  const double inner = inner_sq > 0.0 ? std::sqrt(inner_sq) * (1.0 - 1e-9) : 0.0;
  const auto bound = [&](double s, double f, double t, auto pick) {
    return s + pick({inner * f, inner * t, far * f, far * t});
  };
  const auto lowest = [](std::initializer_list<double> l) { return std::min(l); };
  const auto highest = [](std::initializer_list<double> l) { return std::max(l); };
  const int row_lo =
      std::max({0, grid.cell_y(bound(sensor.y, from.y, to.y, lowest)) - 1, rows.first});
  const int row_hi = std::min(
      {grid.height - 1, grid.cell_y(bound(sensor.y, from.y, to.y, highest)) + 1, rows.last});
  const int col_lo = std::max(0, grid.cell_x(bound(sensor.x, from.x, to.x, lowest)) - 1);
  const int col_hi =
      std::min(grid.width - 1, grid.cell_x(bound(sensor.x, from.x, to.x, highest)) + 1);
  if (row_lo > row_hi || col_lo > col_hi) return;
  const bool along_rows = std::abs(mid.x) >= std::abs(mid.y);
  // In the line's coordinates (along, across): v itself along rows, v transposed along columns,
  // where cross changes sign and so each half-plane its side.
  const double side = along_rows ? 1.0 : -1.0;
  const auto line = [&](Vec2 d) { return along_rows ? d : transposed(d); };
  const HalfPlaneSpan from_side(line(from), side), to_side(line(to), -side),
      front(line({-mid.y, mid.x}), -side);
  const Vec2 s = line(sensor);
  const Vec2 origin = line({grid.origin_x, grid.origin_y});
  const double hair = 1e-9 * outer;
  const double inv_resolution = 1.0 / grid.resolution;
  // The position of offset `along` in cells, less one half: the cell centred there is its ceil.
  const double position_of_sensor = (s.x - origin.x) * inv_resolution - 0.5;
  const int line_first = along_rows ? row_lo : col_lo, line_last = along_rows ? row_hi : col_hi;
  const int pos_first = along_rows ? col_lo : row_lo, pos_last = along_rows ? col_hi : row_hi;
  const double inf = std::numeric_limits<double>::infinity();
  SectorRun r;
  r.along_rows = along_rows;
  const auto emit = [&](int first, int last) {
    if (first > last) return;
    r.first = first;
    r.last = last;
    run(r);
  };
  for (int l = line_first; l <= line_last; ++l) {
    r.line = l;
    const double across = origin.y + (l + 0.5) * grid.resolution - s.y;
    const double chord_sq = outer_sq - across * across;  // (half the disc's chord here)^2
    if (chord_sq <= 0.0) continue;
    double lo = -inf, hi = inf;
    from_side.clip(across, lo, hi);
    to_side.clip(across, lo, hi);
    front.clip(across, lo, hi);
    if (!(lo <= hi)) continue;
    if (lo * lo > chord_sq || hi * hi > chord_sq) {
      const double half_chord = std::sqrt(chord_sq);
      lo = std::max(lo, -half_chord);
      hi = std::min(hi, half_chord);
    }
    // Clamped before the conversion to int, so that far-off sectors cannot overflow it.
    const double first = std::clamp(std::ceil(position_of_sensor + (lo - hair) * inv_resolution),
                                    static_cast<double>(pos_first), pos_last + 1.0);
    const double last = std::clamp(std::floor(position_of_sensor + (hi + hair) * inv_resolution),
                                   pos_first - 1.0, static_cast<double>(pos_last));
    int p_lo = static_cast<int>(first), p_hi = static_cast<int>(last);
    const auto v = [&](int p) { return r.offset(grid, sensor, p); };
    while (p_lo <= p_hi && !inside_outer(v(p_lo))) ++p_lo;
    while (p_hi > p_lo && !inside_outer(v(p_hi))) --p_hi;
    if (p_lo > p_hi) continue;
    if (!(across * across < inner_sq)) {
      emit(p_lo, p_hi);
      continue;
    }
    // The positions closer than the inner radius: one interval [a, b] around the sensor's foot.
    // Its estimate, widened by a position (far more than rounding can move it), is narrowed by
    // the exact comparison.
    const auto closer = [&](int p) { return squared_length(v(p)) < inner_sq; };
    const double half_chord = std::sqrt(inner_sq - across * across) * inv_resolution;
    int a = static_cast<int>(
        std::clamp(std::ceil(position_of_sensor - half_chord) - 1.0, p_lo - 1.0, p_hi + 1.0));
    int b = static_cast<int>(
        std::clamp(std::floor(position_of_sensor + half_chord) + 1.0, p_lo - 1.0, p_hi + 1.0));
    while (a <= b && !closer(a)) ++a;
    while (b >= a && !closer(b)) --b;
    if (a > b) {  // no position of the run is closer
      emit(p_lo, p_hi);
      continue;
    }
    emit(p_lo, std::min(p_hi, a - 1));
    emit(std::max(p_lo, b + 1), p_hi);
  }
}

// Calls visit(cell_index, k) once for every grid cell of the rows `rows` whose centre c satisfies
//   cross(from, c - sensor) >= 0 and cross(to, c - sensor) < 0 (the half-open
//   angular interval [from, to), `to` counter-clockwise of `from` by less than pi),
//   |c - sensor|^2 >= inner_sq and 1 <= round(|c - sensor| / cell) = k <= cells.
// Adjacent beams share a boundary vector, so every cell falls in exactly one.
template <class Visit>
void for_each_footprint_cell(const GridGeometry& grid, Vec2 sensor, Vec2 from, Vec2 to, double cell,
                             std::size_t cells, Visit&& visit, RowBand rows = {},
                             double inner_sq = 0.0) {
  const double reach = (static_cast<double>(cells) + 0.5) * cell;
  const double inv_cell = 1.0 / cell;
  for_each_sector_run(
      grid, sensor, from, to, inner_sq, reach * reach,
      [&](const SectorRun& r) {
        for (int p = r.first; p <= r.last; ++p) {
          const std::size_t k =
              line_of_sight_cell(squared_length(r.offset(grid, sensor, p)), inv_cell);
          if (k >= 1 && k <= cells) visit(r.index(grid, p), k);
        }
      },
      rows);
}

}  // namespace intgrid::core
