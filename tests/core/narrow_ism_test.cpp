#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "intgrid/core/narrow_ism.hpp"

using namespace intgrid::core;

namespace intgrid {
namespace {

TEST(NarrowIsm, EqualsBruteForceBayesForEverySmallGrid) {
  std::mt19937_64 rng(20200619);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int cases = 0;
  for (std::size_t n = 1; n <= 20; ++n) {
    const int trials = n <= 14 ? 40 : 4;
    for (int trial = 0; trial < trials; ++trial, ++cases) {
      const double cell = 0.01 + 0.2 * unit(rng);
      const GaussianBeamModel model{cell * (0.2 + 3.0 * unit(rng)),
                                    trial % 2 ? 0.0 : 2.0 * unit(rng)};
      const double z = cell * (0.5 + (static_cast<double>(n) + 1.0) * unit(rng));
      const std::vector<double> fast = narrow_ism(model, z, cell, n);
      const std::vector<double> oracle = brute_force_ism(
          n, [&](std::size_t g) { return narrow_configuration_likelihood(model, z, cell, g); });
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_NEAR(fast[i], oracle[i], 1e-12)
            << "n=" << n << " cell=" << i + 1 << " z=" << z << " s=" << cell
            << " sigma0=" << model.sigma0 << " k_d=" << model.k_d;
    }
  }
  EXPECT_GT(cases, 500);
}

// An independent long-double evaluation of eq. 2.12, normalized at the cell
// nearest the reading instead of at the largest term.
std::vector<long double> long_double_ism(const GaussianBeamModel& model, long double z,
                                         long double cell, std::size_t n) {
  const long double centre = std::round(z / cell);
  std::vector<long double> w(n);
  long double total = 0.0L;
  for (std::size_t k = 1; k <= n; ++k) {
    const long double d = static_cast<long double>(k) * cell;
    const long double sigma = model.sigma0 * (1.0L + model.k_d * d);
    const long double u = (z - d) / sigma;
    w[k - 1] = std::exp(-0.5L * u * u - std::log(sigma) -
                        (static_cast<long double>(k) - centre) * std::numbers::ln2_v<long double>);
    total += w[k - 1];
  }
  std::vector<long double> p(n);
  long double prefix = 0.0L;
  for (std::size_t k = 0; k < n; ++k) {
    p[k] = (0.5L * prefix + w[k]) / total;
    prefix += w[k];
  }
  return p;
}

TEST(NarrowIsm, MillionCellsMatchLongDoubleReference) {
  constexpr std::size_t kCells = 1'000'000;
  const double cell = 0.05;
  // The reading deep in the grid: 2^-k alone would underflow a double 700 times over.
  for (const GaussianBeamModel model :
       {GaussianBeamModel{0.03, 0.0}, GaussianBeamModel{0.02, 1e-4}}) {
    for (const double z : {12.34, 25'000.021, 49'999.0}) {
      const std::vector<double> fast = narrow_ism(model, z, cell, kCells);
      const std::vector<long double> reference = long_double_ism(model, z, cell, kCells);
      double worst = 0.0;
      for (std::size_t k = 0; k < kCells; ++k)
        worst = std::max(worst, std::abs(fast[k] - static_cast<double>(reference[k])));
      EXPECT_LT(worst, 1e-12) << "z=" << z << " k_d=" << model.k_d;
      // Sanity that the case is not trivial: the peak is confident and sits near z.
      const auto peak = std::max_element(fast.begin(), fast.end()) - fast.begin() + 1;
      EXPECT_GT(fast[static_cast<std::size_t>(peak - 1)], 0.501);
      EXPECT_LE(std::abs(static_cast<double>(peak) - z / cell), 1.0);
    }
  }
}

TEST(NarrowIsm, FarCellsTendToOneHalfAndNearCellsToEmpty) {
  const GaussianBeamModel model{0.03, 0.0};
  const std::vector<double> ism = narrow_ism(model, 5.0, 0.05, 400);
  EXPECT_LT(ism[10], 1e-9);           // 0.55 m: surely empty
  EXPECT_NEAR(ism[399], 0.5, 1e-12);  // 20 m: behind the obstacle, no information
  for (double p : ism) {
    EXPECT_GE(p, 0.0);
    EXPECT_LE(p, 1.0);
  }
}

TEST(NarrowIsm, ArgmaxFollowsTheoremOne) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const double cell = 0.01 + 0.1 * unit(rng);
    const GaussianBeamModel model{cell * (0.1 + 2.0 * unit(rng)), 0.0};
    const std::size_t n = 200;
    const double z = cell * (1.0 + 150.0 * unit(rng));
    const std::vector<double> ism = narrow_ism(model, z, cell, n);
    const auto argmax =
        static_cast<std::size_t>(std::max_element(ism.begin(), ism.end()) - ism.begin()) + 1;
    const std::size_t predicted = predicted_argmax_cell(model, z, cell, n);
    ASSERT_EQ(argmax, predicted) << "z=" << z << " s=" << cell;
    // Lemma 2.4.1's Gaussian form (eq. 2.13): the nearer of the two bracketing centres.
    const double m = std::floor(z / cell);
    const std::size_t lemma =
        static_cast<std::size_t>(m) + (z - m * cell < (m + 1.0) * cell - z ? 0 : 1);
    ASSERT_EQ(predicted, lemma);
  }
}

}  // namespace
}  // namespace intgrid
