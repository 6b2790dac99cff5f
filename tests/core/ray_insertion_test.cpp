// Integer-geometry scan insertion: the incremental ray walk against the projection computed
// afresh and against the ray's geometry in double, the insertion against cells summed one by one,
// the unchecked path (rays inside the grid) against the checked one, and the tables.
#include "intgrid/core/ray_insertion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <random>
#include <vector>

#include "intgrid/core/narrow_ism.hpp"
#include "intgrid/core/scan_insertion.hpp"

using namespace intgrid::core;

namespace intgrid {
namespace {

struct Visit {
  int ix, iy;
  std::int64_t d;
};

std::vector<Visit> walk(const IntegerRays& rays, std::int64_t px, std::int64_t py,
                        std::int32_t angle, std::int64_t limit) {
  std::vector<Visit> out;
  rays.walk(px, py, angle, limit, [&](int ix, int iy, std::int64_t d) {
    out.push_back({ix, iy, d});
  });
  return out;
}

TEST(IntegerRays, WalkCrossesNeighbouringCellsAlongTheRayWithExactProjections) {
  const std::vector<std::int32_t> sine = make_sine_table_q16();
  std::mt19937 random(7);
  std::uniform_int_distribution<std::int32_t> angle_of(0, kAngleUnitsPerTurn - 1);
  for (const std::int32_t cell : {10, 50, 100, 333}) {
    const IntegerRays rays(sine, cell);
    std::uniform_int_distribution<std::int64_t> offset(-cell / 2, cell / 2);
    for (int trial = 0; trial < 400; ++trial) {
      const std::int64_t px = offset(random), py = offset(random);
      // Axis-aligned and diagonal directions too, where the comparisons tie.
      const std::int32_t angle = trial < 16 ? trial * 4096 : angle_of(random);
      const std::int64_t limit = 20 * cell;
      const std::vector<Visit> cells = walk(rays, px, py, angle, limit);
      ASSERT_FALSE(cells.empty());
      const std::int64_t c = cell, c2 = 2 * c, x = 2 * px + c, y = 2 * py + c;
      const std::int64_t cs = rays.cos(angle), sn = rays.sin(angle);
      const double theta = 2.0 * std::numbers::pi * angle / kAngleUnitsPerTurn;
      const double ux = static_cast<double>(cs) / 65536.0, uy = static_cast<double>(sn) / 65536.0;
      const auto cd = static_cast<double>(c);
      for (std::size_t i = 0; i < cells.size(); ++i) {
        const Visit& v = cells[i];
        // The projection of the cell centre, computed afresh.
        EXPECT_EQ(v.d, ((v.ix * c2 + c - x) * cs + (v.iy * c2 + c - y) * sn) >> 17);
        EXPECT_LE(v.d, limit);
        if (i > 0) {
          EXPECT_EQ(std::abs(v.ix - cells[i - 1].ix) + std::abs(v.iy - cells[i - 1].iy), 1);
        }
        // The ray (from the start, along the table's direction) passes within the cell.
        const double cx = v.ix * cd - static_cast<double>(px),
                     cy = v.iy * cd - static_cast<double>(py);
        const double across = std::abs(cx * uy - cy * ux);
        EXPECT_LE(across, cd * (std::abs(ux) + std::abs(uy)) / 2.0 + 1e-6 * cd)
            << "cell " << cell << " angle " << angle << " theta " << theta;
      }
      // It stops at the first cell past the limit.
      const Visit& last = cells.back();
      const int nx = last.ix + (cs > 0 ? 1 : -1), ny = last.iy + (sn > 0 ? 1 : -1);
      const auto d_of = [&](int ix, int iy) {
        return ((ix * c2 + c - x) * cs + (iy * c2 + c - y) * sn) >> 17;
      };
      EXPECT_TRUE(d_of(nx, last.iy) > limit || d_of(last.ix, ny) > limit);
    }
  }
}

TEST(IsmTable, ProbabilityTableHoldsTheExactIsmAndReadingPicksTheNearestBin) {
  const GaussianBeamModel model{0.03, 0.0};
  const double cell = 0.05;
  const IsmTable<double> table = make_probability_ism_table(model, cell, 6, 2000);
  ASSERT_EQ(table.begin.size(), std::size_t(2000 / 6 + 3));
  for (const std::int32_t z_mm : {1, 3, 4, 250, 1337, 1999}) {
    const std::int32_t bin = (z_mm + 3) / 6;
    if (bin == 0) {  // under half a step: the reading says nothing
      EXPECT_TRUE(table.reading(z_mm).empty());
      continue;
    }
    const double z = bin * 6 / 1000.0;
    const std::vector<double> ism =
        narrow_ism(model, z, cell, ism_cells_for_reading(model, z, cell));
    const std::span<const double> got = table.reading(z_mm);
    ASSERT_EQ(got.size(), ism.size()) << z_mm;
    for (std::size_t k = 0; k < ism.size(); ++k) EXPECT_EQ(got[k], ism[k]) << z_mm << " " << k;
    EXPECT_LE(got.size(), table.longest);
  }
}

// A scan of random readings; the oracle sums each reading's table entries cell by cell with the
// walk and the line-of-sight rule written out here.
TEST(ScanInsertion, AlongRaysEqualsCellsSummedOneByOneAndTheEdgeCheckChangesNothingInside) {
  const std::vector<std::int32_t> sine = make_sine_table_q16();
  const std::int32_t cell_mm = 50;
  const IntegerRays rays(sine, cell_mm);
  const SepsCodec codec = SepsCodec::for_levels(8, 0.6, 16);
  const NarrowIsmTable table =
      make_index_ism_table(GaussianBeamModel{0.03, 0.0}, 0.05, codec, 6, 3000, 1);
  std::mt19937 random(11);
  std::vector<std::int32_t> bearing, range;
  for (int b = 0; b < 181; ++b) {
    bearing.push_back(b * 180 - 16384);
    const std::int32_t z = std::uniform_int_distribution<std::int32_t>(-100, 3200)(random);
    range.push_back(b % 17 == 0 ? 0 : z);  // some unusable: 0, negative, past 3000
  }
  const int side = 2 * 3000 / cell_mm + 20;
  const GridGeometry big{side, side, 0.05, 0.0, 0.0};
  Grid<std::int8_t> grid(big, 0);
  const std::int64_t px = 13, py = -21;
  const std::int32_t heading = 5000;
  insert_scan_along_rays(grid, rays, table, side / 2, side / 2, px, py, heading, bearing, range,
                         3000, codec.max_index());

  std::map<std::pair<int, int>, int> sums;
  for (std::size_t b = 0; b < range.size(); ++b) {
    const std::int32_t z = range[b];
    if (z <= 0 || z >= 3000) continue;
    const std::span<const std::int8_t> values = table.reading(z);
    const auto n = static_cast<std::int64_t>(values.size());
    rays.walk(px, py, heading + bearing[b], n * cell_mm + cell_mm / 2,
              [&](int ix, int iy, std::int64_t d) {
                const std::int64_t k = (d + cell_mm / 2) / cell_mm;
                if (k < 1 || k > n) return;
                int& s = sums[{side / 2 + ix, side / 2 + iy}];
                s = std::clamp(s + values[static_cast<std::size_t>(k - 1)], -codec.max_index(),
                               codec.max_index());
              });
  }
  int changed = 0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const auto it = sums.find({x, y});
      const int expected = it == sums.end() ? 0 : it->second;
      ASSERT_EQ(grid.at(x, y), expected) << x << " " << y;
      changed += expected != 0;
    }
  EXPECT_GT(changed, 1000);

  // A grid cut through the scan: its cells are the big grid's, those past its edge dropped.
  const int cut = side / 3;
  Grid<std::int8_t> small({cut * 2, cut, 0.05, 0.0, 0.0}, 0);
  insert_scan_along_rays(small, rays, table, side / 2 - cut, side / 2 - cut, px, py, heading,
                         bearing, range, 3000, codec.max_index());
  for (int y = 0; y < cut; ++y)
    for (int x = 0; x < 2 * cut; ++x)
      ASSERT_EQ(small.at(x, y), grid.at(x + cut, y + cut)) << x << " " << y;
}

}  // namespace
}  // namespace intgrid
