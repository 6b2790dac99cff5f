// The submap SLAM's parts against oracles: growing grids against a flat copy, max-pooled grids
// against brute-force maxima, branch and bound against the exhaustive search, and whole runs on
// a simulated loop against the ground truth and the raw odometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <random>

#include "intgrid/core/ray_insertion.hpp"
#include "intgrid/simulation/simulator.hpp"
#include "intgrid/slam/local_grid.hpp"
#include "intgrid/slam/scan_matching.hpp"
#include "intgrid/slam/submap_slam.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"
#include "simulated_run.hpp"

namespace intgrid::slam {
namespace {

using test::fill_rectangle;
using test::record_run;
using test::SimulatedRun;

template <class Cell>
Cell cell_of(int v) {
  if constexpr (std::is_same_v<Cell, LogOdds>)
    return LogOdds{v * 0.75};
  else
    return static_cast<std::int8_t>(v);
}

// A grid with random cells in [lowest, highest] over [x0, x0 + w) x [y0, y0 + h), each written
// by a reading whose ISM is that one value.
template <class Cell>
LocalGrid<Cell> random_grid(std::mt19937& rng, int x0, int y0, int w, int h, int lowest,
                            int highest) {
  LocalGrid<Cell> grid(50);
  grid.cover(x0, y0, x0 + w - 1, y0 + h - 1);
  std::uniform_int_distribution<int> value(lowest, highest);
  // A table of one reading, one cell: the reading's own cell gets the value.
  const std::vector<std::int32_t> sin = core::make_sine_table_q16();
  const core::IntegerRays rays(sin, 50);
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) {
      const Cell v = cell_of<Cell>(value(rng));
      const core::IsmTable<Cell> table = core::make_ism_table<Cell>(1, {0, 0, 1}, {v});
      const std::int32_t bearing[] = {0}, range[] = {1};
      // A 1 mm reading lays its one value on the first cell of its line of sight: the next one.
      grid.insert(rays, table, std::int64_t{x - 1} * 50, std::int64_t{y} * 50, 0, bearing, range, 2,
                  std::max(-lowest, highest));
    }
  return grid;
}

// The same in [-max, max].
template <class Cell>
LocalGrid<Cell> random_grid(std::mt19937& rng, int x0, int y0, int w, int h, int max) {
  return random_grid<Cell>(rng, x0, y0, w, h, -max, max);
}

template <class Cell>
void growing_grid_keeps_cells() {
  std::mt19937 rng(7);
  LocalGrid<Cell> grid = random_grid<Cell>(rng, -5, 3, 20, 10, 100);
  std::vector<Cell> before;
  for (int y = -10; y < 20; ++y)
    for (int x = -10; x < 20; ++x) before.push_back(grid.at(x, y));
  grid.cover(-300, -200, 150, 400);
  EXPECT_LE(grid.x0(), -300);
  EXPECT_GE(grid.y0() + grid.height(), 401);
  std::size_t i = 0;
  for (int y = -10; y < 20; ++y)
    for (int x = -10; x < 20; ++x)
      EXPECT_EQ(score_value(grid.at(x, y)), score_value(before[i++])) << x << ", " << y;
  EXPECT_EQ(score_value(grid.at(-299, 399)), 0);
}

TEST(LocalGrid, GrowingKeepsEveryCellInInteger) {
  growing_grid_keeps_cells<std::int8_t>();
}
TEST(LocalGrid, GrowingKeepsEveryCellInDouble) {
  growing_grid_keeps_cells<LogOdds>();
}

TEST(LocalGrid, InsertionSaturatesAtTheLargestIndex) {
  LocalGrid<std::int8_t> grid(50);
  const std::vector<std::int32_t> sin = core::make_sine_table_q16();
  const core::IntegerRays rays(sin, 50);
  const core::IsmTable<std::int8_t> table = core::make_ism_table<std::int8_t>(1, {0, 0, 1}, {40});
  const std::int32_t bearing[] = {0}, range[] = {1};
  for (int i = 0; i < 5; ++i) grid.insert(rays, table, 0, 0, 0, bearing, range, 2, 127);
  EXPECT_EQ(grid.at(1, 0), 127);
  EXPECT_EQ(grid.at(0, 0), 0);
  EXPECT_EQ(grid.at(2, 0), 0);
}

// A reading whose ISM reaches far behind its hit (a wide beam): the grid must grow to hold
// every cell the walk lays, in every direction. Oracle: the same walk summed into a map.
TEST(LocalGrid, InsertionHoldsTheWholeIsmBehindTheHit) {
  const std::vector<std::int32_t> sin = core::make_sine_table_q16();
  const core::IntegerRays rays(sin, 50);
  // Every reading below 1 m lays 60 cells of +1: three metres, three times its range.
  const core::IsmTable<std::int8_t> table =
      core::make_ism_table<std::int8_t>(1000, {0, 60, 120}, std::vector<std::int8_t>(120, 1));
  std::vector<std::int32_t> bearing, range;
  for (int b = 0; b < 64; ++b) {
    bearing.push_back(b * 1024 + 300);
    range.push_back(400 + 7 * b);
  }
  for (const std::int64_t sx : {std::int64_t{0}, std::int64_t{-24}, std::int64_t{1337}}) {
    LocalGrid<std::int8_t> grid(50);
    const std::int64_t sy = -sx / 2;
    grid.insert(rays, table, sx, sy, 5000, bearing, range, 1500, 127);
    std::map<std::pair<int, int>, int> expected;
    const int cx = static_cast<int>(core::ray_detail::floor_div<std::int64_t>(sx + 25, 50));
    const int cy = static_cast<int>(core::ray_detail::floor_div<std::int64_t>(sy + 25, 50));
    core::for_each_ism_cell(rays, table, sx - cx * 50, sy - cy * 50, 5000, bearing, range, 1500,
                            [&](int dx, int dy, std::int8_t v) {
                              expected[{cx + dx, cy + dy}] += v;
                            });
    ASSERT_GT(expected.size(), 1000u);
    long held = 0;
    for (const auto& [cell, sum] : expected) {
      EXPECT_EQ(grid.at(cell.first, cell.second), sum) << cell.first << ", " << cell.second;
      held += grid.at(cell.first, cell.second);
    }
    long total = 0;
    for (const std::int8_t v : grid.cells()) total += v;
    EXPECT_EQ(total, held) << "cells written outside the walk";
  }
}

template <class Cell>
void pyramid_holds_block_maxima() {
  std::mt19937 rng(11);
  const LocalGrid<Cell> grid = random_grid<Cell>(rng, -7, 4, 23, 17, 60);
  const MaxPyramid<Cell> pyramid(grid, 4);
  for (int d = 0; d <= 4; ++d)
    for (int y = -30; y < 30; ++y)
      for (int x = -30; x < 30; ++x) {
        Cell best = grid.at(x, y);
        for (int v = 0; v < (1 << d); ++v)
          for (int u = 0; u < (1 << d); ++u) best = std::max(best, grid.at(x + u, y + v));
        if (d == 0)
          ASSERT_EQ(score_value(pyramid.cell(x, y)), score_value(grid.at(x, y)))
              << "cell " << x << ", " << y;
        else  // the whole index at or above the block's maximum, and less than one above it
          ASSERT_EQ(pyramid.bound(d, x, y), std::ceil(score_value(best)))
              << "level " << d << " cell " << x << ", " << y;
      }
}

TEST(MaxPyramid, EachLevelHoldsTheBlockMaximaInInteger) {
  pyramid_holds_block_maxima<std::int8_t>();
}
TEST(MaxPyramid, EachLevelHoldsTheBlockMaximaInDouble) {
  pyramid_holds_block_maxima<LogOdds>();
}

template <class Cell>
void branch_and_bound_finds_the_exhaustive_maximum() {
  std::mt19937 rng(3);
  const std::vector<std::int32_t> sin = core::make_sine_table_q16();
  const core::IntegerRays rays(sin, 50);
  for (int trial = 0; trial < 12; ++trial) {
    const LocalGrid<Cell> grid = random_grid<Cell>(rng, -40, -40, 80, 80, 100);
    ScanPoints points;
    std::uniform_int_distribution<int> coordinate(-1500, 1500);
    for (int p = 0; p < 25; ++p) {
      points.x_mm.push_back(coordinate(rng));
      points.y_mm.push_back(coordinate(rng));
    }
    SearchWindow window;
    window.cells = 3 + trial % 5;
    window.steps = trial % 4;
    window.step_units = 128;
    window.prior_xy_mm = trial % 2 ? 400 : 0;
    window.prior_theta_units = trial % 3 ? 2000 : 0;
    const SlamPose guess{std::int64_t{trial} * 17 - 60, 31 - std::int64_t{trial} * 9, trial * 300};
    const Match<Cell> exhaustive =
        match_exhaustive(grid, rays, points, guess, window, 100, MatchScore<Cell>{-1000000});
    const MaxPyramid<Cell> pyramid(grid, pyramid_levels(window.cells));
    const Match<Cell> bounded = match_branch_and_bound(pyramid, rays, points, guess, window, 100,
                                                       MatchScore<Cell>{-1000000});
    ASSERT_TRUE(exhaustive.found);
    ASSERT_TRUE(bounded.found);
    EXPECT_EQ(bounded.score, exhaustive.score) << "trial " << trial;
    // A threshold above the maximum finds nothing; at the maximum, the maximum.
    EXPECT_FALSE(match_branch_and_bound(pyramid, rays, points, guess, window, 100,
                                        exhaustive.score + MatchScore<Cell>{1})
                     .found);
    const Match<Cell> at =
        match_branch_and_bound(pyramid, rays, points, guess, window, 100, exhaustive.score);
    EXPECT_TRUE(at.found);
    EXPECT_EQ(at.score, exhaustive.score);
  }
}

// The exhaustive search against a sum written out hit by hit: more hits than its 16-bit partial
// sums take at a time (1000 against 256), on cells all at the largest index, all at its
// negative, or random, with windows that leave the grid on every side.
TEST(ExhaustiveSearch, SumsEveryHitOfManyOnSaturatedCellsInInteger) {
  std::mt19937 rng(5);
  const std::vector<std::int32_t> sin = core::make_sine_table_q16();
  const core::IntegerRays rays(sin, 50);
  for (const auto& [lowest, highest] : {std::pair{127, 127}, {-127, -127}, {-127, 127}}) {
    const LocalGrid<std::int8_t> grid =
        random_grid<std::int8_t>(rng, -40, -40, 80, 80, lowest, highest);
    ScanPoints points;
    std::uniform_int_distribution<int> coordinate(-1800, 1800);
    for (int p = 0; p < 1000; ++p) {
      points.x_mm.push_back(coordinate(rng));
      points.y_mm.push_back(coordinate(rng));
    }
    SearchWindow window;
    window.cells = 6;
    window.steps = 2;
    window.step_units = 128;
    const SlamPose guess{-20, 35, 700};
    std::int64_t best = std::numeric_limits<std::int64_t>::min();
    SlamPose best_pose;
    std::vector<int> cx, cy;
    for (int k = -window.steps; k <= window.steps; ++k)
      for (int j = -window.cells; j <= window.cells; ++j)
        for (int i = -window.cells; i <= window.cells; ++i) {
          const SlamPose pose{guess.x_mm + i * 50, guess.y_mm + j * 50,
                              guess.theta + k * window.step_units};
          matching_detail::hit_cells(rays, points, pose.x_mm, pose.y_mm,
                                     static_cast<std::int32_t>(pose.theta), cx, cy);
          std::int64_t sum = 0;
          for (std::size_t p = 0; p < cx.size(); ++p) sum += grid.at(cx[p], cy[p]);
          if (sum > best) {
            best = sum;
            best_pose = pose;
          }
        }
    // Its headings cut into runs on threads (5 headings: runs of 2 and 3, or 1, 2 and 2) keep
    // the first maximum in order, where the saturated grids tie everywhere inside.
    for (const int threads : {1, 2, 3}) {
      const Match<std::int8_t> found =
          match_exhaustive(grid, rays, points, guess, window, 127, std::int64_t{-1000000}, threads);
      EXPECT_EQ(found.evidence, best) << "cells " << lowest << " to " << highest << ", " << threads;
      EXPECT_EQ(found.score, best);
      EXPECT_EQ(found.pose.x_mm, best_pose.x_mm);
      EXPECT_EQ(found.pose.y_mm, best_pose.y_mm);
      EXPECT_EQ(found.pose.theta, best_pose.theta);
    }
  }
}

TEST(BranchAndBound, FindsTheExhaustiveMaximumInInteger) {
  branch_and_bound_finds_the_exhaustive_maximum<std::int8_t>();
}
TEST(BranchAndBound, FindsTheExhaustiveMaximumInDouble) {
  branch_and_bound_finds_the_exhaustive_maximum<LogOdds>();
}

// A scan's pose recovered by matching it against a submap of scans from around it.
template <class Cell>
void match_recovers_the_pose(const core::IsmTable<Cell>& table) {
  simulation::FloorplanConfig floor;
  floor.cell = 0.05;
  const simulation::Floorplan plan = simulation::make_floorplan(floor, 5);
  const simulation::SensorConfig sensor = simulation::lidar_sensor(361, std::numbers::pi, 20.0);
  const std::vector<std::int32_t> sin = core::make_sine_table_q16();
  const core::IntegerRays rays(sin, 50);
  SlamSensor geometry;
  for (std::size_t i = 0; i < 361; ++i)
    geometry.bearing.push_back(static_cast<std::int32_t>(
        std::llround((sensor.angle0 + static_cast<double>(i) * sensor.dangle) /
                     (2 * std::numbers::pi) * 65536)));
  const auto quantized = [&](const core::Pose2& pose, std::uint64_t seed) {
    const core::Scan scan = simulation::simulate_scan(plan.grid, sensor, {}, pose, seed);
    std::vector<std::int32_t> mm;
    for (const double r : scan.ranges)
      mm.push_back(scan.is_valid_range(r) ? static_cast<std::int32_t>(std::llround(r * 1000)) : 0);
    return mm;
  };
  const auto units = [](double a) { return std::llround(a / (2 * std::numbers::pi) * 65536); };
  const simulation::Point2 start = plan.corridor_loop.front();
  LocalGrid<Cell> grid(50);
  for (int k = 0; k < 10; ++k) {
    const core::Pose2 pose{start.x + 0.1 * k, start.y + 0.01 * (k % 3), 0.02 * (k % 2)};
    const std::vector<std::int32_t> mm = quantized(pose, 100 + k);
    grid.insert(rays, table, std::llround(pose.x * 1000), std::llround(pose.y * 1000),
                static_cast<std::int32_t>(units(pose.theta)), geometry.bearing, mm, 20000, 127);
  }
  const core::Pose2 truth{start.x + 0.43, start.y + 0.012, 0.013};
  const ScanPoints points = scan_points(rays, geometry, quantized(truth, 7), 20000);
  SearchWindow window;
  window.cells = 6;
  window.steps = 12;
  window.step_units = 64;
  const SlamPose guess{std::llround(truth.x * 1000) + 90, std::llround(truth.y * 1000) - 70,
                       units(truth.theta) + 400};
  const Match<Cell> lattice =
      match_exhaustive(grid, rays, points, guess, window, 127, MatchScore<Cell>{});
  const Match<Cell> refined = refine_match(grid, rays, points, guess, window, 127, lattice);
  for (const int threads : {2, 3, 5}) {  // its five headings on threads: the same pose
    EXPECT_EQ(
        match_exhaustive(grid, rays, points, guess, window, 127, MatchScore<Cell>{}, threads).pose,
        lattice.pose);
    EXPECT_EQ(refine_match(grid, rays, points, guess, window, 127, lattice, threads).pose,
              refined.pose);
  }
  EXPECT_NEAR(static_cast<double>(refined.pose.x_mm), truth.x * 1000, 15);
  EXPECT_NEAR(static_cast<double>(refined.pose.y_mm), truth.y * 1000, 15);
  EXPECT_NEAR(static_cast<double>(refined.pose.theta), static_cast<double>(units(truth.theta)),
              64);  // one lattice step, 0.35 degree
}

TEST(ScanMatching, RecoversTheTruePoseInInteger) {
  const core::SepsCodec codec = core::SepsCodec::for_levels(8, 0.6, 16);
  match_recovers_the_pose(
      core::make_index_ism_table(core::GaussianBeamModel{0.05, 0.0}, 0.05, codec, 6, 20000, 1));
}

// The corridor loop's scans (simulated_loop): what follows a spin at its start.
constexpr std::size_t kLoopScans = 700;

// The corridor loop of the simulated floor, kLoopScans scans at `beams` beams over half a turn
// with the default odometry noise (about 1 m off after one lap), after spin_turns turns on the
// spot at its start at 2 rad/s (0.4 rad a scan), its odometry's turns scaled by turn_scale
// (record_run).
SimulatedRun simulated_loop(int spin_turns = 0, double turn_scale = 1.0, int beams = 361) {
  simulation::FloorplanConfig floor;
  floor.cell = 0.05;
  const simulation::Floorplan plan = simulation::make_floorplan(floor, 5);
  simulation::TrajectoryConfig route;
  route.scans = kLoopScans;
  const std::vector<core::Pose2> loop = simulation::follow_route(plan.corridor_loop, true, route);
  const double turn_per_scan = 2.0 * 0.2;
  const int spin = static_cast<int>(spin_turns * 2 * std::numbers::pi / turn_per_scan);
  std::vector<core::Pose2> truth;
  for (int i = 0; i < spin; ++i)
    truth.push_back({loop.front().x, loop.front().y,
                     std::remainder(loop.front().theta + turn_per_scan * i, 2 * std::numbers::pi)});
  truth.insert(truth.end(), loop.begin(), loop.end());
  return record_run(plan.grid, truth, 9, simulation::lidar_sensor(beams, std::numbers::pi, 20.0),
                    13, turn_scale);
}

const SimulatedRun& loop_run() {
  static const SimulatedRun run = simulated_loop();
  return run;
}

// The way a run's poses cover against the truth's: their chords over every 20 scans, summed,
// against the truth's over the same scans (a length bias of the front end shows here; closures
// and the graph barely change a trajectory's shape over 20 scans).
double way_against_truth(const std::vector<TimedPose>& poses, const std::vector<TimedPose>& truth) {
  constexpr std::size_t kChord = 20;
  const auto chord = [](const std::vector<TimedPose>& v, std::size_t i) {
    return std::hypot(v[i].pose.x - v[i - kChord].pose.x, v[i].pose.y - v[i - kChord].pose.y);
  };
  double way = 0.0, true_way = 0.0;
  for (std::size_t i = kChord; i < poses.size(); i += kChord) {
    way += chord(poses, i);
    true_way += chord(truth, i);
  }
  return way / true_way;
}

void tracks_the_loop(core::Arithmetic arithmetic) {
  const SimulatedRun& sim = loop_run();
  SubmapSlamStats stats;
  const SlamRun run = run_submap_slam(sim.log, SubmapSlamConfig{}, arithmetic, &stats);
  ASSERT_EQ(run.trajectory.size(), sim.log.scans.size());
  const TrajectoryError slam = absolute_trajectory_error(run.trajectory, sim.truth);
  const TrajectoryError odometry = absolute_trajectory_error(scan_poses(sim.log), sim.truth);
  const double way = way_against_truth(run.trajectory, sim.truth);
  std::printf(
      "simulated loop: ATE %.3f m, odometry %.3f m; way %.4f of the true way (odometry "
      "%.4f)\n",
      slam.rmse, odometry.rmse, way, way_against_truth(scan_poses(sim.log), sim.truth));
  EXPECT_GT(odometry.rmse, 0.5);  // about 1 m: the test means something
  EXPECT_LT(std::abs(way - 1.0), 0.005);
  // Measured 0.057 m (integer) and 0.065 m (double) (docs/results.md); 0.20 m in an earlier
  // revision: the floor is a third of the odometry's. The way: 1.0018 (integer) and 1.0026
  // (double) of the true way, the odometry's 0.9923; with the ISM's sigma at 5 cm 1.0053, at 8
  // cm 1.0055 (a fused wall leans outward by a part of sigma, SubmapSlamConfig::sensor.sigma): the
  // floor, half a per cent either way.
  EXPECT_LT(slam.rmse, 0.3);
  EXPECT_LT(slam.rmse, odometry.rmse / 3);
  EXPECT_GT(stats.loop_closures, 0u);
  EXPECT_GT(stats.nodes, 10u);
  EXPECT_EQ(stats.scans, sim.log.scans.size());
}

TEST(SubmapSlam, TracksASimulatedLoopFarBetterThanOdometryInInteger) {
  tracks_the_loop(core::Arithmetic::integer);
}
TEST(SubmapSlam, TracksASimulatedLoopFarBetterThanOdometryInDouble) {
  tracks_the_loop(core::Arithmetic::floating);
}

// The same loop, but the robot first spins twice on the spot at 2 rad/s (23 degrees between
// scans) before the first submap holds more than a few scans, and its odometry reports every
// turn 10% too large: the start that the benchmark logs' first seconds never show (a log of the
// same benchmark that the defaults were not chosen on carried 9 degree errors in its first
// 50 s). Measured: at most 0.36 degree off during the spin, ATE 0.035 m (integer) and 0.039 m
// (double) against the odometry's 8.4 m (0.042 / 0.043 m without young nodes matched again);
// without the bias 0.080 / 0.107 m (measured before closures took only what their match fixes and
// the ISM's sigma went from 5 to 3 cm).
// The spin of `sim` held to 3 degrees and the run to 0.15 m ATE, where the odometry's ATE exceeds
// min_odometry_rmse (the test means something).
void holds_a_spin(const SimulatedRun& sim, const char* label, double min_odometry_rmse,
                  core::Arithmetic arithmetic) {
  const std::size_t spin = sim.truth.size() - kLoopScans;
  const SlamRun run = run_submap_slam(sim.log, SubmapSlamConfig{}, arithmetic);
  double worst_heading = 0.0;  // during the spin, against the truth: both start at the same pose
  for (std::size_t i = 0; i < spin; ++i)
    worst_heading =
        std::max(worst_heading,
                 std::abs(std::remainder(run.trajectory[i].pose.theta - sim.truth[i].pose.theta,
                                         2 * std::numbers::pi)));
  const TrajectoryError slam = absolute_trajectory_error(run.trajectory, sim.truth);
  const TrajectoryError odometry = absolute_trajectory_error(scan_poses(sim.log), sim.truth);
  std::printf("%s: %.2f degrees off at most during the spin; ATE %.3f m, odometry %.3f m\n", label,
              worst_heading * 180 / std::numbers::pi, slam.rmse, odometry.rmse);
  EXPECT_GT(odometry.rmse, min_odometry_rmse);
  EXPECT_LT(worst_heading * 180 / std::numbers::pi, 3.0);
  EXPECT_LT(slam.rmse, 0.15);
}

const SimulatedRun& spinning_start() {
  static const SimulatedRun run = simulated_loop(2, 1.1);
  return run;
}

TEST(SubmapSlam, HoldsASpinOnTheSpotAtTheStartWithAHeadingBiasInInteger) {
  holds_a_spin(spinning_start(), "spinning start", 3.0, core::Arithmetic::integer);
}
TEST(SubmapSlam, HoldsASpinOnTheSpotAtTheStartWithAHeadingBiasInDouble) {
  holds_a_spin(spinning_start(), "spinning start", 3.0, core::Arithmetic::floating);
}

// The spinning start with unbiased odometry that arrives late: every third scan of the spin's
// second turn (or of the whole spin, from its second scan) carries the odometry pose of the scan
// before it, so that one increment reports no turn and the
// next two scans' worth (ACES at 411.6 s: 4 degrees reported where the scans turned 20, the rest
// a scan later). The narrow window (+-8 degrees) cannot reach a 23-degree slip, the wide one can,
// and there the prediction it contradicts must not veto the scan's pose.
SimulatedRun spin_with_late_odometry(bool from_the_start, int beams = 361) {
  SimulatedRun late = simulated_loop(2, 1.0, beams);
  const std::size_t spin = late.truth.size() - kLoopScans;
  const std::size_t first = from_the_start ? 2 : spin / 2 + 1;
  for (std::size_t i = first; i < spin; i += 3)
    late.log.scans[i].robot = late.log.scans[i - 1].robot;
  return late;
}

// Late in the second turn, once the first has shown the room. Measured: 0.43 degree off at most
// during the spin (integer and double), the odometry's ATE 2.0 m; 22.9 degrees when the wide
// search kept the odometry's prior.
const SimulatedRun& spin_with_late_odometry_in_its_second_turn() {
  static const SimulatedRun run = spin_with_late_odometry(false);
  return run;
}

TEST(SubmapSlam, HoldsASpinWhoseOdometryArrivesLateInInteger) {
  holds_a_spin(spin_with_late_odometry_in_its_second_turn(), "spin, odometry late", 1.0,
               core::Arithmetic::integer);
}
TEST(SubmapSlam, HoldsASpinWhoseOdometryArrivesLateInDouble) {
  holds_a_spin(spin_with_late_odometry_in_its_second_turn(), "spin, odometry late", 1.0,
               core::Arithmetic::floating);
}

// Late from the second scan on, while the first submap holds a few scans: there a slipped scan's
// narrow match still scores above `wide_below`, and the wide search is made because the narrow
// match's best pose lies on the window's edge (submap_tracking.hpp). Measured: 0.39 / 0.85
// degree off at most during the spin (integer / double), ATE 0.032 / 0.022 m; 23.1 / 23.2 degrees
// and ATE 1.27 / 1.34 m before the edge rule.
const SimulatedRun& spin_with_late_odometry_from_the_start() {
  static const SimulatedRun run = spin_with_late_odometry(true);
  return run;
}

TEST(SubmapSlam, HoldsASpinWhoseOdometryArrivesLateFromTheStartInInteger) {
  holds_a_spin(spin_with_late_odometry_from_the_start(), "spin, odometry late from the start", 1.0,
               core::Arithmetic::integer);
}
TEST(SubmapSlam, HoldsASpinWhoseOdometryArrivesLateFromTheStartInDouble) {
  holds_a_spin(spin_with_late_odometry_from_the_start(), "spin, odometry late from the start", 1.0,
               core::Arithmetic::floating);
}

// The spinning starts at 181 beams, a laser of half the resolution (as the benchmark's Intel
// and ACES at 180, and its third log's interlaced scans): measured 0.29 / 0.28 degree off at most
// during the biased spin (integer / double), ATE 0.011 / 0.012 m; 0.66 / 0.66 degree with the
// odometry late in the second turn, ATE 0.012 / 0.013 m. Not held yet, and so not here: the
// odometry late from the spin's second scan (11.4 degrees off at 181 beams, about 15 at 90: there
// the slipped scan's best lies inside the narrow window, at a wrong heading), and at 90 beams late
// in the second turn too (13.7 degrees, integer; docs/results.md).
const SimulatedRun& spinning_start_at_181_beams() {
  static const SimulatedRun run = simulated_loop(2, 1.1, 181);
  return run;
}
const SimulatedRun& spin_with_late_odometry_at_181_beams() {
  static const SimulatedRun run = spin_with_late_odometry(false, 181);
  return run;
}

TEST(SubmapSlam, HoldsTheSpinningStartsAt181BeamsInInteger) {
  holds_a_spin(spinning_start_at_181_beams(), "spinning start, 181 beams", 3.0,
               core::Arithmetic::integer);
  holds_a_spin(spin_with_late_odometry_at_181_beams(), "spin, odometry late, 181 beams", 1.0,
               core::Arithmetic::integer);
}
TEST(SubmapSlam, HoldsTheSpinningStartsAt181BeamsInDouble) {
  holds_a_spin(spinning_start_at_181_beams(), "spinning start, 181 beams", 3.0,
               core::Arithmetic::floating);
  holds_a_spin(spin_with_late_odometry_at_181_beams(), "spin, odometry late, 181 beams", 1.0,
               core::Arithmetic::floating);
}

// A start in a featureless corridor: 34 m long and 2 m wide with straight, plain walls, a room
// with pillars at its east end. The robot starts 11 m from the corridor's blind west end and
// drives east; with 8 m of range, for its first 15 m it sees only the two side walls, which fix
// its heading and its place across the corridor but nothing along it. Then it goes round the
// room and comes back the same way to its start, and sets out again. A matcher that let the
// scans slide along the corridor (to whatever noise scores best), or a first submap laid down
// before anything along the corridor could be seen, would carry that error into the rest; a
// loop closure in the corridor fixes nothing along it, and taken at full weight in every
// direction it pinned the nodes where noise put them (the closures' information follows the
// match's evidence curvature, submap_slam.cpp).
SimulatedRun featureless_corridor_start() {
  core::ProbabilityGrid world(core::GridGeometry{900, 200, 0.05, 0.0, 0.0}, 1.0);
  const auto carve = [&](double x0, double y0, double x1, double y1, double value) {
    fill_rectangle(world, x0, y0, x1, y1, value);
  };
  carve(1, 4, 35, 6, 0.0);   // the corridor
  carve(35, 1, 44, 9, 0.0);  // the room
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{37, 2.5}, {40, 6.5}, {42.5, 3}})
    carve(x, y, x + 0.4, y + 0.4, 1.0);  // its pillars
  simulation::TrajectoryConfig route;
  route.scans = 800;
  const std::vector<core::Pose2> truth = simulation::follow_route(
      {{12, 5}, {36, 5}, {38.5, 4.5}, {41.5, 5}, {38.5, 7.5}, {36, 5}}, true, route);
  return record_run(world, truth, 31, simulation::lidar_sensor(361, std::numbers::pi, 8.0), 37);
}

void holds_a_featureless_corridor_start(core::Arithmetic arithmetic) {
  static const SimulatedRun sim = featureless_corridor_start();
  SubmapSlamStats stats;
  const SlamRun run = run_submap_slam(sim.log, SubmapSlamConfig{}, arithmetic, &stats);
  // Along the corridor (x) and across it (y) while only the side walls are in sight: both start
  // at the same pose.
  const std::vector<TimedPose> odometry_trajectory = scan_poses(sim.log);
  double slam_along = 0, odometry_along = 0, slam_across = 0;
  std::size_t blind = 0;
  while (sim.truth[blind].pose.x < 27.0) {
    const core::Pose2& truth = sim.truth[blind].pose;
    slam_along = std::max(slam_along, std::abs(run.trajectory[blind].pose.x - truth.x));
    slam_across = std::max(slam_across, std::abs(run.trajectory[blind].pose.y - truth.y));
    odometry_along =
        std::max(odometry_along, std::abs(odometry_trajectory[blind].pose.x - truth.x));
    ++blind;
  }
  const TrajectoryError slam = absolute_trajectory_error(run.trajectory, sim.truth);
  const TrajectoryError odometry = absolute_trajectory_error(odometry_trajectory, sim.truth);
  std::printf(
      "featureless corridor start (%zu scans blind along it): at most %.3f m off along it "
      "(odometry %.3f m), %.3f m across; ATE %.3f m (max %.3f m), odometry %.3f m; %zu closures\n",
      blind, slam_along, odometry_along, slam_across, slam.rmse, slam.max, odometry.rmse,
      stats.loop_closures);
  EXPECT_GT(odometry.rmse, 0.3);  // about 0.5 m: the test means something
  EXPECT_LT(slam_along, odometry_along + 0.1);
  EXPECT_LT(slam_across, 0.05);
  // Measured 0.094 m (integer) and 0.079 m (double), at most 0.19 m off; with every closure at
  // full weight in every direction, 0.167 and 0.161 m, up to 0.55 m (docs/results.md; both at
  // the ISM's former sigma of 5 cm).
  EXPECT_LT(slam.rmse, 0.12);
  EXPECT_LT(slam.max, 0.35);
}

TEST(SubmapSlam, HoldsAStartInAFeaturelessCorridorInInteger) {
  holds_a_featureless_corridor_start(core::Arithmetic::integer);
}
TEST(SubmapSlam, HoldsAStartInAFeaturelessCorridorInDouble) {
  holds_a_featureless_corridor_start(core::Arithmetic::floating);
}

// A robot that drives round a cramped room (4 x 3 m) and then out through its door into an open
// hall (20 x 16 m, with pillars), at 90 beams: the scans move on from what the older active
// submap holds (the room) to what only the newer one has begun to hold (the hall), as at ACES's
// 502 s. The newer submap then takes over as the target (SubmapSlamConfig::Submaps::
// handover_scans); while the robot stays in the room the older submap holds all it sees, with
// more scans than the newer one, and none is handed over.
SimulatedRun room_then_hall(bool leave_the_room) {
  core::ProbabilityGrid world(core::GridGeometry{540, 360, 0.05, 0.0, 0.0}, 1.0);
  fill_rectangle(world, 1, 1, 5, 4, 0.0);        // the room
  fill_rectangle(world, 4.9, 2, 6.1, 3, 0.0);    // its door
  fill_rectangle(world, 6, 0.5, 26, 16.5, 0.0);  // the hall
  for (const auto& [x, y] :
       std::vector<std::pair<double, double>>{{10, 5}, {15, 12}, {20, 4}, {23, 13}, {12, 14}})
    fill_rectangle(world, x, y, x + 0.5, y + 0.5, 1.0);  // its pillars
  simulation::TrajectoryConfig route;
  route.scans = 900;
  std::vector<core::Pose2> truth =
      simulation::follow_route({{2, 2}, {4, 2}, {4, 3}, {2, 3}}, true, route);
  truth.resize(500);  // about 12 rounds of the room, about 450 nodes
  if (leave_the_room) {
    route.scans = 500;
    const std::vector<core::Pose2> out = simulation::follow_route(
        {{2, 2}, {4, 2.5}, {8, 2.5}, {13, 8}, {21, 9}, {17, 14}, {8, 10}}, false, route);
    truth.insert(truth.end(), out.begin(), out.end());
  }
  return record_run(world, truth, 41, simulation::lidar_sensor(90, std::numbers::pi, 20.0), 43);
}

void hands_over_when_the_scans_move_on(core::Arithmetic arithmetic) {
  const SimulatedRun stay = room_then_hall(false), leave = room_then_hall(true);
  SubmapSlamStats stayed, left;
  const SlamRun stay_run = run_submap_slam(stay.log, SubmapSlamConfig{}, arithmetic, &stayed);
  const SlamRun leave_run = run_submap_slam(leave.log, SubmapSlamConfig{}, arithmetic, &left);
  SubmapSlamConfig never;
  never.submaps.handover_scans = 0;
  SubmapSlamStats kept;
  const SlamRun never_run = run_submap_slam(leave.log, never, arithmetic, &kept);
  const TrajectoryError stay_error = absolute_trajectory_error(stay_run.trajectory, stay.truth);
  const TrajectoryError leave_error = absolute_trajectory_error(leave_run.trajectory, leave.truth);
  const TrajectoryError never_error = absolute_trajectory_error(never_run.trajectory, leave.truth);
  std::printf(
      "room then hall: staying %zu handovers (%zu nodes, ATE %.3f m); leaving %zu handovers "
      "(%zu nodes, ATE %.3f m), never handing over ATE %.3f m\n",
      stayed.handovers, stayed.nodes, stay_error.rmse, left.handovers, left.nodes, leave_error.rmse,
      never_error.rmse);
  EXPECT_EQ(stayed.handovers, 0u);
  EXPECT_GT(left.handovers, 0u);
  EXPECT_EQ(kept.handovers, 0u);
  EXPECT_GT(stayed.nodes, 4u * static_cast<std::size_t>(SubmapSlamConfig{}.submaps.scans));
}

TEST(SubmapSlam, HandsOverToTheNewerSubmapWhenTheScansMoveOnInInteger) {
  hands_over_when_the_scans_move_on(core::Arithmetic::integer);
}
TEST(SubmapSlam, HandsOverToTheNewerSubmapWhenTheScansMoveOnInDouble) {
  hands_over_when_the_scans_move_on(core::Arithmetic::floating);
}

// The loop as an interlaced laser records it: successive scans take every other beam, the even
// ones (181) and the odd ones (180, half a step further on), and the odd scans list their beams
// from the last bearing backwards. Each scan states its geometry; an engine that read the odd
// scans with the even ones' would see them mirrored.
void tracks_an_interlaced_loop(core::Arithmetic arithmetic) {
  const SimulatedRun& sim = loop_run();
  core::Log log = sim.log;
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    core::Scan& s = log.scans[i];
    const std::vector<double> all = s.ranges;
    s.ranges.clear();
    if (i % 2 == 0) {
      for (std::size_t b = 0; b < all.size(); b += 2) s.ranges.push_back(all[b]);
      s.dangle *= 2;
    } else {
      for (std::size_t b = all.size() - 2;; b -= 2) {
        s.ranges.push_back(all[b]);
        if (b < 2) break;
      }
      s.angle0 += static_cast<double>(all.size() - 2) * s.dangle;
      s.dangle *= -2;
    }
  }
  ASSERT_EQ(log.scans[0].ranges.size(), 181u);
  ASSERT_EQ(log.scans[1].ranges.size(), 180u);
  SubmapSlamStats stats;
  const SlamRun run = run_submap_slam(log, SubmapSlamConfig{}, arithmetic, &stats);
  const TrajectoryError slam = absolute_trajectory_error(run.trajectory, sim.truth);
  const TrajectoryError odometry = absolute_trajectory_error(scan_poses(log), sim.truth);
  std::printf("interlaced loop: ATE %.3f m, odometry %.3f m\n", slam.rmse, odometry.rmse);
  // The bounds of the 361-beam loop above.
  EXPECT_LT(slam.rmse, 0.3);
  EXPECT_LT(slam.rmse, odometry.rmse / 3);
  EXPECT_GT(stats.loop_closures, 0u);
}

TEST(SubmapSlam, TakesEachScansOwnGeometryInInteger) {
  tracks_an_interlaced_loop(core::Arithmetic::integer);
}
TEST(SubmapSlam, TakesEachScansOwnGeometryInDouble) {
  tracks_an_interlaced_loop(core::Arithmetic::floating);
}

TEST(SubmapSlam, RunsAreBitIdentical) {
  core::Log log = loop_run().log;
  log.scans.resize(150);
  const SlamRun a = run_submap_slam(log, SubmapSlamConfig{}, core::Arithmetic::integer);
  const SlamRun b = run_submap_slam(log, SubmapSlamConfig{}, core::Arithmetic::integer);
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t i = 0; i < a.trajectory.size(); ++i)
    EXPECT_EQ(a.trajectory[i].pose, b.trajectory[i].pose) << i;
  EXPECT_EQ(a.map.cells, b.map.cells);
}

// The back end's searches on several threads (loop closures, a finished submap's nodes matched
// again): the whole simulated loop, closures included, the same to the bit for 1, 2 and 3
// threads (the double arithmetic runs the same code on its own cells).
TEST(SubmapSlam, TheSameForAnyThreadCount) {
  const core::Log& log = loop_run().log;
  {
    const core::Arithmetic arithmetic = core::Arithmetic::integer;
    SubmapSlamConfig config;
    SubmapSlamStats one_stats;
    const SlamRun one = run_submap_slam(log, config, arithmetic, &one_stats);
    ASSERT_GT(one_stats.loop_closures, 0u);  // the searches ran and found closures
    for (const int threads : {2, 3}) {
      config.threads = threads;
      SubmapSlamStats stats;
      const SlamRun run = run_submap_slam(log, config, arithmetic, &stats);
      ASSERT_EQ(run.trajectory.size(), one.trajectory.size());
      for (std::size_t i = 0; i < run.trajectory.size(); ++i)
        ASSERT_EQ(run.trajectory[i].pose, one.trajectory[i].pose) << threads << " threads, " << i;
      EXPECT_EQ(run.map.cells, one.map.cells) << threads;
      EXPECT_EQ(stats.loop_closures, one_stats.loop_closures) << threads;
      EXPECT_EQ(stats.rejected_closures, one_stats.rejected_closures) << threads;
    }
  }
}

// The online API needs no map size: a robot that drives 200 m straight down a long corridor.
TEST(SubmapSlam, MapGrowsAsTheRobotDrivesAway) {
  core::Log log;
  for (int i = 0; i < 400; ++i) {
    core::Scan s;
    s.t = i * 0.2;
    s.robot = {0.5 * i, 0.0, 0.0};
    s.angle0 = -std::numbers::pi / 2;
    s.dangle = std::numbers::pi / 180;
    s.max_range = 40.0;
    // Walls 2 m either side, posts every 5 m on the left one.
    for (int b = 0; b <= 180; ++b) {
      const double a = s.angle0 + b * s.dangle;
      const double side = std::abs(std::sin(a)) > 1e-6 ? 2.0 / std::abs(std::sin(a)) : 0.0;
      s.ranges.push_back(side > 0.0 && side < 30.0 ? side : 0.0);
    }
    log.scans.push_back(std::move(s));
  }
  SubmapSlamStats stats;
  const SlamRun run = run_submap_slam(log, SubmapSlamConfig{}, core::Arithmetic::integer, &stats);
  EXPECT_GT(run.map.geometry.width * run.map.geometry.resolution, 200.0);
  EXPECT_GT(stats.submaps, 3u);
}

TEST(SubmapSlam, ConfigCheckNamesTheField) {
  SubmapSlamConfig c;
  c.loops.window = -1;
  try {
    check_submap_slam_config(c);
    FAIL() << "accepted a negative window";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("loops.window"), std::string::npos) << e.what();
  }
  c = {};
  c.cell = 0.0125;
  EXPECT_THROW(check_submap_slam_config(c), std::invalid_argument);  // not whole millimetres
  c = {};
  c.headings = 1000;
  EXPECT_THROW(check_submap_slam_config(c), std::invalid_argument);
  for (const int threads : {-1, 257}) {
    c = {};
    c.threads = threads;
    try {
      check_submap_slam_config(c);
      FAIL() << "accepted " << threads << " threads";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("threads"), std::string::npos) << e.what();
    }
  }
}

// Two look-alike corridors: A (y 1 to 3 m) and B (y 5 to 7 m), 30 m long, the same niches at the
// same x in both, joined at both ends; the robot drives A east, B west and A again. Seen from
// inside, B is A moved 4 m north: a scan in B matches A's submaps 4 m off, inside the loop
// search's window.
SimulatedRun look_alike_corridors(std::size_t scans) {
  core::ProbabilityGrid world(core::GridGeometry{680, 200, 0.05, 0.0, 0.0}, 1.0);
  const auto carve = [&](double x0, double y0, double x1, double y1) {
    fill_rectangle(world, x0, y0, x1, y1, 0.0);
  };
  carve(1, 1, 31, 3);   // A
  carve(1, 5, 31, 7);   // B
  carve(1, 1, 3, 7);    // the west connector
  carve(29, 1, 31, 7);  // the east connector
  for (double x = 6; x < 28; x += 5.5) {
    for (const double y : {0.5, 4.5}) carve(x, y, x + 0.6, y + 0.6);        // niches below A and B
    for (const double y : {2.9, 6.9}) carve(x + 2.0, y, x + 2.4, y + 0.5);  // and above
  }
  simulation::TrajectoryConfig route;
  route.scans = scans;
  const std::vector<core::Pose2> truth =
      simulation::follow_route({{2, 2}, {30, 2}, {30, 6}, {2, 6}}, true, route);
  return record_run(world, truth, 21, simulation::lidar_sensor(361, std::numbers::pi, 8.0), 23);
}

// A scan in B matches a submap of A 4 m off, and the loop search's window (+-5 m) reaches it.
// The closure is rejected as moving the node further than the front end can have drifted since
// the trajectory last met that submap; the true closures (A with A, B with B, and A again at
// the end of the lap) pass. Without the check (drift 1 m a metre, every match within the
// window kept) the run ends up to 1 m off; with none at all (before the check), up to 4 m: B
// laid onto A.
void rejects_the_look_alike_corridor(core::Arithmetic arithmetic) {
  static const SimulatedRun sim = look_alike_corridors(900);
  SubmapSlamStats stats;
  const SlamRun run = run_submap_slam(sim.log, SubmapSlamConfig{}, arithmetic, &stats);
  const TrajectoryError slam = absolute_trajectory_error(run.trajectory, sim.truth);
  const TrajectoryError odometry = absolute_trajectory_error(scan_poses(sim.log), sim.truth);
  std::printf(
      "look-alike corridors: ATE %.3f m (max %.3f m), odometry %.3f m; %zu closures, "
      "%zu rejected, of %zu searches; %zu switched off\n",
      slam.rmse, slam.max, odometry.rmse, stats.loop_closures, stats.rejected_closures,
      stats.loop_searches, stats.switched_off_closures);
  EXPECT_GT(odometry.rmse, 1.0);
  EXPECT_GT(stats.rejected_closures, 0u);
  EXPECT_GT(stats.loop_closures, 0u);
  EXPECT_LT(slam.rmse, 0.15);
  EXPECT_LT(slam.max, 0.5);
}

TEST(SubmapSlam, RejectsALookAlikeCorridorAndKeepsTheTrueClosuresInInteger) {
  rejects_the_look_alike_corridor(core::Arithmetic::integer);
}
TEST(SubmapSlam, RejectsALookAlikeCorridorAndKeepsTheTrueClosuresInDouble) {
  rejects_the_look_alike_corridor(core::Arithmetic::floating);
}

}  // namespace
}  // namespace intgrid::slam
