#include "intgrid/core/map_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "intgrid/core/failure.hpp"

namespace intgrid::core {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The 1D squared distance transform of f over n samples with stride (Felzenszwalb and
// Huttenlocher, "Distance transforms of sampled functions", 2012): d(q) = min_p (q - p)^2 + f(p).
void distance_transform_1d(double* f, std::size_t n, std::size_t stride, std::vector<double>& d,
                           std::vector<std::size_t>& v, std::vector<double>& z) {
  d.resize(n);
  v.resize(n);
  z.resize(n + 1);
  std::size_t k = 0;
  bool any = false;
  for (std::size_t q = 0; q < n; ++q) {
    const double fq = f[q * stride];
    if (fq == kInfinity) continue;
    if (!any) {
      any = true;
      v[0] = q;
      z[0] = -kInfinity;
      z[1] = kInfinity;
      continue;
    }
    const auto dq = static_cast<double>(q);
    double s = 0.0;
    while (true) {
      const auto dv = static_cast<double>(v[k]);
      s = ((fq + dq * dq) - (f[v[k] * stride] + dv * dv)) / (2.0 * dq - 2.0 * dv);
      if (s <= z[k] && k > 0) {
        --k;
        continue;
      }
      break;
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInfinity;
  }
  if (!any) return;  // every sample infinite: so is the transform
  k = 0;
  for (std::size_t q = 0; q < n; ++q) {
    const auto dq = static_cast<double>(q);
    while (z[k + 1] < dq) ++k;
    const auto dv = static_cast<double>(v[k]);
    d[q] = (dq - dv) * (dq - dv) + f[v[k] * stride];
  }
  for (std::size_t q = 0; q < n; ++q) f[q * stride] = d[q];
}

}  // namespace

std::vector<double> squared_distance_transform(const std::vector<char>& occupied, int width,
                                               int height) {
  std::vector<double> f(occupied.size());
  for (std::size_t i = 0; i < occupied.size(); ++i) f[i] = occupied[i] ? 0.0 : kInfinity;
  std::vector<double> d;
  std::vector<std::size_t> v;
  std::vector<double> z;
  const auto w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  for (std::size_t x = 0; x < w; ++x) distance_transform_1d(&f[x], h, w, d, v, z);
  for (std::size_t y = 0; y < h; ++y) distance_transform_1d(&f[y * w], w, 1, d, v, z);
  return f;
}

ObstacleDistance distance_to_nearest_obstacle(const ProbabilityGrid& built, double built_threshold,
                                              const ProbabilityGrid& truth, double truth_threshold,
                                              ObstacleExtent extent) {
  check_geometry(built.geometry);
  check_geometry(truth.geometry);
  if (built.cells.size() != built.geometry.size() || truth.cells.size() != truth.geometry.size())
    fail<std::invalid_argument>("distance_to_nearest_obstacle: cells do not match the geometry");
  const GridGeometry& t = truth.geometry;
  std::vector<char> occupied(truth.cells.size());
  bool any = false;
  for (std::size_t i = 0; i < truth.cells.size(); ++i) {
    occupied[i] = truth.cells[i] > truth_threshold;  // NaN: false
    any = any || occupied[i];
  }
  if (!any)
    fail<std::invalid_argument>("distance_to_nearest_obstacle: the true map has no occupied cell");
  const std::vector<double> squared = squared_distance_transform(occupied, t.width, t.height);

  ObstacleDistance out;
  double sum = 0.0;
  const GridGeometry& b = built.geometry;
  for (int by = 0; by < b.height; ++by) {
    for (int bx = 0; bx < b.width; ++bx) {
      if (!(built.at(bx, by) > built_threshold)) continue;
      const double x = b.centre_x(bx), y = b.centre_y(by);
      // The truth cell nearest the point bounds the answer: the point is within `offset` of
      // its centre, which is within sqrt(squared) cells of an occupied centre.
      const int cx = std::clamp(t.cell_x(x), 0, t.width - 1);
      const int cy = std::clamp(t.cell_y(y), 0, t.height - 1);
      const double offset = std::hypot(x - t.centre_x(cx), y - t.centre_y(cy));
      const double bound = offset + std::sqrt(squared[t.index(cx, cy)]) * t.resolution;
      // Every occupied cell whose square reaches within bound of the point (that holds every
      // centre within bound), widened by a cell for rounding.
      const auto index_range = [&](double lo, double hi, double origin, int n) {
        const double a = std::floor((lo - origin) / t.resolution) - 1.0;
        const double c = std::floor((hi - origin) / t.resolution) + 1.0;
        return std::pair<int, int>{static_cast<int>(std::max(a, 0.0)),
                                   static_cast<int>(std::min(c, static_cast<double>(n - 1)))};
      };
      const auto [x0, x1] = index_range(x - bound, x + bound, t.origin_x, t.width);
      const auto [y0, y1] = index_range(y - bound, y + bound, t.origin_y, t.height);
      // The distance along one axis from the point to a cell: to its centre, or to its
      // interval (0 inside).
      const double half = extent == ObstacleExtent::cell ? 0.5 * t.resolution : 0.0;
      const auto axis = [half](double centre, double v) {
        return std::max(std::abs(centre - v) - half, 0.0);
      };
      double best = kInfinity;
      for (int iy = y0; iy <= y1; ++iy) {
        const double dy = axis(t.centre_y(iy), y);
        for (int ix = x0; ix <= x1; ++ix) {
          if (!occupied[t.index(ix, iy)]) continue;
          best = std::min(best, std::hypot(axis(t.centre_x(ix), x), dy));
        }
      }
      sum += best;
      out.max = std::max(out.max, best);
      ++out.cells;
    }
  }
  if (out.cells == 0) {
    out.mean = out.max = std::numeric_limits<double>::quiet_NaN();
  } else {
    out.mean = sum / static_cast<double>(out.cells);
  }
  return out;
}

double mean_distance_to_nearest_obstacle(const ProbabilityGrid& built, double built_threshold,
                                         const ProbabilityGrid& truth, double truth_threshold,
                                         ObstacleExtent extent) {
  return distance_to_nearest_obstacle(built, built_threshold, truth, truth_threshold, extent).mean;
}

}  // namespace intgrid::core
