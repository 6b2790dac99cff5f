#include "intgrid/core/resolution.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/narrow_ism.hpp"

namespace intgrid::core {

double narrow_pmax(double cell, double sigma, double offset) {
  // The ISM depends on cell / sigma only; past these ratios its line of sight would take
  // millions of cells, or every term underflows.
  if (!(cell > 0.0) || !(sigma > 0.0) || !(cell / sigma >= 1e-4) || !(cell / sigma <= 1e4))
    fail<std::invalid_argument>("cell size " + number_text(cell) +
                                " m is not within 1e-4 to 1e4 times sigma (" + number_text(sigma) +
                                " m)");
  // Far enough from the sensor and from the grid's end that neither boundary
  // moves the peak: 40 sigma covers every term double precision can see.
  const double reach = std::ceil(40.0 * sigma / cell);
  const double m = std::max(20.0, reach) + 1.0;
  const auto cells = static_cast<std::size_t>(m + reach + 20.0);
  const std::vector<double> ism = narrow_ism({sigma, 0.0}, (m + offset) * cell, cell, cells);
  return *std::max_element(ism.begin(), ism.end());
}

WorstCasePmax narrow_pmax_worst_case(double cell, double sigma) {
  // A coarse scan of the offsets, then a golden-section refinement of the minimum.
  constexpr int kSamples = 64;
  WorstCasePmax worst{narrow_pmax(cell, sigma, 0.0), 0.0};
  for (int i = 1; i < kSamples; ++i) {
    const double offset = static_cast<double>(i) / kSamples;
    const double p = narrow_pmax(cell, sigma, offset);
    if (p < worst.pmax) worst = {p, offset};
  }
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double lo = worst.offset - 1.0 / kSamples, hi = worst.offset + 1.0 / kSamples;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double a = hi - ratio * (hi - lo), b = lo + ratio * (hi - lo);
    if (narrow_pmax(cell, sigma, a) < narrow_pmax(cell, sigma, b))
      hi = b;
    else
      lo = a;
  }
  const double offset = 0.5 * (lo + hi);
  const double p = narrow_pmax(cell, sigma, offset);
  if (p < worst.pmax) worst = {p, offset - std::floor(offset)};
  return worst;
}

double smallest_cell_for_pmax(double sigma, double pmax, bool worst_case) {
  if (!(sigma >= 1e-6) || !(sigma <= 1e6))
    fail<std::invalid_argument>("sigma must lie in [1e-6, 1e6] metres");
  if (!(pmax > 0.5 && pmax < 1.0)) fail<std::invalid_argument>("Pmax must lie in (1/2, 1)");
  const auto reached = [&](double cell) {
    return (worst_case ? narrow_pmax_worst_case(cell, sigma).pmax : narrow_pmax(cell, sigma)) >=
           pmax;
  };
  // Pmax grows with s/sigma: bisect on the ratio.
  double lo = 1e-3 * sigma, hi = 50.0 * sigma;
  if (reached(lo)) return lo;
  if (!reached(hi))
    fail<std::invalid_argument>(worst_case && pmax > 2.0 / 3.0
                                    ? "no cell size reaches a worst-case Pmax above 2/3: a "
                                      "reading on a cell boundary splits between two cells"
                                    : "Pmax is too close to 1 to be reached");
  while (hi - lo > 1e-9 * hi) {
    const double mid = 0.5 * (lo + hi);
    (reached(mid) ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace intgrid::core
