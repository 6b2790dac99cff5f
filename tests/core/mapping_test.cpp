#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "intgrid/core/map_compare.hpp"
#include "intgrid/core/mapping.hpp"

using namespace intgrid::core;

namespace intgrid {
namespace {

GridGeometry square_grid(int cells, double resolution) {
  return {cells, cells, resolution, -0.5 * cells * resolution, -0.5 * cells * resolution};
}

// A full turn of n beams: every cell near the sensor must land in exactly one
// footprint, the one whose bearing interval holds the cell centre's bearing.
TEST(Footprint, BeamsPartitionTheDiscAndFollowTheBearing) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const GridGeometry grid = square_grid(120, 0.05);
  for (int trial = 0; trial < 6; ++trial) {
    const int n = 90 + 97 * trial;
    const Vec2 sensor{0.3 * (unit(rng) - 0.5), 0.3 * (unit(rng) - 0.5)};
    const double start = 2.0 * std::numbers::pi * unit(rng);
    const double step = 2.0 * std::numbers::pi / n;
    const std::size_t cells = 50;
    std::vector<int> beam_of(grid.size(), -1), visits(grid.size(), 0);
    std::vector<std::size_t> k_of(grid.size(), 0);
    for (int i = 0; i < n; ++i)
      for_each_footprint_cell(grid, sensor, unit_vector(start + i * step),
                              unit_vector(start + (i + 1) * step), 0.05, cells,
                              [&](std::size_t index, std::size_t k) {
                                ++visits[index];
                                beam_of[index] = i;
                                k_of[index] = k;
                              });
    for (int iy = 0; iy < grid.height; ++iy)
      for (int ix = 0; ix < grid.width; ++ix) {
        const double dx = grid.centre_x(ix) - sensor.x, dy = grid.centre_y(iy) - sensor.y;
        const double rho = std::hypot(dx, dy);
        const auto k = static_cast<std::size_t>(std::floor(rho / 0.05 + 0.5));
        const std::size_t index = grid.index(ix, iy);
        if (k < 1 || k > cells) {
          ASSERT_EQ(visits[index], 0) << ix << "," << iy;
          continue;
        }
        ASSERT_EQ(visits[index], 1) << ix << "," << iy << " trial " << trial;
        ASSERT_EQ(k_of[index], k);
        double bearing = std::atan2(dy, dx) - start;
        bearing -= 2.0 * std::numbers::pi * std::floor(bearing / (2.0 * std::numbers::pi));
        const double position = bearing / step;
        if (std::abs(position - std::round(position)) > 1e-9) {  // not on a boundary
          ASSERT_EQ(beam_of[index], static_cast<int>(std::floor(position)) % n);
        }
      }
  }
}

// The footprint's definition, cell by cell over the whole grid (brute force): the walk, which
// tests only the ends of the runs its lines' set-up names, must visit exactly these cells with
// these k, for sectors from a hundredth of a degree to nearly half a turn, sensors inside and
// outside the grid, bands of rows, and with or without an inner radius.
TEST(Footprint, VisitsExactlyTheCellsItsDefinitionNames) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const GridGeometry grid{97, 83, 0.05, -2.1, -1.7};
  for (int trial = 0; trial < 800; ++trial) {
    const Vec2 sensor{-3.0 + 6.0 * unit(rng), -3.0 + 6.0 * unit(rng)};
    const double start = 2.0 * std::numbers::pi * unit(rng);
    const double angle =
        trial % 7 == 0 ? 3.1 * unit(rng) : std::pow(10.0, -4.0 + 4.4 * unit(rng));  // radians
    const Vec2 from = unit_vector(start), to = unit_vector(start + angle);
    const auto cells = static_cast<std::size_t>(1 + unit(rng) * 120.0);
    RowBand rows;
    if (trial % 3 == 0) {
      rows.first = static_cast<int>(unit(rng) * grid.height);
      rows.last = rows.first + static_cast<int>(unit(rng) * 30.0);
    }
    const double reach = (static_cast<double>(cells) + 0.5) * 0.05;
    // No inner radius, a random one, or one through a cell's centre (a tie the walk must break
    // as the definition does).
    double inner_sq = 0.0;
    if (trial % 4 == 1) inner_sq = std::pow(unit(rng) * reach, 2);
    if (trial % 4 == 3) {
      const Vec2 v{grid.centre_x(static_cast<int>(unit(rng) * grid.width)) - sensor.x,
                   grid.centre_y(static_cast<int>(unit(rng) * grid.height)) - sensor.y};
      inner_sq = v.x * v.x + v.y * v.y;
    }
    std::vector<std::size_t> visited(grid.size(), 0);
    for_each_footprint_cell(
        grid, sensor, from, to, 0.05, cells,
        [&](std::size_t index, std::size_t k) {
          ASSERT_EQ(visited[index], 0u) << "visited twice";
          visited[index] = k;
        },
        rows, inner_sq);
    const Vec2 mid{from.x + to.x, from.y + to.y};
    for (int iy = 0; iy < grid.height; ++iy)
      for (int ix = 0; ix < grid.width; ++ix) {
        const Vec2 v{grid.centre_x(ix) - sensor.x, grid.centre_y(iy) - sensor.y};
        std::size_t k = 0;
        if (iy >= rows.first && iy <= rows.last && cross(from, v) >= 0.0 && cross(to, v) < 0.0 &&
            dot(mid, v) > 0.0 && v.x * v.x + v.y * v.y < reach * reach &&
            v.x * v.x + v.y * v.y >= inner_sq) {
          k = static_cast<std::size_t>(std::sqrt(v.x * v.x + v.y * v.y) * (1.0 / 0.05) + 0.5);
          if (k > cells) k = 0;
        }
        ASSERT_EQ(visited[grid.index(ix, iy)], k)
            << "trial " << trial << " cell " << ix << "," << iy;
      }
  }
}

Scan one_scan(const std::vector<double>& ranges, Pose2 robot) {
  Scan scan;
  scan.robot = robot;
  scan.sensor_mount = {0.1, 0.0, 0.0};
  scan.angle0 = -std::numbers::pi / 2;
  scan.dangle = std::numbers::pi / static_cast<double>(ranges.size() - 1);
  scan.max_range = 8.0;
  scan.ranges = ranges;
  return scan;
}

// Every cell is in one footprint, so one scan into an empty grid leaves each cell
// at its beam's ISM value: the integer grid must hold exactly the conservative
// quantization of the double grid.
TEST(ScanInsertion, IntegerScanIsTheQuantizedDoubleScan) {
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<int> millimetres(300, 5500);
  std::vector<double> ranges(181);
  // Readings on the inserter's 1 mm grid, computed as it computes them.
  for (double& r : ranges) r = millimetres(rng) * 0.001;
  const Scan scan = one_scan(ranges, {0.2, -0.1, 0.3});
  const GridGeometry geometry = square_grid(260, 0.05);
  const GaussianBeamModel model{0.03, 0.01};
  for (const SepsCodec& codec : {SepsCodec(8, 0.05), SepsCodec(16, 0.01)}) {
    ProbabilityGrid reference(geometry, 0.5);
    InsertionStats float_stats, int_stats;
    insert_scan(reference, scan, model, float_stats);
    IndexScanInserter<std::int16_t> inserter(model, 0.05, codec);
    Grid<std::int16_t> grid(geometry, 0);
    inserter.insert(grid, scan, int_stats);
    std::size_t nonzero = 0;
    const int floor_index = codec.quantize_conservative(1e-300);
    for (std::size_t i = 0; i < grid.cells.size(); ++i) {
      // Below 1e-300 the double fusion itself goes subnormal and loses digits.
      if (reference.cells[i] < 1e-300) {
        ASSERT_LE(grid.cells[i], floor_index) << i;
        continue;
      }
      ASSERT_EQ(grid.cells[i], codec.quantize_conservative(reference.cells[i])) << i;
      nonzero += grid.cells[i] != 0;
    }
    EXPECT_GT(nonzero, 3000u);
    EXPECT_EQ(int_stats.inserted, 181u);
    EXPECT_LE(int_stats.cells_updated, float_stats.cells_updated);
  }
}

// Bands of rows filled apart give the cells of the whole grid's insertion, in both arithmetics,
// with cells driven to saturation (the order of the adds matters there) and the bands' cell
// counts adding up to the whole's.
TEST(ScanInsertion, BandsOfRowsFilledApartGiveTheWholeGrid) {
  std::mt19937_64 rng(4);
  std::uniform_int_distribution<int> millimetres(200, 4000);
  std::uniform_real_distribution<double> offset(-1.0, 1.0);
  std::vector<Scan> scans;
  for (int i = 0; i < 80; ++i) {
    std::vector<double> ranges(181);
    for (double& r : ranges) r = millimetres(rng) * 0.001;
    scans.push_back(one_scan(ranges, {offset(rng), offset(rng), 3.0 * offset(rng)}));
  }
  const GridGeometry geometry = square_grid(200, 0.05);
  const std::vector<RowBand> bands{{0, 61}, {62, 62}, {63, 140}, {141, 199}};
  const GaussianBeamModel model{0.03, 0.0};
  const SepsCodec codec(8, 0.02);
  IndexScanInserter<std::int8_t> inserter(model, 0.05, codec);
  Grid<std::int8_t> whole(geometry, 0), banded(geometry, 0);
  InsertionStats whole_stats;
  insert_scans(whole, scans, inserter, whole_stats);
  std::size_t banded_cells = 0;
  for (const RowBand& band : bands) {
    InsertionStats stats;
    insert_scans(banded, scans, inserter, stats, band);
    banded_cells += stats.cells_updated;
  }
  EXPECT_EQ(banded.cells, whole.cells);
  EXPECT_EQ(banded_cells, whole_stats.cells_updated);
  const auto saturated = std::count(whole.cells.begin(), whole.cells.end(), codec.max_index()) +
                         std::count(whole.cells.begin(), whole.cells.end(), -codec.max_index());
  EXPECT_GT(saturated, 100) << "no cell saturated: the order of the adds was not tested";

  ProbabilityGrid whole_p(geometry, 0.5), banded_p(geometry, 0.5);
  InsertionStats whole_p_stats;
  insert_scans(whole_p, scans, model, whole_p_stats);
  for (const RowBand& band : bands) {
    InsertionStats stats;
    insert_scans(banded_p, scans, model, stats, band);
  }
  EXPECT_EQ(banded_p.cells, whole_p.cells);
}

// The integer inserter fills a group of beams' common core in runs and each beam's cells beyond
// it apart; the grid must be the one its definition gives, each valid beam's footprint fused
// beam by beam in the scan's order (for_each_footprint_cell, checked cell by cell above), with
// the same count of cells: scans turning either way, of 90 to 400 beams over up to more than a
// whole turn (those overlap: fused in order), with invalid readings, sensors in and off the
// grid, cells driven to saturation, and bands of rows.
TEST(ScanInsertion, IntegerInsertionIsEachBeamsFootprintFusedInOrder) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const GridGeometry geometry{180, 150, 0.05, -4.0, -3.5};
  const GaussianBeamModel model{0.03, 0.005};
  const SepsCodec codec(8, 0.03);
  IndexScanInserter<std::int8_t> inserter(model, 0.05, codec, VetoBound::strongest_claim);
  IndexScanInserter<std::int8_t> exact(model, 0.05, codec);
  Grid<std::int8_t> grid(geometry, 0), reference(geometry, 0);
  std::size_t saturated = 0;
  for (int trial = 0; trial < 120; ++trial) {
    IndexScanInserter<std::int8_t>& ins = trial % 5 == 4 ? exact : inserter;
    Scan scan;
    scan.robot = {-4.5 + 9.0 * unit(rng), -4.0 + 8.0 * unit(rng), 7.0 * unit(rng)};
    scan.sensor_mount = {0.1, 0.0, 0.0};
    const auto beams = static_cast<std::size_t>(90 + unit(rng) * 310);
    const double fov = (trial % 6 == 0 ? 2.05 : 1.9 * unit(rng) + 0.05) * std::numbers::pi;
    scan.dangle = (trial % 2 == 0 ? 1.0 : -1.0) * fov / static_cast<double>(beams);
    scan.angle0 = -0.5 * fov * (trial % 2 == 0 ? 1.0 : -1.0);
    scan.max_range = 6.0;
    for (std::size_t i = 0; i < beams; ++i) {
      const double u = unit(rng);
      scan.ranges.push_back(u < 0.05 ? 0.0 : u < 0.1 ? 7.0 : std::round(200 + u * 5500) * 0.001);
    }
    RowBand rows;
    if (trial % 4 == 3)
      rows = {static_cast<int>(unit(rng) * 100), 100 + static_cast<int>(unit(rng) * 60)};
    InsertionStats stats, reference_stats;
    ins.insert(grid, scan, stats, rows);
    std::size_t updated = 0;
    for_each_valid_beam(scan, reference_stats, [&](double z, Vec2 from, Vec2 to) {
      const std::vector<std::int8_t> indices = ins.beam_indices(z);
      const Pose2 pose = scan.sensor_pose();
      for_each_footprint_cell(
          geometry, {pose.x, pose.y}, from, to, 0.05, indices.size(),
          [&](std::size_t index, std::size_t k) {
            reference.cells[index] =
                fuse_indices(reference.cells[index], indices[k - 1], codec.max_index());
            ++updated;
          },
          rows);
    });
    ASSERT_EQ(grid.cells, reference.cells) << "trial " << trial;
    ASSERT_EQ(stats.cells_updated, updated) << "trial " << trial;
    ASSERT_EQ(stats.inserted, reference_stats.inserted);
  }
  saturated = static_cast<std::size_t>(
      std::count(grid.cells.begin(), grid.cells.end(), -codec.max_index()) +
      std::count(grid.cells.begin(), grid.cells.end(), codec.max_index()));
  EXPECT_GT(saturated, 100u) << "no cell saturated: the order of the adds was not tested";
}

TEST(ScanInsertion, InvalidReadingsAreSkippedAndCounted) {
  const Scan scan = one_scan({1.0, 0.0, std::nan(""), -2.0, 8.0, 9.5, INFINITY, 2.0}, {});
  const GridGeometry geometry = square_grid(100, 0.05);
  ProbabilityGrid grid(geometry, 0.5);
  InsertionStats stats;
  insert_scan(grid, scan, {0.03, 0.0}, stats);
  EXPECT_EQ(stats.readings, 8u);
  EXPECT_EQ(stats.inserted, 2u);
  EXPECT_EQ(stats.zero, 1u);
  EXPECT_EQ(stats.not_finite, 2u);
  EXPECT_EQ(stats.negative, 1u);
  EXPECT_EQ(stats.at_or_over_max, 2u);
  EXPECT_EQ(stats.skipped(), 6u);
}

TEST(ScanInsertion, VetoBoundLimitsEmptyIndicesToTheStrongestClaim) {
  const SepsCodec codec(8, 0.02);
  IndexScanInserter<std::int8_t> bounded(GaussianBeamModel{0.05, 0.0}, 0.05, codec,
                                         VetoBound::strongest_claim);
  IndexScanInserter<std::int8_t> exact(GaussianBeamModel{0.05, 0.0}, 0.05, codec);
  const std::vector<std::int8_t>& b = bounded.beam_indices(3.0);
  const std::vector<std::int8_t>& e = exact.beam_indices(3.0);
  ASSERT_EQ(b.size(), e.size());
  const int top = *std::max_element(e.begin(), e.end());
  EXPECT_GT(top, 0);
  EXPECT_EQ(e.front(), -127);  // the exact ISM: surely empty near the sensor
  for (std::size_t k = 0; k < e.size(); ++k) EXPECT_EQ(b[k], std::max<int>(e[k], -top));
}

TEST(Mapping, GeometryCoversEveryEndPointAndRejectsEmptyLogs) {
  const Scan scan = one_scan({1.0, 2.0, 3.0}, {5.0, -2.0, 1.0});
  const GridGeometry g = geometry_covering(std::span(&scan, 1), 0.1, 0.5);
  const Pose2 sensor = scan.sensor_pose();
  for (std::size_t i = 0; i < 3; ++i) {
    const double a = sensor.theta + scan.bearing(i);
    EXPECT_TRUE(g.contains(g.cell_x(sensor.x + scan.ranges[i] * std::cos(a)),
                           g.cell_y(sensor.y + scan.ranges[i] * std::sin(a))));
  }
  const Scan empty = one_scan({0.0, std::nan(""), 9.0}, {});
  EXPECT_THROW(geometry_covering(std::span(&empty, 1), 0.1, 0.5), std::invalid_argument);
  EXPECT_THROW(geometry_covering(std::span(&scan, 1), -0.1, 0.5), std::invalid_argument);
  EXPECT_THROW(geometry_covering(std::span(&scan, 1), 1e-9, 0.5), std::invalid_argument);
}

TEST(MapCompare, CountsNearOccupiedCellsBothWays) {
  const GridGeometry g = square_grid(20, 0.1);
  ProbabilityGrid a(g, 0.1), b(g, 0.1);
  a.at(5, 5) = 0.9;  // b has one at distance 0.2: near at tolerance 0.2
  b.at(7, 5) = 0.9;
  a.at(15, 15) = 0.9;  // nothing near in b
  const MapAgreement m = compare_occupied(a, 0.65, b, 0.65, 0.2);
  EXPECT_EQ(m.ours_occupied, 2u);
  EXPECT_EQ(m.reference_occupied, 1u);
  EXPECT_DOUBLE_EQ(m.ours_near_reference, 0.5);
  EXPECT_DOUBLE_EQ(m.reference_near_ours, 1.0);
  EXPECT_DOUBLE_EQ(compare_occupied(a, 0.65, b, 0.65, 0.19).reference_near_ours, 0.0);
}

}  // namespace
}  // namespace intgrid
