// Scan insertion with integer geometry: angles in units of 2^-16 turn with a fixed-point sine
// table, positions in millimetres, rays walked cell by cell with exact integer comparisons, and
// each reading's narrow ISM precomputed per range bin. The SLAM's events walk the same rays; the
// embedded target runs this insertion as it is.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/sensor_model.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/units.hpp"

namespace intgrid::core {

// sin(2 pi a / 2^16) * 2^16 rounded, a = 0..2^16 - 1: the one table of the integer geometry.
std::vector<std::int32_t> make_sine_table_q16();

namespace ray_detail {
// a / b rounded toward minus infinity.
template <class Int>
constexpr Int floor_div(Int a, Int b) {
  const Int q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}
// floor(sqrt(v)) for v >= 0, bit by bit.
constexpr std::int64_t isqrt(std::int64_t v) {
  if (v <= 0) return 0;
  std::uint64_t x = static_cast<std::uint64_t>(v), root = 0, bit = std::uint64_t{1} << 62;
  while (bit > x) bit >>= 2;
  while (bit != 0) {
    if (x >= root + bit) {
      x -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return static_cast<std::int64_t>(root);
}
}  // namespace ray_detail

// Rays over a grid of cell_mm cells, with a sine table of make_sine_table_q16's.
class IntegerRays {
 public:
  IntegerRays(std::span<const std::int32_t> sin_q16, std::int32_t cell_mm)
      : sin_q16_(sin_q16), cell_mm_(cell_mm) {}

  std::int32_t cell_mm() const { return cell_mm_; }
  std::int32_t sin(std::int32_t a) const { return sin_q16_[static_cast<std::size_t>(a & 0xFFFF)]; }
  std::int32_t cos(std::int32_t a) const {
    return sin_q16_[static_cast<std::size_t>((a + 16384) & 0xFFFF)];
  }
  // (x, y) turned by the angle a, in the units of x and y.
  std::pair<std::int64_t, std::int64_t> rotate(std::int32_t a, std::int64_t x,
                                               std::int64_t y) const {
    const std::int64_t c = cos(a), s = sin(a);
    return {(c * x - s * y) >> 16, (s * x + c * y) >> 16};
  }

  // Visits every cell the ray crosses from (px, py) (mm from the centre of cell (0, 0)) in
  // direction `angle`, as visit(cell dx, cell dy, d) with d the distance in mm along the ray of
  // the cell centre's projection, until d passes limit_mm. Crossings are decided by exact
  // integer comparisons of the distances to the next cell boundaries (Amanatides-Woo).
  // Requires cell_mm <= 10^4, |px| and |py| < 2^29 and limit_mm < 2^40.
  template <class Visit>
  void walk(std::int64_t px, std::int64_t py, std::int32_t angle, std::int64_t limit_mm,
            Visit&& visit) const {
    using ray_detail::floor_div;
    const std::int64_t c = cell_mm_, c2 = 2 * c;        // doubled millimetres
    const std::int64_t x = 2 * px + c, y = 2 * py + c;  // from the cell's lower-left corner
    // In 32 bits: a 64-bit division is a library call on a 32-bit core.
    const auto x32 = static_cast<std::int32_t>(x), y32 = static_cast<std::int32_t>(y);
    const auto c2_32 = static_cast<std::int32_t>(c2);
    int ix = floor_div(x32, c2_32), iy = floor_div(y32, c2_32);
    const std::int32_t cs = cos(angle), sn = sin(angle);
    const int step_x = cs > 0 ? 1 : -1, step_y = sn > 0 ? 1 : -1;
    const std::int64_t acs = cs < 0 ? -cs : cs, asn = sn < 0 ? -sn : sn;
    // The ray meets first the boundary with the smaller bx / |cos| versus by / |sin| (bx, by the
    // distances along each axis to the next boundary): cross-multiplied, tx = bx |sin| against
    // ty = by |cos|. They, and 2^17 d, are updated step by step rather than recomputed (the
    // same integers, without a multiply per cell); the steps fit 32 bits.
    std::int64_t tx = (step_x > 0 ? (ix + 1) * c2 - x : x - ix * c2) * asn;
    std::int64_t ty = (step_y > 0 ? (iy + 1) * c2 - y : y - iy * c2) * acs;
    const auto tx_step = static_cast<std::int32_t>(c2 * asn);
    const auto ty_step = static_cast<std::int32_t>(c2 * acs);
    std::int64_t d_q17 = (ix * c2 + c - x) * cs + (iy * c2 + c - y) * sn;
    const auto d_step_x = static_cast<std::int32_t>(step_x * c2 * cs);
    const auto d_step_y = static_cast<std::int32_t>(step_y * c2 * sn);
    const std::int64_t end_q17 = (limit_mm + 1) * (std::int64_t{1} << 17);  // d > limit_mm
    while (d_q17 < end_q17) {
      visit(ix, iy, d_q17 >> 17);
      if (tx < ty) {
        ix += step_x;
        tx += tx_step;
        d_q17 += d_step_x;
      } else {
        iy += step_y;
        ty += ty_step;
        d_q17 += d_step_y;
      }
    }
  }

 private:
  std::span<const std::int32_t> sin_q16_;
  std::int32_t cell_mm_;
};

// The narrow ISM of every reading, precomputed: for a reading rounded to z_step_mm, the values
// of line-of-sight cells 1..n. S_eps indices (std::int8_t) or probabilities (double).
template <class T>
struct IsmTable {
  std::int32_t z_step_mm = 1;
  std::vector<std::uint32_t> begin;  // per z bin, into values; begin.size() = bins + 1
  std::vector<T> values;
  std::uint32_t longest = 0;  // the most cells of one reading

  // The cells of a reading of z_mm, 0 <= z_mm < the table's range.
  std::span<const T> reading(std::int32_t z_mm) const {
    const auto bin = static_cast<std::size_t>((z_mm + z_step_mm / 2) / z_step_mm);
    return {values.data() + begin[bin], begin[bin + 1] - begin[bin]};
  }
};
using NarrowIsmTable = IsmTable<std::int8_t>;

// A table from its bins, with `longest` derived from them.
template <class T>
IsmTable<T> make_ism_table(std::int32_t z_step_mm, std::vector<std::uint32_t> begin,
                           std::vector<T> values) {
  IsmTable<T> table{z_step_mm, std::move(begin), std::move(values)};
  for (std::size_t b = 0; b + 1 < table.begin.size(); ++b)
    table.longest = std::max(table.longest, table.begin[b + 1] - table.begin[b]);
  return table;
}

// The integer table for readings below max_range_mm: the scan inserter's conservatively quantized
// beams, the occupied bound veto (VetoBound::strongest_claim), and empty indices divided by
// empty_divisor (rounded away from 0).
NarrowIsmTable make_index_ism_table(const GaussianBeamModel& model, double cell,
                                    const SepsCodec& codec, std::int32_t z_step_mm,
                                    std::int32_t max_range_mm, int empty_divisor);
// The double table: the exact ISM over the cells ism_cells_for_reading gives.
IsmTable<double> make_probability_ism_table(const GaussianBeamModel& model, double cell,
                                            std::int32_t z_step_mm, std::int32_t max_range_mm);

// Lays every usable reading (0 < z < max_range_mm) of a scan taken from (px, py) mm off the
// centre of cell (0, 0), sensor heading `heading`, along its ray: visit(dx, dy, value) for every
// line-of-sight cell k = round(d / cell) in 1..n the ray crosses, with value the table's entry k.
template <class T, class Visit>
void for_each_ism_cell(const IntegerRays& rays, const IsmTable<T>& table, std::int64_t px,
                       std::int64_t py, std::int32_t heading, std::span<const std::int32_t> bearing,
                       std::span<const std::int32_t> range_mm, std::int32_t max_range_mm,
                       Visit&& visit) {
  const std::int32_t c = rays.cell_mm();
  for (std::size_t b = 0; b < range_mm.size(); ++b) {
    const std::int32_t z = range_mm[b];
    if (z <= 0 || z >= max_range_mm) continue;
    const std::span<const T> values = table.reading(z);
    const auto cells = static_cast<std::int32_t>(values.size());
    // Captures by value: on a core of 13 registers, a reference is a reload per cell.
    rays.walk(px, py, heading + bearing[b], std::int64_t{cells} * c + c / 2,
              [c, cells, first = values.data(), &visit](int dx, int dy, std::int64_t d) {
                // The line-of-sight cell, 1-based: d lies within the walk, so 32 bits divide it
                // (one instruction on a 32-bit core, a library call in 64).
                const std::int32_t k = (static_cast<std::int32_t>(d) + c / 2) / c;
                if (k >= 1 && k <= cells) visit(dx, dy, first[k - 1]);
              });
  }
}

// Bayesian fusion of one ISM value into a cell: saturating index addition, or Bayes' rule.
inline void fuse_into(std::int8_t& cell, std::int8_t value, int max_index) {
  cell = fuse_indices(cell, value, max_index);
}
inline void fuse_into(double& cell, double value, int /*max_index*/) {
  cell = fuse_probabilities(cell, value);
}

// Scan insertion into a grid: the sensor at (px, py) mm off the centre of cell (cx, cy), heading
// `heading`; cells outside the grid are skipped. max_index bounds S_eps sums (unused for
// probabilities). Allocates nothing.
template <class T>
void insert_scan_along_rays(Grid<T>& grid, const IntegerRays& rays, const IsmTable<T>& table,
                            int cx, int cy, std::int64_t px, std::int64_t py, std::int32_t heading,
                            std::span<const std::int32_t> bearing,
                            std::span<const std::int32_t> range_mm, std::int32_t max_range_mm,
                            int max_index) {
  const int width = grid.geometry.width, height = grid.geometry.height;
  // When the longest ray stays inside the grid, no cell needs a bounds check.
  const std::int64_t c = rays.cell_mm();
  const std::int64_t reach =
      (std::int64_t{table.longest} * c + c + std::max(px < 0 ? -px : px, py < 0 ? -py : py)) / c +
      2;
  const bool inside =
      cx - reach >= 0 && cy - reach >= 0 && cx + reach < width && cy + reach < height;
  const auto fuse_along_rays = [&](auto checked) {
    for_each_ism_cell(rays, table, px, py, heading, bearing, range_mm, max_range_mm,
                      [cells = grid.cells.data(), width, height, cx, cy, max_index, checked](
                          int dx, int dy, T value) {
                        const int x = cx + dx, y = cy + dy;
                        if (checked && !(static_cast<unsigned>(x) < static_cast<unsigned>(width) &&
                                         static_cast<unsigned>(y) < static_cast<unsigned>(height)))
                          return;
                        fuse_into(
                            cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                  static_cast<std::size_t>(x)],
                            value, max_index);
                      });
  };
  if (inside)
    fuse_along_rays(std::false_type{});
  else
    fuse_along_rays(std::true_type{});
}

}  // namespace intgrid::core
