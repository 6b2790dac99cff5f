#include "intgrid/core/map_compare.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace intgrid::core {
namespace {

// The share of `from`'s occupied cells whose centre lies within `tolerance` of
// the centre of an occupied cell of `to`, by a search of the neighbourhood.
double share_near(const ProbabilityGrid& from, double from_threshold, const ProbabilityGrid& to,
                  double to_threshold, double tolerance, std::size_t& occupied) {
  const GridGeometry& g = to.geometry;
  // The search window in cells, in double precision (any tolerance and any other map's
  // extent may come in), cut to the grid: a tolerance past the grid costs no more than the grid.
  const double reach = std::ceil(tolerance / g.resolution) + 1.0;
  const double tolerance_sq = tolerance * tolerance;
  std::size_t near = 0;
  occupied = 0;
  for (int iy = 0; iy < from.geometry.height; ++iy)
    for (int ix = 0; ix < from.geometry.width; ++ix) {
      if (!(from.at(ix, iy) > from_threshold)) continue;
      ++occupied;
      const double x = from.geometry.centre_x(ix), y = from.geometry.centre_y(iy);
      const double cx = std::floor((x - g.origin_x) / g.resolution);
      const double cy = std::floor((y - g.origin_y) / g.resolution);
      const double x0 = std::max(cx - reach, 0.0), x1 = std::min(cx + reach, g.width - 1.0);
      const double y0 = std::max(cy - reach, 0.0), y1 = std::min(cy + reach, g.height - 1.0);
      if (!(x0 <= x1 && y0 <= y1)) continue;  // the window misses the grid (or is NaN)
      bool found = false;
      for (auto jy = static_cast<int>(y0); jy <= static_cast<int>(y1) && !found; ++jy)
        for (auto jx = static_cast<int>(x0); jx <= static_cast<int>(x1) && !found; ++jx) {
          if (!(to.at(jx, jy) > to_threshold)) continue;
          const double dx = g.centre_x(jx) - x, dy = g.centre_y(jy) - y;
          found = dx * dx + dy * dy <= tolerance_sq;
        }
      near += found;
    }
  return occupied ? static_cast<double>(near) / static_cast<double>(occupied) : 0.0;
}

}  // namespace

MapAgreement compare_occupied(const ProbabilityGrid& ours, double our_threshold,
                              const ProbabilityGrid& reference, double reference_threshold,
                              double tolerance) {
  MapAgreement a;
  a.ours_near_reference =
      share_near(ours, our_threshold, reference, reference_threshold, tolerance, a.ours_occupied);
  a.reference_near_ours = share_near(reference, reference_threshold, ours, our_threshold, tolerance,
                                     a.reference_occupied);
  return a;
}

}  // namespace intgrid::core
