// The linear sectoral ISM against brute-force Bayes over every configuration, the
// narrow ISM, and its own behaviour for long grids.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "intgrid/core/narrow_ism.hpp"
#include "intgrid/core/sectoral_ism.hpp"

using namespace intgrid::core;

namespace intgrid {
namespace {

struct Shape {
  int rings, bins, sectors;
};

std::vector<double> brute_force(const ConeSensorModel& model, const SectoralGrid& grid, double z) {
  return brute_force_ism(grid.cells(), [&](std::size_t g) {
    return sectoral_configuration_likelihood(model, grid, z, g);
  });
}

// Every shape with N = R * A <= 20 cells that the acceptance list names: A = 1 (narrow),
// Ns = 1, Ns = A, and splits in between.
const Shape kShapes[] = {{1, 1, 1}, {3, 1, 1}, {20, 1, 1},  {2, 2, 1},  {2, 2, 2},
                         {3, 4, 2}, {5, 4, 1}, {5, 4, 2},   {5, 4, 4},  {3, 6, 1},
                         {3, 6, 3}, {3, 6, 6}, {2, 8, 4},   {2, 8, 8},  {4, 5, 5},
                         {4, 5, 1}, {2, 9, 3}, {1, 16, 16}, {1, 20, 5}, {2, 10, 10}};

TEST(SectoralIsm, EqualsBruteForceBayesForEveryShape) {
  const ConeSensorModel model{0.02, 0.05, 0.5, 0.5};
  for (const Shape& s : kShapes) {
    const SectoralGrid grid{0.5, s.rings, s.bins, s.sectors, 0.05};
    check_sectoral_grid(grid);
    // Readings before the first ring, on a ring, between rings, at and past the last.
    for (const double z_cells :
         {0.3, 1.0, 1.5, 0.5 * s.rings + 0.27, double(s.rings), s.rings + 0.6}) {
      const double z = z_cells * grid.cell;
      const std::vector<double> fast = sectoral_ism(model, grid, z);
      const std::vector<double> slow = brute_force(model, grid, z);
      for (std::size_t i = 0; i < fast.size(); ++i)
        ASSERT_NEAR(fast[i], slow[i], 1e-12) << "R=" << s.rings << " A=" << s.bins
                                             << " Ns=" << s.sectors << " z=" << z << " cell " << i;
    }
  }
}

TEST(SectoralIsm, EqualsBruteForceWithWideAndGrowingSigma) {
  // A sensor model whose spread in every effect is large, so that classes differ a lot.
  const ConeSensorModel model{0.06, 0.8, 2.0, 3.0};
  for (const Shape& s : {Shape{4, 4, 2}, Shape{2, 9, 3}, Shape{3, 6, 6}}) {
    const SectoralGrid grid{1.2, s.rings, s.bins, s.sectors, 0.1};
    for (const double z : {0.05, 0.17, 0.31}) {
      const std::vector<double> fast = sectoral_ism(model, grid, z);
      const std::vector<double> slow = brute_force(model, grid, z);
      for (std::size_t i = 0; i < fast.size(); ++i) ASSERT_NEAR(fast[i], slow[i], 1e-12);
    }
  }
}

TEST(SectoralIsm, OneBinIsTheNarrowIsm) {
  const ConeSensorModel model{0.03, 0.1, 0.5, 0.5};
  // One bin: theta = 0, one sector, so sigma is the narrow model's times 1.
  const GaussianBeamModel narrow{0.03, 0.1};
  for (const int rings : {1, 7, 300, 5000}) {
    const SectoralGrid grid{0.1, rings, 1, 1, 0.02};
    for (const double z : {0.011, 0.1, 0.0917 * rings, 0.02 * rings + 0.01}) {
      const std::vector<double> wide = sectoral_ism(model, grid, z);
      const std::vector<double> line = narrow_ism(narrow, z, grid.cell, std::size_t(rings));
      for (std::size_t i = 0; i < wide.size(); ++i) ASSERT_NEAR(wide[i], line[i], 1e-12) << i;
    }
  }
}

TEST(SectoralIsm, CellsOfOneSectorAndRingShareTheirProbability) {
  const SectoralGrid grid{0.5, 30, 16, 4, 0.05};
  const std::vector<double> p = sectoral_ism(ConeSensorModel{}, grid, 0.77);
  for (int r = 1; r <= grid.rings; ++r)
    for (int a = 0; a < grid.bins; ++a) {
      const int first = grid.sector_of_bin(a) * grid.bins_per_sector();
      EXPECT_EQ(p[std::size_t((r - 1) * grid.bins + a)],
                p[std::size_t((r - 1) * grid.bins + first)]);
    }
  // Mirror sectors see the same thing.
  for (int r = 1; r <= grid.rings; ++r)
    for (int a = 0; a < grid.bins; ++a)
      EXPECT_NEAR(p[std::size_t((r - 1) * grid.bins + a)],
                  p[std::size_t((r - 1) * grid.bins + grid.bins - 1 - a)], 1e-15);
}

TEST(SectoralIsm, StableForAMillionRings) {
  // 2^-M_r underflows a double after 64 rings of 16 bins; the answer near z must not
  // depend on how many rings lie beyond it, and far cells tend to 1/2.
  const ConeSensorModel model;
  const SectoralGrid small{0.5, 60, 16, 4, 0.05}, large{0.5, 1'000'000, 16, 4, 0.05};
  const double z = 1.234;
  const std::vector<double> a = sectoral_ism(model, small, z), b = sectoral_ism(model, large, z);
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_NEAR(a[i], b[i], 1e-12) << i;
  for (const double p : b) ASSERT_TRUE(p >= 0.0 && p <= 1.0);
  EXPECT_NEAR(b.back(), 0.5, 1e-12);
  // And z far out in a long grid, sigma constant: the rings up to z look exactly as they
  // do for the same reading near the start of a short grid.
  const ConeSensorModel flat{0.02, 0.0, 0.5, 0.5};
  const SectoralGrid short_grid{0.5, 100, 16, 4, 0.05};
  const std::vector<double> near_start = sectoral_ism(flat, short_grid, 2.0);
  const std::vector<double> far_out = sectoral_ism(flat, large, 40'000.0);
  for (std::size_t k = 0; k < 30; ++k)
    for (std::size_t bin = 0; bin < 16; ++bin)
      ASSERT_NEAR(far_out[(800'000 - 1 - k) * 16 + bin], near_start[(40 - 1 - k) * 16 + bin], 1e-9)
          << k << " rings before z";
}

TEST(SectoralIsm, RejectsInvalidGrids) {
  const auto rejects = [](SectoralGrid g, const char* word) {
    try {
      check_sectoral_grid(g);
      ADD_FAILURE() << "accepted " << word;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  rejects({0.5, 10, 16, 3, 0.05}, "multiple");
  rejects({0.5, 10, 4, 8, 0.05}, "exceed bins");
  rejects({0.5, 10, 128, 128, 0.05}, "exceed 64");
  rejects({0.5, 10, 2000, 4, 0.05}, "exceed 1000");
  rejects({0.5, 0, 16, 4, 0.05}, "rings");
  rejects({0.5, 10, 0, 1, 0.05}, "bins");
  rejects({0.5, 10, 16, 0, 0.05}, "sectors");
  rejects({0.5, 10, 16, 4, 0.0}, "cell");
  rejects({0.5, 10, 16, 4, -1.0}, "cell");
  rejects({0.0, 10, 16, 4, 0.05}, "FOV");
  rejects({std::numbers::pi, 10, 16, 4, 0.05}, "FOV");
  rejects({0.5, 200'000'000, 1, 1, 0.05}, "polar cells");
}

}  // namespace
}  // namespace intgrid
