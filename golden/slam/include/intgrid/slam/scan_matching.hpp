// Scan-to-submap matching on a pose lattice, in index sums: a pose's score is the sum of the
// submap's cells (S_eps indices, or their unquantized LogOdds) under the scan's hits, which is
// the scan's log-likelihood ratio up to the S_eps step, less a quadratic prior around the guess.
// Three searches over the same lattice (one cell in x and y, one heading step):
//   match_exhaustive       every pose of the window (the oracle of the other two);
//   match_branch_and_bound the same maximum, bounded from above by max-pooled grids: the most a
//                          block of 2^d x 2^d translations can score is at most the sum, over
//                          the hits, of the largest cell each hit can meet in the block (exact
//                          for S_eps cells, rounded up to a whole index for LogOdds);
//   refine_match           quarter-cell and half-step poses around a lattice match, scored by
//                          bilinear interpolation of the cells (Q8 weights).
// Integer arithmetic throughout for std::int8_t cells; the double arithmetic (LogOdds) is the same
// code with double scores.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "intgrid/core/parallel.hpp"
#include "intgrid/core/ray_insertion.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"
#include "intgrid/slam/local_grid.hpp"

namespace intgrid::slam {

// Scores: whole index sums for S_eps cells, double for LogOdds.
template <class Cell>
using MatchScore = std::conditional_t<std::is_same_v<Cell, LogOdds>, double, std::int64_t>;

// A scan's hits in the robot frame (mm): every reading 0 < z < max_range_mm.
struct ScanPoints {
  std::vector<std::int32_t> x_mm, y_mm;
  std::size_t size() const { return x_mm.size(); }
};

ScanPoints scan_points(const core::IntegerRays& rays, const SlamSensor& sensor,
                       std::span<const std::int32_t> range_mm, std::int32_t max_range_mm);

// The poses searched: the guess plus (i c, j c) for |i|, |j| <= cells and the guess's heading plus
// k step_units for |k| <= steps. The prior costs w ((d / prior_xy_mm)^2 + (a / prior_theta)^2)
// (0: no prior), w being prior_weight_permille thousandths of full, the score of every hit on a
// cell of the largest index.
struct SearchWindow {
  int cells = 0;
  int steps = 0;
  std::int32_t step_units = 64;
  std::int64_t prior_xy_mm = 0;
  std::int64_t prior_theta_units = 0;
  std::int64_t prior_weight_permille = 1000;
};

template <class Cell>
struct Match {
  SlamPose pose;                // in the grid's frame
  MatchScore<Cell> score{};     // the hits' sum less the prior's cost
  MatchScore<Cell> evidence{};  // the hits' sum alone
  bool found = false;           // score reached the minimum asked for
};

namespace matching_detail {

using core::ray_detail::floor_div;

template <class Cell>
MatchScore<Cell> prior_cost(const SearchWindow& w, MatchScore<Cell> full, std::int64_t dx_mm,
                            std::int64_t dy_mm, std::int64_t da) {
  MatchScore<Cell> cost{};
  full = full * MatchScore<Cell>(w.prior_weight_permille) / MatchScore<Cell>(1000);
  if (w.prior_xy_mm > 0)
    cost += full * MatchScore<Cell>(dx_mm * dx_mm + dy_mm * dy_mm) /
            MatchScore<Cell>(w.prior_xy_mm * w.prior_xy_mm);
  if (w.prior_theta_units > 0)
    cost += full * MatchScore<Cell>(da * da) /
            MatchScore<Cell>(w.prior_theta_units * w.prior_theta_units);
  return cost;
}

// The cells of the hits for the pose (x, y, theta).
inline void hit_cells(const core::IntegerRays& rays, const ScanPoints& points, std::int64_t x,
                      std::int64_t y, std::int32_t theta, std::vector<int>& cx,
                      std::vector<int>& cy) {
  const std::int64_t c = rays.cell_mm();
  cx.resize(points.size());
  cy.resize(points.size());
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto [rx, ry] = rays.rotate(theta, points.x_mm[p], points.y_mm[p]);
    cx[p] = static_cast<int>(floor_div(x + rx + c / 2, c));
    cy[p] = static_cast<int>(floor_div(y + ry + c / 2, c));
  }
}

// The hits turned to the heading theta (mm, robot frame axes).
inline void turned_hits(const core::IntegerRays& rays, const ScanPoints& points, std::int64_t theta,
                        std::vector<int>& qx, std::vector<int>& qy) {
  qx.resize(points.size());
  qy.resize(points.size());
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto [rx, ry] =
        rays.rotate(static_cast<std::int32_t>(theta), points.x_mm[p], points.y_mm[p]);
    qx[p] = static_cast<int>(rx);
    qy[p] = static_cast<int>(ry);
  }
}

// The hits at (hx, hy), in 1/256 cell from the centre of cell (0, 0), scored by bilinear
// interpolation of the cells, in 1/65536 of an index: cell centres are lattice points, so the
// four around a hit weigh by its fractions.
template <class Cell>
MatchScore<Cell> interpolated_evidence(const LocalGrid<Cell>& grid,
                                       std::span<const std::int64_t> hx,
                                       std::span<const std::int64_t> hy) {
  using S = MatchScore<Cell>;
  S sum{};
  for (std::size_t p = 0; p < hx.size(); ++p) {
    const int ix = static_cast<int>(hx[p] >> 8), iy = static_cast<int>(hy[p] >> 8);
    const std::int64_t fx = hx[p] & 255, fy = hy[p] & 255;
    sum += S((256 - fx) * (256 - fy)) * score_value(grid.at(ix, iy)) +
           S(fx * (256 - fy)) * score_value(grid.at(ix + 1, iy)) +
           S((256 - fx) * fy) * score_value(grid.at(ix, iy + 1)) +
           S(fx * fy) * score_value(grid.at(ix + 1, iy + 1));
  }
  return sum;
}

// The hits q (one axis, turned to the pose's heading, mm) shifted by t (mm), in 1/256 cell.
inline void hit_positions_q8(const std::vector<int>& q, std::int64_t t, std::int64_t c,
                             std::span<std::int64_t> out) {
  for (std::size_t p = 0; p < q.size(); ++p) out[p] = floor_div((t + q[p]) * 256, c);
}

// The hits (qx, qy), turned to the pose's heading (mm), scored at the translation (x, y).
template <class Cell>
MatchScore<Cell> interpolated_evidence(const LocalGrid<Cell>& grid, const std::vector<int>& qx,
                                       const std::vector<int>& qy, std::int64_t x, std::int64_t y,
                                       std::int64_t c) {
  std::vector<std::int64_t> hx(qx.size()), hy(qy.size());
  hit_positions_q8(qx, x, c, hx);
  hit_positions_q8(qy, y, c, hy);
  return interpolated_evidence(grid, std::span<const std::int64_t>(hx),
                               std::span<const std::int64_t>(hy));
}

}  // namespace matching_detail

// The largest score of the window, and its pose (the first in k, j, i order among equals).
// found says whether it reached min_score. The headings are cut into up to `threads` runs of
// consecutive k searched on threads; each run's best is taken in k order with the same strict
// comparison, so the result is the same for any count.
template <class Cell>
Match<Cell> match_exhaustive(const LocalGrid<Cell>& grid, const core::IntegerRays& rays,
                             const ScanPoints& points, const SlamPose& guess,
                             const SearchWindow& window, int max_index, MatchScore<Cell> min_score,
                             int threads = 1) {
  using S = MatchScore<Cell>;
  const int n = 2 * window.cells + 1;
  const S full = S(static_cast<std::int64_t>(points.size()) * max_index);
  // Per-pose sums of whole indices fit 32 bits (100000 beams of 127 at most). S_eps cells are
  // first summed in 16 bits, kHitsPer16Bits hits at a time, over rows padded to whole blocks of
  // 16 cells: fixed-width adds of 16 lanes that the compiler vectorizes, where 13 cells of 32
  // bits a row did not (then ACES's integer localization took 1.37 times the double one's time).
  constexpr bool kIndices = std::is_same_v<Cell, std::int8_t>;
  constexpr int kBlock = 16;
  constexpr int kHitsPer16Bits = 256;  // 256 x 128 = 2^15: no partial sum leaves int16
  using Sum = std::conditional_t<std::is_same_v<S, double>, double, std::int32_t>;
  const int stride = kIndices ? (n + kBlock - 1) / kBlock * kBlock : n;
  const auto cells_of = [&](int rows) {
    return static_cast<std::size_t>(rows) * static_cast<std::size_t>(stride);
  };
  const std::int64_t c = rays.cell_mm();
  struct Best {
    Match<Cell> match;
    bool any = false;
  };
  // The best of headings k_first..k_last, in k, j, i order.
  const auto search = [&](int k_first, int k_last) {
    std::vector<int> cx, cy;
    std::vector<Sum> sums(cells_of(n));
    std::vector<std::int16_t> partial(kIndices ? cells_of(n) : 0);
    int partial_hits = 0;
    const auto flush_partial = [&] {
      for (std::size_t q = 0; q < partial.size(); ++q) sums[q] += partial[q];
      std::fill(partial.begin(), partial.end(), std::int16_t{0});
      partial_hits = 0;
    };
    Best best;
    for (int k = k_first; k <= k_last; ++k) {
      const std::int64_t da = std::int64_t{k} * window.step_units;
      const auto theta = static_cast<std::int32_t>(guess.theta + da);
      matching_detail::hit_cells(rays, points, guess.x_mm, guess.y_mm, theta, cx, cy);
      std::fill(sums.begin(), sums.end(), Sum{});
      for (std::size_t p = 0; p < points.size(); ++p) {
        const int x0 = cx[p] - window.cells, y0 = cy[p] - window.cells;
        if (x0 >= grid.x0() && y0 >= grid.y0() && x0 + stride <= grid.x0() + grid.width() &&
            y0 + n <= grid.y0() + grid.height()) {
          // The whole (padded) window inside the grid: rows read straight.
          const Cell* cells =
              grid.cells().data() +
              (static_cast<std::ptrdiff_t>(y0 - grid.y0()) * grid.width() + (x0 - grid.x0()));
          for (int j = 0; j < n; ++j) {
            const Cell* source = cells + static_cast<std::ptrdiff_t>(j) * grid.width();
            if constexpr (kIndices) {
              std::int16_t* row = &partial[cells_of(j)];
              for (int b = 0; b < stride; b += kBlock)
                for (int i = 0; i < kBlock; ++i) row[b + i] += source[b + i];
            } else {
              Sum* row = &sums[cells_of(j)];
              for (int i = 0; i < n; ++i) row[i] += score_value(source[i]);
            }
          }
          if (kIndices && ++partial_hits == kHitsPer16Bits) flush_partial();
          continue;
        }
        for (int j = 0; j < n; ++j) {
          Sum* row = &sums[cells_of(j)];
          for (int i = 0; i < n; ++i) row[i] += score_value(grid.at(x0 + i, y0 + j));
        }
      }
      if (kIndices) flush_partial();
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const S evidence = S(sums[cells_of(j) + static_cast<std::size_t>(i)]);
          const S score =
              evidence - matching_detail::prior_cost<Cell>(window, full, (i - window.cells) * c,
                                                           (j - window.cells) * c, da);
          if (!best.any || score > best.match.score) {
            best.any = true;
            best.match.score = score;
            best.match.evidence = evidence;
            best.match.pose = {guess.x_mm + (i - window.cells) * c,
                               guess.y_mm + (j - window.cells) * c, guess.theta + da};
          }
        }
    }
    return best;
  };
  const int headings = 2 * window.steps + 1;
  const int runs = std::clamp(threads, 1, headings);
  std::vector<Best> bests(static_cast<std::size_t>(runs));
  core::run_parts(static_cast<std::size_t>(runs), runs, [&](std::size_t r) {
    const int part = static_cast<int>(r);
    bests[r] = search(-window.steps + headings * part / runs,
                      -window.steps + headings * (part + 1) / runs - 1);
  });
  Best best;
  for (const Best& b : bests)
    if (b.any && (!best.any || b.match.score > best.match.score)) best = b;
  best.match.found = best.any && best.match.score >= min_score;
  return best.match;
}

// Max-pooled copies of a grid: level 0 is the grid itself; level d >= 1 holds, for each cell
// (x, y), the largest cell of [x, x + 2^d) x [y, y + 2^d) (cells outside the grid count 0) as a
// whole index: the cell itself for S_eps cells, its ceiling for LogOdds. A ceiling still bounds
// every score from above, so branch and bound finds the same maximum, and the levels take one
// byte a cell in both arithmetics: the double pyramid held 8 (a submap's 9 levels at 5 m / 5 cm,
// 80 MB, so that the loop search's cache held two submaps and rebuilt one for most searches).
// Cells hold at most the codec's largest index, which S_eps keeps within std::int8_t.
template <class Cell>
class MaxPyramid {
 public:
  MaxPyramid(const LocalGrid<Cell>& grid, int levels) : grid_(grid) {
    bounds_.resize(static_cast<std::size_t>(levels));
    if (levels == 0) return;
    Level whole{grid.width(), grid.height(), std::vector<std::int8_t>(grid.cells().size())};
    std::transform(grid.cells().begin(), grid.cells().end(), whole.cells.begin(),
                   whole_index_above);
    bounds_[0] = coarser(whole, 1);
    for (int d = 1; d < levels; ++d)
      bounds_[static_cast<std::size_t>(d)] =
          coarser(bounds_[static_cast<std::size_t>(d) - 1], 1 << d);
  }

  int levels() const { return static_cast<int>(bounds_.size()); }
  // The grid's cell (cx, cy): level 0.
  Cell cell(int cx, int cy) const { return grid_.at(cx, cy); }
  // The largest grid cell of [cx, cx + 2^d) x [cy, cy + 2^d) as a whole index (rounded up), d >= 1.
  std::int8_t bound(int d, int cx, int cy) const {
    const int shift = (1 << d) - 1;
    return bounds_[static_cast<std::size_t>(d) - 1].get(cx - grid_.x0() + shift,
                                                        cy - grid_.y0() + shift);
  }
  std::size_t bytes() const {
    std::size_t total = grid_.cells().size() * sizeof(Cell);
    for (const Level& l : bounds_) total += l.cells.size();
    return total;
  }

 private:
  struct Level {
    int width = 0, height = 0;
    std::vector<std::int8_t> cells;
    std::int8_t get(int x, int y) const {
      if (static_cast<unsigned>(x) >= static_cast<unsigned>(width) ||
          static_cast<unsigned>(y) >= static_cast<unsigned>(height))
        return 0;
      return cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(x)];
    }
  };
  static std::int8_t whole_index_above(Cell v) {
    if constexpr (std::is_same_v<Cell, LogOdds>)
      return static_cast<std::int8_t>(std::ceil(v.steps));
    else
      return v;
  }
  // Level d + 1 from level d (h = 2^d): its cell (x, y) is the largest of the fine cells
  // (x - h, y - h), (x, y - h), (x - h, y) and (x, y), outside cells counting 0; taken as the
  // larger of two row maxima.
  static Level coarser(const Level& fine, int h) {
    Level coarse;
    coarse.width = fine.width + h;
    coarse.height = fine.height + h;
    coarse.cells.resize(static_cast<std::size_t>(coarse.width) *
                        static_cast<std::size_t>(coarse.height));
    // The larger of fine cells (x - h, r) and (x, r), for a row r that may lie outside.
    const auto row_max = [&](const std::int8_t* row, int x) {
      if (row == nullptr) return std::int8_t{0};
      const std::int8_t left = x >= h ? row[x - h] : std::int8_t{0};
      const std::int8_t here = x < fine.width ? row[x] : std::int8_t{0};
      return std::max(left, here);
    };
    for (int y = 0; y < coarse.height; ++y) {
      const auto row = [&](int r) {
        return r >= 0 && r < fine.height
                   ? &fine.cells[static_cast<std::size_t>(r) * static_cast<std::size_t>(fine.width)]
                   : nullptr;
      };
      const std::int8_t* above = row(y - h);
      const std::int8_t* here = row(y);
      std::int8_t* out =
          &coarse.cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(coarse.width)];
      for (int x = 0; x < coarse.width; ++x) out[x] = std::max(row_max(above, x), row_max(here, x));
    }
    return coarse;
  }

  LocalGrid<Cell> grid_;       // level 0: a copy of the grid
  std::vector<Level> bounds_;  // levels 1 .. levels
};

// The levels a window of `cells` needs: 2^levels >= 2 cells + 1.
inline int pyramid_levels(int cells) {
  int d = 0;
  while ((1 << d) < 2 * cells + 1) ++d;
  return d;
}

// match_exhaustive's maximum over the same window, with poses whose score can not reach
// min_score (or the best found so far) left unvisited. The pyramid needs
// pyramid_levels(window.cells) levels.
template <class Cell>
Match<Cell> match_branch_and_bound(const MaxPyramid<Cell>& pyramid, const core::IntegerRays& rays,
                                   const ScanPoints& points, const SlamPose& guess,
                                   const SearchWindow& window, int max_index,
                                   MatchScore<Cell> min_score) {
  using S = MatchScore<Cell>;
  const int depth = pyramid_levels(window.cells);
  const S full = S(static_cast<std::int64_t>(points.size()) * max_index);
  const std::int64_t c = rays.cell_mm();
  const int headings = 2 * window.steps + 1;
  std::vector<std::vector<int>> cx(static_cast<std::size_t>(headings)),
      cy(static_cast<std::size_t>(headings));
  for (int k = 0; k < headings; ++k)
    matching_detail::hit_cells(
        rays, points, guess.x_mm, guess.y_mm,
        static_cast<std::int32_t>(guess.theta + std::int64_t{k - window.steps} * window.step_units),
        cx[static_cast<std::size_t>(k)], cy[static_cast<std::size_t>(k)]);

  struct Block {
    int k, i, j, d;  // translations [i, i + 2^d) x [j, j + 2^d) from -cells, heading k - steps
    S bound;
  };
  // The nearest offset to 0 of [i, i + 2^d) within the window, in cells.
  const auto nearest = [&](int i, int d) {
    const int lo = i - window.cells,
              hi = std::min(i + (1 << d) - 1, 2 * window.cells) - window.cells;
    return lo > 0 ? lo : hi < 0 ? hi : 0;
  };
  const auto bound = [&](int k, int i, int j, int d) {
    const auto& hx = cx[static_cast<std::size_t>(k)];
    const auto& hy = cy[static_cast<std::size_t>(k)];
    S sum{};
    const int ox = i - window.cells, oy = j - window.cells;
    if (d == 0)
      for (std::size_t p = 0; p < hx.size(); ++p)
        sum += score_value(pyramid.cell(hx[p] + ox, hy[p] + oy));
    else
      for (std::size_t p = 0; p < hx.size(); ++p) sum += pyramid.bound(d, hx[p] + ox, hy[p] + oy);
    return sum - matching_detail::prior_cost<Cell>(
                     window, full, std::int64_t{nearest(i, d)} * c, std::int64_t{nearest(j, d)} * c,
                     std::int64_t{k - window.steps} * window.step_units);
  };
  const auto by_bound = [](const Block& a, const Block& b) {
    return a.bound > b.bound || (a.bound == b.bound && (a.k < b.k || (a.k == b.k && a.j < b.j) ||
                                                        (a.k == b.k && a.j == b.j && a.i < b.i)));
  };

  std::vector<Block> stack;
  for (int k = 0; k < headings; ++k) stack.push_back({k, 0, 0, depth, bound(k, 0, 0, depth)});
  std::sort(stack.begin(), stack.end(), by_bound);
  std::reverse(stack.begin(), stack.end());  // the best on top
  Match<Cell> best;
  best.score = min_score;
  std::vector<Block> children;
  while (!stack.empty()) {
    const Block b = stack.back();
    stack.pop_back();
    if (b.bound < best.score || (best.found && b.bound == best.score)) continue;
    if (b.d == 0) {
      best.found = true;
      best.score = b.bound;
      best.evidence = b.bound + matching_detail::prior_cost<Cell>(
                                    window, full, std::int64_t{b.i - window.cells} * c,
                                    std::int64_t{b.j - window.cells} * c,
                                    std::int64_t{b.k - window.steps} * window.step_units);
      best.pose = {guess.x_mm + (b.i - window.cells) * c, guess.y_mm + (b.j - window.cells) * c,
                   guess.theta + std::int64_t{b.k - window.steps} * window.step_units};
      continue;
    }
    const int h = 1 << (b.d - 1);
    children.clear();
    for (const auto& [di, dj] : {std::pair{0, 0}, {h, 0}, {0, h}, {h, h}}) {
      const int i = b.i + di, j = b.j + dj;
      if (i > 2 * window.cells || j > 2 * window.cells) continue;
      children.push_back({b.k, i, j, b.d - 1, bound(b.k, i, j, b.d - 1)});
    }
    std::sort(children.begin(), children.end(), by_bound);
    stack.insert(stack.end(), children.rbegin(), children.rend());
  }
  if (!best.found) best.score = min_score;
  return best;
}

// The best of the poses a quarter cell and half a heading step apart around `lattice` (within
// one cell and one step), scored by bilinear interpolation (in 1/65536 of an index) less the
// prior around `guess`. (A second pass at half those steps made the ACES run worse, 0.33 m
// against 0.20 m: it fits the interpolation's ripple, not the walls.) Its five headings are
// searched on up to `threads` threads and their bests taken in order: the same for any count.
template <class Cell>
Match<Cell> refine_match(const LocalGrid<Cell>& grid, const core::IntegerRays& rays,
                         const ScanPoints& points, const SlamPose& guess,
                         const SearchWindow& window, int max_index, const Match<Cell>& lattice,
                         int threads = 1) {
  using S = MatchScore<Cell>;
  const S full = S(static_cast<std::int64_t>(points.size()) * max_index) * S(65536);
  const std::int64_t c = rays.cell_mm();
  const auto offset = [c](int k) { return k * c / 4; };  // of pose k = -4..4 from the lattice's
  constexpr int kHeadings = 5;                           // m = -2..2 half steps
  struct Best {
    S score{};
    SlamPose pose;
  };
  std::vector<Best> bests(kHeadings);
  const std::size_t n = points.size();
  core::run_parts(kHeadings, threads, [&](std::size_t h) {
    const int m = static_cast<int>(h) - 2;
    std::vector<int> qx, qy;
    // The hits' positions at each of the nine offsets along x and along y, computed once a
    // heading (a division each) rather than once a pose.
    constexpr int kOffsets = 9;
    std::vector<std::int64_t> hx(kOffsets * n), hy(kOffsets * n);
    const auto at_offset = [n](std::vector<std::int64_t>& v, int k) {
      return std::span<std::int64_t>(v).subspan(static_cast<std::size_t>(k + 4) * n, n);
    };
    const std::int64_t theta = lattice.pose.theta + m * window.step_units / 2;
    matching_detail::turned_hits(rays, points, theta, qx, qy);
    for (int k = -4; k <= 4; ++k) {
      matching_detail::hit_positions_q8(qx, lattice.pose.x_mm + offset(k), c, at_offset(hx, k));
      matching_detail::hit_positions_q8(qy, lattice.pose.y_mm + offset(k), c, at_offset(hy, k));
    }
    Best& best = bests[h];
    bool any = false;
    for (int v = -4; v <= 4; ++v)
      for (int u = -4; u <= 4; ++u) {
        const std::int64_t x = lattice.pose.x_mm + offset(u), y = lattice.pose.y_mm + offset(v);
        S sum = matching_detail::interpolated_evidence(
            grid, std::span<const std::int64_t>(at_offset(hx, u)),
            std::span<const std::int64_t>(at_offset(hy, v)));
        sum -= matching_detail::prior_cost<Cell>(window, full, x - guess.x_mm, y - guess.y_mm,
                                                 theta - guess.theta);
        if (!any || sum > best.score) {
          any = true;
          best = {sum, {x, y, theta}};
        }
      }
  });
  std::size_t kept = 0;
  for (std::size_t h = 1; h < bests.size(); ++h)
    if (bests[h].score > bests[kept].score) kept = h;
  Match<Cell> best = lattice;
  best.pose = bests[kept].pose;
  best.score = lattice.score;  // callers compare lattice scores with their thresholds
  return best;
}

// How sharply a match's evidence peaks at its pose, direction by direction: the second
// differences of the interpolated evidence one cell apart, along x and y (xx, yy) and across
// the diagonals (xy), negated, so that a peak has xx, yy > 0; in 1/65536 of an index. A scan
// of two parallel walls along x scores the same shifted along them: xx = xy = 0.
template <class Cell>
struct EvidenceCurvature {
  MatchScore<Cell> xx{}, xy{}, yy{};
};

template <class Cell>
EvidenceCurvature<Cell> evidence_curvature(const LocalGrid<Cell>& grid,
                                           const core::IntegerRays& rays, const ScanPoints& points,
                                           const SlamPose& pose) {
  using S = MatchScore<Cell>;
  std::vector<int> qx, qy;
  matching_detail::turned_hits(rays, points, pose.theta, qx, qy);
  const std::int64_t c = rays.cell_mm();
  const auto at = [&](int i, int j) {
    return matching_detail::interpolated_evidence(grid, qx, qy, pose.x_mm + i * c,
                                                  pose.y_mm + j * c, c);
  };
  const S here = at(0, 0);
  EvidenceCurvature<Cell> k;
  k.xx = S(2) * here - at(1, 0) - at(-1, 0);
  k.yy = S(2) * here - at(0, 1) - at(0, -1);
  k.xy = (at(1, -1) + at(-1, 1) - at(1, 1) - at(-1, -1)) / S(4);
  return k;
}

}  // namespace intgrid::slam
