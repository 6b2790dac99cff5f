// The grid SLAM's mapping: the first scan's cells against its analytic hits, a spread pose
// grid's map against the mixture of single-pose maps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "intgrid/core/scan_insertion.hpp"
#include "intgrid/core/sensor_model.hpp"
#include "intgrid/slam/grid_slam.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"
#include "intgrid/slam/log_run.hpp"
#include "intgrid/slam/probabilities.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

using namespace intgrid::core;

#include "grid_slam_world.hpp"

namespace intgrid {
namespace {

using namespace intgrid::grid_slam_test;

// ---------------------------------------------------------------------------------------------
// 2. Mapping geometry: the first scan is mapped from the single pose at the origin.

// The map cell holding the SLAM-frame point (x, y).
int cell_of(double v, double cell) {
  return static_cast<int>(std::floor(v / cell + 0.5));
}

template <class Pr>
Grid<std::int8_t> first_scan_map(const SlamSetup& setup, const QuantizedScan& scan) {
  GridSlamEngine<Pr> slam(setup, make_probabilities<Pr>(setup));
  slam.process(scan);
  EXPECT_EQ(slam.mappings(), 1u);
  EXPECT_EQ(slam.localizations(), 0u);
  EXPECT_EQ(slam.estimate().x_um, 0);
  EXPECT_EQ(slam.estimate().y_um, 0);
  EXPECT_EQ(slam.estimate().theta_q8, 0);
  EXPECT_EQ(slam.estimate().sigma_um, 0);
  return slam.map();
}

TEST(SlamMapping, FirstScanMarksTheHitsAndClearsTheLineOfSight) {
  const World world = room_with_pillar();
  // The robot's world pose; the SLAM frame is this pose, so the room appears rotated in it.
  const Pose2 robot{0.3, -0.4, 0.5};
  GridSlamConfig config = small_config();
  config.schedule.lambda = 1000;
  config.sensor.max_range = 3.2;  // some walls are farther: those readings are dropped
  Log log;
  log.scans.push_back(make_scan(world, robot, robot, 0.0, 90));
  const Scan& scan = log.scans[0];
  const SlamSetup setup = make_slam_setup(config, scan, 0.0);
  const std::vector<QuantizedScan> q = quantize(log, config);
  const Grid<std::int8_t> map = first_scan_map<DoubleProbabilities>(setup, q[0]);
  // The map does not depend on the arithmetic of Pi while Pi is one pose.
  EXPECT_EQ(map.cells, first_scan_map<IndexProbabilities>(setup, q[0]).cells);

  const double c = config.cell;
  const Pose2 sensor = kMount;  // in the SLAM frame
  const auto to_world = [&](double x, double y) { return compose(robot, {x, y, 0.0}); };
  // Hits of the usable readings, as SLAM-frame cells.
  std::vector<std::pair<int, int>> hits;
  std::size_t dropped = 0;
  const auto usable = [&](std::size_t i) { return q[0].range_mm[i] > 0; };
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double z = scan.ranges[i];
    if (!usable(i)) {
      ASSERT_GE(z, config.sensor.max_range - 0.001) << i;
      ++dropped;
      continue;
    }
    const double a = sensor.theta + scan.bearing(i);
    hits.emplace_back(cell_of(sensor.x + z * std::cos(a), c),
                      cell_of(sensor.y + z * std::sin(a), c));
  }
  ASSERT_GT(dropped, 5u);
  ASSERT_GT(hits.size(), 30u);

  // (a) every positive cell is within one cell of a hit; (b) every touched cell is inside the
  // room (plus two cells) and within max_range (plus two cells) of the sensor.
  int positive = 0, negative = 0, worst_hit_distance = 0;
  double farthest = 0.0;
  const GridGeometry& g = map.geometry;
  for (int iy = 0; iy < g.height; ++iy)
    for (int ix = 0; ix < g.width; ++ix) {
      const int n = map.at(ix, iy);
      if (n == 0) continue;
      const int cx = ix - setup.origin_cell_x, cy = iy - setup.origin_cell_y;
      const Pose2 w = to_world(cx * c, cy * c);
      ASSERT_TRUE(world.inside_room(w.x, w.y, 2 * c)) << cx << "," << cy;
      const double r = std::hypot(cx * c - sensor.x, cy * c - sensor.y);
      farthest = std::max(farthest, r);
      ASSERT_LE(r, config.sensor.max_range + 2 * c) << cx << "," << cy;
      if (n > 0) {
        ++positive;
        int nearest = 1 << 30;
        for (const auto& [hx, hy] : hits)
          nearest = std::min(nearest, std::max(std::abs(hx - cx), std::abs(hy - cy)));
        worst_hit_distance = std::max(worst_hit_distance, nearest);
        EXPECT_LE(nearest, 1) << "positive cell " << cx << "," << cy << " far from every hit";
      } else {
        ++negative;
      }
    }
  // (c) every hit has a positive cell within one cell.
  for (const auto& [hx, hy] : hits) {
    bool found = false;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        found = found || map.at(hx + dx + setup.origin_cell_x, hy + dy + setup.origin_cell_y) > 0;
    EXPECT_TRUE(found) << "no occupied cell at the hit " << hx << "," << hy;
  }
  // (d) the line of sight, from 1.5 cells to 2 cells before the hit, is empty, away from the
  // walls (a grazing beam's last cells lie beside the wall, which other beams hit).
  std::size_t sampled = 0;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (!usable(i)) continue;
    const double z = scan.ranges[i];
    const double a = sensor.theta + scan.bearing(i);
    for (double t = 1.5 * c; t < z - 2.0 * c; t += 0.25 * c) {
      const double x = sensor.x + t * std::cos(a), y = sensor.y + t * std::sin(a);
      // Not within 2 mm of a cell boundary: the integer ray may pass on either side.
      const double fx = x / c + 0.5 - std::floor(x / c + 0.5);
      const double fy = y / c + 0.5 - std::floor(y / c + 0.5);
      if (std::min({fx, 1.0 - fx, fy, 1.0 - fy}) * c < 0.002) continue;
      const int cx = cell_of(x, c), cy = cell_of(y, c);
      const Pose2 w = to_world(cx * c, cy * c);
      if (world.clearance(w.x, w.y) < 1.5 * c) continue;
      ++sampled;
      ASSERT_LT(map.at(cx + setup.origin_cell_x, cy + setup.origin_cell_y), 0)
          << "beam " << i << " at " << t << " m";
    }
  }
  EXPECT_GT(sampled, 500u);
  std::printf(
      "[slam] first scan: %d occupied, %d empty cells; worst occupied-to-hit distance %d "
      "cell(s); farthest touched cell %.3f m (max range %.1f m); %zu line-of-sight samples\n",
      positive, negative, worst_hit_distance, farthest, config.sensor.max_range, sampled);
}

// The mapping event with a spread Pi: P(o_c) = sum_x w_x P_x(o_c) + (1 - W_c) / 2 over the poses
// x above the cut-off (weights renormalized), P_x the ISM of the scan seen from x, W_c the
// weight of the poses whose ISM reaches c. The oracle maps the same scan from each pose alone
// (a GridSlamEngine driven there by exact odometry, without motion noise) and mixes the indices
// here.
struct MixtureError {
  std::size_t poses = 0, cells = 0, exact = 0, more_confident = 0;
  int worst = 0;
  double mean = 0.0;  // mean |difference| in S_eps steps
};

template <class Pr>
MixtureError mixture_map_error(int ugamma_steps_per_halving) {
  const World world = room_with_pillar();
  GridSlamConfig config = small_config();
  config.ugamma.steps_per_halving = ugamma_steps_per_halving;
  config.motion.xy0 = 0.05;  // half a cell: Pi spreads over the neighbouring cells
  config.motion.theta0 = 0.004;
  Log log;
  log.scans.push_back(make_scan(world, {}, {}, 0.0, 90));
  log.scans.push_back(make_scan(world, {}, {}, 0.1, 90));
  std::vector<QuantizedScan> scans = quantize(log, config);
  std::fill(scans[0].range_mm.begin(), scans[0].range_mm.end(), 0);  // no mapping at scan 0
  const SlamSetup setup = make_slam_setup(config, log.scans[0], 1.0);
  GridSlamEngine<Pr> mixed(setup, make_probabilities<Pr>(setup));
  mixed.process(scans[0]);
  mixed.process(scans[1]);  // motion update (spreads Pi), then mapping with that Pi
  EXPECT_EQ(mixed.mappings(), 1u);
  EXPECT_EQ(mixed.localizations(), 0u);
  MixtureError r;

  // The poses above the cut-off and their weights, in double.
  const Pr& pr = mixed.probabilities();
  struct Weighted {
    SlamPose pose;
    double w;
  };
  std::vector<Weighted> poses;
  double total = 0.0;
  for (std::size_t q = 0; q < mixed.pose_grid().size(); ++q) {
    const auto p = mixed.pose_grid()[q];
    if (pr.below_cutoff(p)) continue;
    double w = 0.0;
    if constexpr (std::is_same_v<Pr, IndexProbabilities>)
      w = pr.u.to_probability(p);
    else
      w = p;
    poses.push_back({mixed.pose_of(q), w});
    total += w;
  }
  r.poses = poses.size();
  if (poses.size() < 9) return r;  // not a real mixture: the caller fails

  // Each pose's own ISM image: one pose reached by exact odometry, mapped alone.
  GridSlamConfig exact = config;
  exact.motion.xy0 = exact.motion.xy_per_m = exact.motion.xy_per_rad = 0.0;
  exact.motion.theta0 = exact.motion.theta_per_m = exact.motion.theta_per_rad = 0.0;
  const SlamSetup exact_setup = make_slam_setup(exact, log.scans[0], 1.0);
  const std::size_t cells = mixed.map().cells.size();
  std::vector<double> occ(cells, 0.0), emp(cells, 0.0), weight(cells, 0.0);
  for (const Weighted& x : poses) {
    GridSlamEngine<DoubleProbabilities> alone(exact_setup,
                                              make_probabilities<DoubleProbabilities>(exact_setup));
    QuantizedScan there = scans[1];
    there.odom_dx_mm = static_cast<std::int32_t>(x.pose.x_mm);
    there.odom_dy_mm = static_cast<std::int32_t>(x.pose.y_mm);
    there.odom_dtheta = static_cast<std::int32_t>(x.pose.theta);
    alone.process(scans[0]);
    alone.process(there);
    const std::size_t at = mode_of(alone);
    EXPECT_EQ(alone.pose_of(at).x_mm, x.pose.x_mm);
    EXPECT_EQ(alone.pose_of(at).y_mm, x.pose.y_mm);
    EXPECT_EQ(alone.pose_of(at).theta, x.pose.theta);
    EXPECT_EQ(alone.pose_grid()[at], 1.0);  // alone indeed
    const double w = x.w / total;
    for (std::size_t c = 0; c < cells; ++c) {
      const int k = alone.map().cells[c];
      if (k == 0) continue;
      occ[c] += w * setup.codec.probability(k);
      emp[c] += w * setup.codec.probability(-k);
      weight[c] += w;
    }
  }
  double total_error = 0.0;
  for (std::size_t c = 0; c < cells; ++c) {
    const int got = mixed.map().cells[c];
    if (weight[c] == 0.0) {
      EXPECT_EQ(got, 0) << "cell " << c << " reached by no pose";
      continue;
    }
    const double rest = 0.5 * (1.0 - weight[c]);
    const int expected =
        setup.codec.quantize_conservative((occ[c] + rest) / (occ[c] + emp[c] + 2.0 * rest));
    ++r.cells;
    r.exact += got == expected;
    r.more_confident += std::abs(got) > std::abs(expected) && (got > 0) == (expected > 0);
    r.worst = std::max(r.worst, std::abs(got - expected));
    total_error += std::abs(got - expected);
  }
  r.mean = r.cells > 0 ? total_error / static_cast<double>(r.cells) : 0.0;
  return r;
}

template <class Pr>
void expect_mixture_map(const char* name, int ugamma_steps_per_halving, int worst, double mean,
                        double exact) {
  const MixtureError r = mixture_map_error<Pr>(ugamma_steps_per_halving);
  std::printf(
      "[slam] mixture map, %s (U_gamma %d steps a halving): %zu poses; %zu cells, %zu exactly "
      "as the oracle, %zu more confident; worst difference %d, mean %.3f S_eps steps\n",
      name, ugamma_steps_per_halving, r.poses, r.cells, r.exact, r.more_confident, r.worst, r.mean);
  ASSERT_GE(r.poses, 9u) << name;  // a real mixture
  EXPECT_GT(r.cells, 1000u);
  EXPECT_LE(r.worst, worst) << name;
  EXPECT_LE(r.mean, mean) << name;
  EXPECT_GE(static_cast<double>(r.exact), exact * static_cast<double>(r.cells)) << name;
}

// Double: the same sums in another order; only a sum landing on a quantization boundary could
// round the other way (measured: none of 3862 cells).
TEST(SlamMapping, MixtureOfPosesIsTheWeightedSumOfTheirIsmsInDouble) {
  expect_mixture_map<DoubleProbabilities>("double", 16, 1, 0.01, 0.99);
}

// U_gamma: one S_eps step (lambda = 0.107 nats here) is only 2.5 steps of the default U_gamma
// (ln 2 / 16 = 0.043 nats), and each probability, weight and addition of the ~15-term sums
// rounds by half a step, so the mixed index is off by one step for about 40% of the cells, by
// two for about 1% (measured: worst 2, mean 0.43). With 128 steps a halving (one S_eps step =
// 20 U_gamma steps) the same code must come within one step and mostly exact: what is left is
// rounding, not a wrong formula.
TEST(SlamMapping, MixtureOfPosesIsTheWeightedSumOfTheirIsmsInInteger) {
  expect_mixture_map<IndexProbabilities>("integer", 16, 3, 0.6, 0.5);
  expect_mixture_map<IndexProbabilities>("integer", 128, 1, 0.1, 0.9);
}

TEST(SlamMapping, ScanWithoutUsableReadingsTouchesNothing) {
  const World world;
  GridSlamConfig config = small_config();
  config.sensor.max_range = 1.0;  // every wall is farther
  Log log;
  log.scans.push_back(make_scan(world, {}, {}, 0.0, 36));
  const SlamSetup setup = make_slam_setup(config, log.scans[0], 0.0);
  GridSlamEngine<IndexProbabilities> slam(setup, make_probabilities<IndexProbabilities>(setup));
  slam.process(quantize(log, config)[0]);
  EXPECT_EQ(slam.skipped_scans(), 1u);
  EXPECT_EQ(slam.mappings(), 0u);
  EXPECT_TRUE(std::all_of(slam.map().cells.begin(), slam.map().cells.end(),
                          [](std::int8_t n) { return n == 0; }));
}

TEST(SlamMapping, ProcessRejectsAScanOfAnotherBeamCount) {
  const World world;
  const GridSlamConfig config = small_config();
  const SlamSetup setup = make_slam_setup(config, make_scan(world, {}, {}, 0.0, 36), 0.0);
  GridSlamEngine<DoubleProbabilities> slam(setup, make_probabilities<DoubleProbabilities>(setup));
  QuantizedScan scan;
  scan.range_mm.assign(35, 1000);
  EXPECT_THROW(slam.process(scan), std::invalid_argument);
}

}  // namespace
}  // namespace intgrid
