#include "intgrid/core/sectoral_ism.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "intgrid/core/failure.hpp"

namespace intgrid::core {
namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

// |2j + 1 - Ns| orders the sectors by distance to the axis exactly: mirror sectors tie.
int off_axis_rank(int sector, int sectors) {
  return std::abs(2 * sector + 1 - sectors);
}

// The natural-log arithmetic of the double-precision ISM. Priors count from the ring
// nearest z, so the terms that matter keep small exponents for any number of rings.
struct NaturalLogArith {
  const ConeSensorModel& model;
  const SectoralGrid& grid;
  const PatternClasses& classes;
  double z;
  int reference_ring;

  double zero() const { return kMinusInfinity; }
  double add(double a, double b) const {
    if (a < b) std::swap(a, b);
    if (b == kMinusInfinity) return a;
    return a + std::log1p(std::exp(b - a));
  }
  double mul(double a, double b) const { return a + b; }
  double log_density(int ring, std::size_t c) const {
    // fma gives z - r * cell with one rounding, as in the narrow ISM.
    return model.log_density_of_error(std::fma(-double(ring), grid.cell, z),
                                      grid.ring_distance(ring), classes.theta[c], classes.size[c]);
  }
  double log_weight(int v, std::size_t c) const { return classes.log_weight_of(v, c); }
  double ring_prior(int ring) const {
    return -double(ring - reference_ring) * grid.bins * std::numbers::ln2;
  }
  double two() const { return std::numbers::ln2; }
  double output(double log_num, double log_den) const {
    if (log_num == kMinusInfinity && log_den == kMinusInfinity) return 0.5;
    return 1.0 / (1.0 + std::exp(log_den - log_num));
  }
};

}  // namespace

double SectoralGrid::sector_theta(int sector) const {
  return static_cast<double>(off_axis_rank(sector, sectors)) / sectors;
}

void check_sectoral_grid(const SectoralGrid& g) {
  const auto invalid = [](const std::string& message) { fail<std::invalid_argument>(message); };
  if (!(g.fov > 0.0 && g.fov < std::numbers::pi))
    invalid("FOV must lie strictly between 0 and 180 degrees");
  if (!(g.cell > 0.0) || !std::isfinite(g.cell))
    invalid("cell size must be a positive finite number");
  if (g.rings < 1) invalid("rings (R) must be at least 1, got " + std::to_string(g.rings));
  if (g.bins < 1) invalid("bins (A) must be at least 1, got " + std::to_string(g.bins));
  if (g.sectors < 1) invalid("sectors (Ns) must be at least 1, got " + std::to_string(g.sectors));
  if (g.bins > kMaxBins)
    invalid("bins (A = " + std::to_string(g.bins) + ") exceed " + std::to_string(kMaxBins) +
            ": the prior 2^-A of an empty ring would leave double precision");
  if (g.sectors > g.bins)
    invalid("sectors (Ns = " + std::to_string(g.sectors) +
            ") exceed bins (A = " + std::to_string(g.bins) + ")");
  if (g.bins % g.sectors != 0)
    invalid("bins (A = " + std::to_string(g.bins) +
            ") must be a multiple of sectors (Ns = " + std::to_string(g.sectors) +
            "), so that sectors are equal and symmetric about the axis");
  if (g.sectors > kMaxSectors)
    invalid("sectors (Ns = " + std::to_string(g.sectors) + ") exceed " +
            std::to_string(kMaxSectors) + ", the largest pattern-class table this model builds");
  if (static_cast<long long>(g.rings) * g.bins > kMaxPolarCells)
    invalid("rings x bins exceeds " + std::to_string(kMaxPolarCells) + " polar cells");
}

PatternClasses pattern_classes(const SectoralGrid& grid) {
  const int ns = grid.sectors;
  const auto sectors = static_cast<std::size_t>(ns);
  // Sectors from the axis outwards; the first occupied one in this order sets theta(S).
  std::vector<int> order(sectors);
  for (int j = 0; j < ns; ++j) order[static_cast<std::size_t>(j)] = j;
  std::stable_sort(order.begin(), order.end(),
                   [ns](int a, int b) { return off_axis_rank(a, ns) < off_axis_rank(b, ns); });
  std::vector<int> ranks;  // distinct off-axis ranks, ascending: one group each
  for (const int j : order)
    if (ranks.empty() || ranks.back() != off_axis_rank(j, ns))
      ranks.push_back(off_axis_rank(j, ns));
  const std::size_t groups = ranks.size();
  const auto group_of = [&](int j) {
    return static_cast<std::size_t>(
        std::lower_bound(ranks.begin(), ranks.end(), off_axis_rank(j, ns)) - ranks.begin());
  };

  // weight[v][g * Ns + (m - 1)] by a Poisson-binomial recursion over the ordered sectors:
  // the first occupied sector t, none before it, and m - 1 of those after it occupied.
  const int conditions = 2 * ns + 1;
  const double empty_sector = std::exp2(-grid.bins_per_sector());
  const double empty_sector_less_one = std::exp2(-(grid.bins_per_sector() - 1));
  std::vector<std::vector<double>> weight(static_cast<std::size_t>(conditions),
                                          std::vector<double>(groups * sectors, 0.0));
  for (int v = 0; v < conditions; ++v) {
    std::vector<double> p_empty(sectors, empty_sector);  // by position in `order`
    for (std::size_t t = 0; t < sectors; ++t) {
      if (v >= 1 && v <= ns && order[t] == v - 1) p_empty[t] = 0.0;
      if (v > ns && order[t] == v - 1 - ns) p_empty[t] = empty_sector_less_one;
    }
    // count_after[t][k]: probability that k of the sectors at positions > t are occupied.
    std::vector<std::vector<double>> count_after(sectors, std::vector<double>(sectors, 0.0));
    std::vector<double> dist{1.0};
    for (std::size_t t = sectors; t-- > 0;) {
      count_after[t].assign(dist.begin(), dist.end());
      count_after[t].resize(sectors, 0.0);
      std::vector<double> next(dist.size() + 1, 0.0);
      for (std::size_t k = 0; k < dist.size(); ++k) {
        next[k] += dist[k] * p_empty[t];
        next[k + 1] += dist[k] * (1.0 - p_empty[t]);
      }
      dist = std::move(next);
    }
    double none_before = 1.0;
    for (std::size_t t = 0; t < sectors; ++t) {
      const double first_here = none_before * (1.0 - p_empty[t]);
      const std::size_t g = group_of(order[t]);
      for (std::size_t k = 0; k < sectors; ++k)
        weight[static_cast<std::size_t>(v)][g * sectors + k] += first_here * count_after[t][k];
      none_before *= p_empty[t];
    }
  }

  PatternClasses out;
  out.sectors = ns;
  std::vector<std::size_t> kept;  // classes possible under some condition
  for (std::size_t c = 0; c < groups * sectors; ++c) {
    bool possible = false;
    for (const auto& w : weight) possible = possible || w[c] > 0.0;
    if (!possible) continue;
    kept.push_back(c);
    out.theta.push_back(static_cast<double>(ranks[c / sectors]) / ns);
    out.size.push_back(static_cast<int>(c % sectors) + 1);
  }
  for (const auto& w : weight)
    for (const std::size_t c : kept)
      out.log_weight.push_back(w[c] > 0.0 ? std::log(w[c]) : kMinusInfinity);
  return out;
}

void sectoral_ism(const ConeSensorModel& model, const SectoralGrid& grid, double z,
                  std::span<double> out) {
  if (out.size() != grid.cells())
    fail<std::invalid_argument>("sectoral_ism: output size differs from rings x bins");
  const PatternClasses classes = pattern_classes(grid);
  const int reference_ring =
      static_cast<int>(std::clamp(std::round(z / grid.cell), 1.0, double(grid.rings)));
  const NaturalLogArith arith{model, grid, classes, z, reference_ring};
  const auto bins = static_cast<std::size_t>(grid.bins);
  const auto per_sector = static_cast<std::size_t>(grid.bins_per_sector());
  sectoral_ism_rings(arith, grid.rings, grid.sectors, classes.classes(),
                     [&](int ring, int sector, double p) {
                       double* first = &out[static_cast<std::size_t>(ring - 1) * bins +
                                            static_cast<std::size_t>(sector) * per_sector];
                       std::fill(first, first + per_sector, p);
                     });
}

std::vector<double> sectoral_ism(const ConeSensorModel& model, const SectoralGrid& grid, double z) {
  std::vector<double> out(grid.cells());
  sectoral_ism(model, grid, z, out);
  return out;
}

long double sectoral_configuration_likelihood(const ConeSensorModel& model,
                                              const SectoralGrid& grid, double z,
                                              unsigned long long g) {
  if (g == 0) return 0.0L;
  const int first = std::countr_zero(g);
  const int ring = first / grid.bins + 1;
  const unsigned long long ring_bits =
      g >> ((ring - 1) * grid.bins) & ((1ull << grid.bins) - 1);  // bins < 64 here
  int size = 0;
  int nearest_rank = grid.sectors;
  for (int j = 0; j < grid.sectors; ++j) {
    const unsigned long long sector_bits = ((1ull << grid.bins_per_sector()) - 1)
                                           << (j * grid.bins_per_sector());
    if (!(ring_bits & sector_bits)) continue;
    ++size;
    nearest_rank = std::min(nearest_rank, off_axis_rank(j, grid.sectors));
  }
  const double theta = static_cast<double>(nearest_rank) / grid.sectors;
  const double d = grid.ring_distance(ring);
  return std::exp(static_cast<long double>(model.log_density_of_error(z - d, d, theta, size)));
}

}  // namespace intgrid::core
