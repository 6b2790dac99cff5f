// A submap's grid: an occupancy grid in S_eps indices (std::int8_t) or in their unquantized
// double form (LogOdds), indexed by cell in the frame it was started in and grown on demand, so
// that a run needs no map size in advance. Cell (i, j) is centred on (i c, j c) mm, as the
// integer rays (core::IntegerRays) count cells; cells never written read 0: probability 1/2.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "intgrid/core/ray_insertion.hpp"

namespace intgrid::slam {

// The double arithmetic's cell: log-odds in units of the S_eps step lambda, so n lambda is the
// log-odds of index n. Bayesian fusion is addition, saturating where S_eps does; only the
// rounding of each reading's ISM to whole indices is left out.
struct LogOdds {
  double steps = 0.0;
  friend bool operator<(LogOdds a, LogOdds b) { return a.steps < b.steps; }
};

// The value a cell adds to a match score.
inline int score_value(std::int8_t n) {
  return n;
}
inline double score_value(LogOdds v) {
  return v.steps;
}

// Fusion of one reading's value into a cell: saturating index addition in both arithmetics.
inline void fuse_into(std::int8_t& cell, std::int8_t value, int max_index) {
  cell = core::fuse_indices(cell, value, max_index);
}
inline void fuse_into(LogOdds& cell, LogOdds value, int max_index) {
  cell.steps = std::clamp(cell.steps + value.steps, -static_cast<double>(max_index),
                          static_cast<double>(max_index));
}

template <class Cell>
class LocalGrid {
 public:
  explicit LocalGrid(std::int32_t cell_mm) : cell_mm_(cell_mm) {}
  // A grid that holds `cells` (row by row, width x height of them) as [x0, x0 + width) x
  // [y0, y0 + height): a map given whole (MapLocalizer).
  LocalGrid(std::int32_t cell_mm, int x0, int y0, int width, int height, std::vector<Cell> cells)
      : cell_mm_(cell_mm),
        x0_(x0),
        y0_(y0),
        width_(width),
        height_(height),
        cells_(std::move(cells)) {}

  std::int32_t cell_mm() const { return cell_mm_; }
  bool empty() const { return width_ == 0; }
  // The cells held: [x0, x0 + width) x [y0, y0 + height).
  int x0() const { return x0_; }
  int y0() const { return y0_; }
  int width() const { return width_; }
  int height() const { return height_; }
  std::span<const Cell> cells() const { return cells_; }

  Cell at(int cx, int cy) const {
    const int x = cx - x0_, y = cy - y0_;
    if (static_cast<unsigned>(x) >= static_cast<unsigned>(width_) ||
        static_cast<unsigned>(y) >= static_cast<unsigned>(height_))
      return Cell{};
    return cells_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                  static_cast<std::size_t>(x)];
  }

  // Holds at least the cells [cx0, cx1] x [cy0, cy1], growing by whole blocks (kept cells keep
  // their values).
  void cover(int cx0, int cy0, int cx1, int cy1) {
    if (!empty() && cx0 >= x0_ && cy0 >= y0_ && cx1 < x0_ + width_ && cy1 < y0_ + height_) return;
    constexpr int kBlock = 64;
    const auto down = [](int v) { return core::ray_detail::floor_div(v, kBlock) * kBlock; };
    int nx0 = down(cx0), ny0 = down(cy0), nx1 = down(cx1) + kBlock, ny1 = down(cy1) + kBlock;
    if (!empty()) {
      nx0 = std::min(nx0, x0_);
      ny0 = std::min(ny0, y0_);
      nx1 = std::max(nx1, x0_ + width_);
      ny1 = std::max(ny1, y0_ + height_);
    }
    std::vector<Cell> grown(
        static_cast<std::size_t>(nx1 - nx0) * static_cast<std::size_t>(ny1 - ny0), Cell{});
    for (int y = 0; y < height_; ++y)
      std::copy_n(
          cells_.begin() + static_cast<std::ptrdiff_t>(y) * width_, width_,
          grown.begin() + (static_cast<std::ptrdiff_t>(y + y0_ - ny0) * (nx1 - nx0) + (x0_ - nx0)));
    cells_ = std::move(grown);
    x0_ = nx0;
    y0_ = ny0;
    width_ = nx1 - nx0;
    height_ = ny1 - ny0;
  }

  // One scan's ISM fused in along its rays, the sensor at (sx, sy) mm heading `heading` in this
  // grid's frame. The grid first grows to hold every ray.
  void insert(const core::IntegerRays& rays, const core::IsmTable<Cell>& table, std::int64_t sx,
              std::int64_t sy, std::int32_t heading, std::span<const std::int32_t> bearing,
              std::span<const std::int32_t> range_mm, std::int32_t max_range_mm, int max_index) {
    const std::int64_t c = cell_mm_;
    // A reading's ISM reaches past its range (the beam's spread behind the hit): the walk's
    // length is the table's cell count, so that count bounds the cells touched.
    std::size_t longest = 0;
    for (const std::int32_t z : range_mm)
      if (z > 0 && z < max_range_mm) longest = std::max(longest, table.reading(z).size());
    const int cx = static_cast<int>(core::ray_detail::floor_div(sx + c / 2, c));
    const int cy = static_cast<int>(core::ray_detail::floor_div(sy + c / 2, c));
    // The walk stops once a cell centre's projection passes (longest + 1/2) c from the sensor,
    // which lies within half a cell of cell (cx, cy)'s centre: a cell's centre is then within
    // (longest + 1/2) c + c / sqrt(2) + c / sqrt(2) of it.
    const int reach = static_cast<int>(longest) + 3;
    cover(cx - reach, cy - reach, cx + reach, cy + reach);
    // Every cell lies inside once covered: no bounds check per cell.
    Cell* origin = cells_.data() + (static_cast<std::ptrdiff_t>(cy - y0_) * width_ + (cx - x0_));
    const std::ptrdiff_t width = width_;
    core::for_each_ism_cell(rays, table, sx - cx * c, sy - cy * c, heading, bearing, range_mm,
                            max_range_mm, [origin, width, max_index](int dx, int dy, Cell value) {
                              fuse_into(origin[dy * width + dx], value, max_index);
                            });
  }

 private:
  std::int32_t cell_mm_;
  int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;
  std::vector<Cell> cells_;
};

}  // namespace intgrid::slam
