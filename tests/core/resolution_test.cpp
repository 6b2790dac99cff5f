#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "intgrid/core/resolution.hpp"

using namespace intgrid::core;

namespace intgrid {
namespace {

TEST(Resolution, PmaxDependsOnlyOnTheRatioOfCellToSigma) {
  // The thesis's figure 2.6: s/sigma = 3 for (0.6, 0.2) and (0.9, 0.3).
  EXPECT_NEAR(narrow_pmax(0.006, 0.002), narrow_pmax(0.009, 0.003), 1e-12);
  EXPECT_NEAR(narrow_pmax(0.05, 0.03), narrow_pmax(0.5, 0.3), 1e-12);
  EXPECT_GT(narrow_pmax(0.006, 0.002), narrow_pmax(0.005, 0.002));
}

TEST(Resolution, PmaxGrowsWithCellSize) {
  double previous = 0.5;
  // Below s/sigma ~ 0.3 Pmax is 1/2 to double precision: the ISM says nothing.
  EXPECT_LT(narrow_pmax(0.001, 0.01), 0.5 + 1e-12);
  for (double ratio = 0.4; ratio < 8.0; ratio *= 1.2) {
    const double p = narrow_pmax(ratio * 0.01, 0.01);
    EXPECT_GT(p, previous) << "s/sigma=" << ratio;
    previous = p;
  }
}

TEST(Resolution, WorstCaseIsBelowEveryOffsetAndBelowTheCentredCase) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const double ratio : {0.5, 1.0, 2.0, 3.0}) {
    const WorstCasePmax worst = narrow_pmax_worst_case(ratio * 0.02, 0.02);
    EXPECT_LE(worst.pmax, narrow_pmax(ratio * 0.02, 0.02));
    for (int i = 0; i < 200; ++i)
      ASSERT_LE(worst.pmax, narrow_pmax(ratio * 0.02, 0.02, unit(rng)) + 1e-12) << ratio;
  }
}

TEST(Resolution, SmallestCellReachesPmaxAndNoSmallerCellDoes) {
  for (const bool worst_case : {false, true}) {
    for (const double pmax :
         worst_case ? std::vector{0.55, 0.6, 0.65} : std::vector{0.6, 0.8, 0.95}) {
      const double sigma = 0.02;
      const double cell = smallest_cell_for_pmax(sigma, pmax, worst_case);
      const auto reached = [&](double s) {
        return worst_case ? narrow_pmax_worst_case(s, sigma).pmax : narrow_pmax(s, sigma);
      };
      EXPECT_GE(reached(cell), pmax - 1e-12);
      EXPECT_LT(reached(cell * (1.0 - 1e-6)), pmax);
    }
  }
  EXPECT_GT(smallest_cell_for_pmax(0.02, 0.65, true), smallest_cell_for_pmax(0.02, 0.65, false));
}

TEST(Resolution, WorstCaseNeverPassesTwoThirds) {
  // A reading on a cell boundary splits the evidence between the two cells:
  // P = (p/2^m) / (1.5 p/2^m) = 2/3 at best, however coarse the grid.
  for (const double ratio : {2.0, 5.0, 20.0}) {
    const WorstCasePmax worst = narrow_pmax_worst_case(ratio, 1.0);
    EXPECT_LE(worst.pmax, 2.0 / 3.0 + 1e-12);
    EXPECT_NEAR(worst.offset, 0.5, 1e-3);
  }
  EXPECT_NEAR(narrow_pmax_worst_case(20.0, 1.0).pmax, 2.0 / 3.0, 1e-9);
  EXPECT_THROW(smallest_cell_for_pmax(0.02, 0.7, true), std::invalid_argument);
}

TEST(Resolution, RejectsImpossibleRequests) {
  EXPECT_THROW(smallest_cell_for_pmax(-0.1, 0.9), std::invalid_argument);
  EXPECT_THROW(smallest_cell_for_pmax(0.1, 0.4), std::invalid_argument);
  EXPECT_THROW(smallest_cell_for_pmax(0.1, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace intgrid
