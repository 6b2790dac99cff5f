// The refinement on the map's own cells and localization from a sequence (docs/algorithms.md 7):
// the fine map's clearance and first hits against brute force, refined poses against the truth,
// the fused grid against a per-cell composition of poses, and a corridor that one scan cannot
// place and a short drive can, fused as a log's scans come (SequenceLocalizer).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "intgrid/localization/global_localization.hpp"
#include "intgrid/localization/sequence_localizer.hpp"
#include "intgrid/simulation/simulator.hpp"

using namespace intgrid::core;
using namespace intgrid::localization;
using namespace intgrid::simulation;

namespace intgrid {
namespace {

constexpr double kPi = std::numbers::pi;

ProbabilityGrid random_map(int width, int height, double res, double p_occupied,
                           SimRandom& random) {
  ProbabilityGrid g(GridGeometry{width, height, res, 0.4, -1.3}, 0.0);
  for (double& p : g.cells) {
    const double u = random.uniform();
    p = u < p_occupied ? 1.0 : u < p_occupied + 0.05 ? 0.5 : 0.0;
  }
  return g;
}

TEST(FineMap, ClearanceIsTheChebyshevDistanceToTheNearestOccupiedCell) {
  SimRandom random(11);
  for (const double p : {0.002, 0.02, 0.2}) {
    const ProbabilityGrid map = random_map(53, 41, 0.05, p, random);
    const FineMap fine(map, 0.65, 0.196, 64);
    for (int y = 0; y < 41; ++y)
      for (int x = 0; x < 53; ++x) {
        int nearest = FineMap::kMaxClearance;
        for (int v = 0; v < 41; ++v)
          for (int u = 0; u < 53; ++u)
            if (map.at(u, v) >= 0.65)
              nearest = std::min(nearest, std::max(std::abs(u - x), std::abs(v - y)));
        ASSERT_EQ(fine.clearance(x, y), nearest) << x << ' ' << y << " p " << p;
      }
  }
}

// The first occupied cell along a ray, walked one column (row) at a time in double precision:
// the cell holding the ray at each column's centre, from the first centre ahead of the point.
double walked_first_hit(const ProbabilityGrid& map, double x, double y, double angle,
                        double limit) {
  const GridGeometry& g = map.geometry;
  const double c = std::cos(angle), s = std::sin(angle);
  const bool x_major = std::abs(c) >= std::abs(s);
  const double major = x_major ? c : s, minor = x_major ? s : c;
  const double a0 = (x_major ? x - g.origin_x : y - g.origin_y) / g.resolution;
  const double b0 = (x_major ? y - g.origin_y : x - g.origin_x) / g.resolution;
  const int sign = major > 0 ? 1 : -1;
  const int major_len = x_major ? g.width : g.height, minor_len = x_major ? g.height : g.width;
  int u = static_cast<int>(std::floor(a0));
  if ((u + 0.5 - a0) * sign <= 0) u += sign;
  for (; u >= 0 && u < major_len; u += sign) {
    const double along = (u + 0.5 - a0) * sign;
    const double distance = along / std::abs(major);
    if (distance > limit) return -1.0;
    const int v = static_cast<int>(std::floor(b0 + along * sign * minor / major));
    if (v < 0 || v >= minor_len) return -1.0;
    if ((x_major ? map.at(u, v) : map.at(v, u)) >= 0.65) return distance;
  }
  return -1.0;
}

TEST(FineMap, FirstHitsMatchAColumnByColumnWalk) {
  SimRandom random(12);
  std::size_t rays = 0, hits = 0, equal = 0;
  for (const double p : {0.005, 0.05}) {
    const ProbabilityGrid map = random_map(120, 90, 0.05, p, random);
    const FineMap fine(map, 0.65, 0.196, 1024);
    const double scale = std::ldexp(1.0, FineMap::kDistanceBits);
    for (int n = 0; n < 4000; ++n) {
      const Pose2 pose{0.4 + random.uniform(0.0, 6.0), -1.3 + random.uniform(0.0, 4.5), 0.0};
      const FinePose at = fine.fine_pose(pose);
      const int d = static_cast<int>(random.below(1024));
      const double limit = random.uniform(0.5, 200.0);  // cells
      const std::int64_t hit =
          fine.first_hit(at.x, at.y, d, static_cast<std::int64_t>(limit * scale));
      const Pose2 exact = fine.pose_of({at.x, at.y, 0});  // the fixed-point position
      const double walked = walked_first_hit(map, exact.x, exact.y, d * fine.heading_bin(), limit);
      ++rays;
      if (walked >= 0) ++hits;
      // The fixed-point slope may put a ray on the other side of a cell corner than double does,
      // very rarely; otherwise the distance is the walk's to within the fixed point's steps (the
      // distance truncated, the secant rounded).
      if ((hit == FineMap::kNoHit) == (walked < 0) &&
          (walked < 0 || std::abs(double(hit) / scale - walked) <= 2.0 / scale))
        ++equal;
    }
  }
  std::printf("[fine map] %zu rays, %zu hits, %zu equal to the walk\n", rays, hits, equal);
  EXPECT_GT(hits, rays / 4);
  EXPECT_GE(double(equal), 0.999 * double(rays));
}

// near_occupied against the endpoint computed in double: its cell's 3 x 3 neighbourhood holds an
// occupied cell. Fixed point may put an endpoint within a hair of a cell border in the next cell.
TEST(FineMap, NearOccupiedIsTheEndpointCellsNeighbourhood) {
  SimRandom random(13);
  const ProbabilityGrid map = random_map(120, 90, 0.05, 0.01, random);
  const FineMap fine(map, 0.65, 0.196, 1024);
  const double scale = std::ldexp(1.0, FineMap::kDistanceBits);
  std::size_t near = 0, equal = 0;
  constexpr int kPoints = 20000;
  for (int n = 0; n < kPoints; ++n) {
    const FinePose at =
        fine.fine_pose({0.4 + random.uniform(0.0, 6.0), -1.3 + random.uniform(0.0, 4.5), 0.0});
    const Pose2 exact = fine.pose_of({at.x, at.y, 0});
    const int d = static_cast<int>(random.below(1024));
    const double cells = random.uniform(0.0, 100.0);
    const double angle = d * fine.heading_bin(), r = cells * map.geometry.resolution;
    const int ix = static_cast<int>(std::floor((exact.x + r * std::cos(angle) - 0.4) / 0.05));
    const int iy = static_cast<int>(std::floor((exact.y + r * std::sin(angle) + 1.3) / 0.05));
    bool expected = false;
    if (ix >= 0 && iy >= 0 && ix < 120 && iy < 90)
      for (int v = std::max(iy - 1, 0); v <= std::min(iy + 1, 89); ++v)
        for (int u = std::max(ix - 1, 0); u <= std::min(ix + 1, 119); ++u)
          expected = expected || map.at(u, v) >= 0.65;
    const bool got = fine.near_occupied(at.x, at.y, d, std::llround(cells * scale));
    near += got ? 1 : 0;
    equal += got == expected ? 1 : 0;
  }
  EXPECT_GT(near, std::size_t{kPoints / 40});
  EXPECT_GE(double(equal), 0.995 * kPoints);
}

// A reading that ends on a ragged wall its ray meets at 4 degrees: the ray meets a cell standing
// out of the wall well before the reading's range, so the strict first hit vetoes the true pose;
// the grazing rule scores it as the hit it is. A reading that crosses the wall and ends in free
// space beyond is vetoed either way.
TEST(FineMap, AWallMetAtAGrazingAngleScoresAsAHitUnderTheGrazingRule) {
  const double res = 0.05;
  ProbabilityGrid map(GridGeometry{400, 120, res, 0.0, 0.0}, 0.0);
  for (int x = 0; x < 400; ++x)
    for (int y = x % 10 == 0 ? 59 : 60; y < 62; ++y) map.at(x, y) = 1.0;  // surface y = 3 m
  const FineMap fine(map, 0.65, 0.196, 1024);
  const Pose2 pose{1.0, 2.5, 0.0};
  const int d = static_cast<int>(std::lround(4.0 * kPi / 180.0 / fine.heading_bin()));
  const double angle = d * fine.heading_bin();
  const double z = (3.0 - pose.y) / std::sin(angle);  // where the ray meets the wall's surface
  const FinePose at = fine.fine_pose(pose);
  const std::int64_t hit = fine.first_hit(at.x, at.y, d, 100000);
  ASSERT_NE(hit, FineMap::kNoHit);
  const double hit_m = double(hit) / std::ldexp(1.0, FineMap::kDistanceBits) * res;
  std::printf("[grazing] range %.3f m, first hit %.3f m\n", z, hit_m);
  ASSERT_LT(hit_m, z - 0.2);  // the scenario: the cells are entered well before the surface
  const double sigma = 0.05;
  const FineClaims on_wall = fine.claims(z, angle, sigma, 16, 8);
  const FineClaims beyond = fine.claims(z + 6.0, angle, sigma, 16, 8);
  const std::int32_t peak = *std::max_element(on_wall.claim.begin(), on_wall.claim.end());
  const FinePose heading0{at.x, at.y, 0};
  EXPECT_LT(fine.score(std::span(&on_wall, 1), heading0, false), 0);
  EXPECT_EQ(fine.score(std::span(&on_wall, 1), heading0, true), peak);
  EXPECT_LT(fine.score(std::span(&beyond, 1), heading0, false), 0);
  EXPECT_EQ(fine.score(std::span(&beyond, 1), heading0, true),
            fine.score(std::span(&beyond, 1), heading0, false));
}

// A 16 x 13 m floor at 5 cm: outer walls, inner walls with doors, pillars, no symmetry.
ProbabilityGrid floor_map() {
  FloorplanConfig f;
  f.width = 16.0;
  f.height = 13.0;
  f.cell = 0.05;
  return procedural_floorplan(f, 5);
}

GlobalLocConfig floor_config() {
  GlobalLocConfig config;
  config.pose_res = 0.2;
  config.headings = 64;
  config.sensor.max_range = 10.0;
  return config;
}

TEST(PoseRefinement, RefinedPosesAreWithinAFractionOfAPoseCell) {
  const ProbabilityGrid world = floor_map();
  const LocalizationMap lmap(world, 0.65, 0.196, floor_config());
  GlobalLocConfig lattice_config = floor_config();
  lattice_config.refine_levels = 0;
  const LocalizationMap lattice(world, 0.65, 0.196, lattice_config);
  SimRandom random(21);
  std::vector<double> refined_errors, lattice_errors, heading_errors;
  for (int n = 0; n < 12; ++n) {
    // A pose at least 0.4 m from the walls, anywhere in its pose cell, any heading.
    Pose2 truth;
    do {
      truth = {random.uniform(0.5, 15.5), random.uniform(0.5, 12.5), random.uniform(-kPi, kPi)};
    } while (clearance_map(world, 0.196)
                 .at(world.geometry.cell_x(truth.x), world.geometry.cell_y(truth.y)) < 0.4);
    const Scan scan = simulate_scan(world, lidar_sensor(180, 2.0 * kPi, 10.0),
                                    RangeNoiseConfig{0.01, 0.0, 0.0}, truth, 100 + n);
    const std::vector<RangeReading> readings = readings_of(scan, 0, 10.0);
    const GlobalEstimate fine = localize_global(lmap, readings, Pose2{}, GlobalMethod::pose_grid);
    const GlobalEstimate coarse =
        localize_global(lattice, readings, Pose2{}, GlobalMethod::pose_grid);
    refined_errors.push_back(std::hypot(fine.robot.x - truth.x, fine.robot.y - truth.y));
    heading_errors.push_back(std::abs(wrap_angle(fine.robot.theta - truth.theta)));
    lattice_errors.push_back(std::hypot(coarse.robot.x - truth.x, coarse.robot.y - truth.y));
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  std::printf(
      "[refinement] median position error %.3f m refined, %.3f m on the lattice; "
      "heading %.2f deg\n",
      median(refined_errors), median(lattice_errors), median(heading_errors) * 180.0 / kPi);
  // The lattice's cells are 0.2 m and 5.6 degrees; the refinement's last level steps 1.25 cm and
  // 0.35 degrees. Every pose is found, to a fraction of a pose cell.
  for (std::size_t n = 0; n < refined_errors.size(); ++n) {
    EXPECT_LE(refined_errors[n], 0.1) << n;
    EXPECT_LE(heading_errors[n], 1.5 * kPi / 180.0) << n;
  }
  EXPECT_LE(median(refined_errors), 0.04);
  EXPECT_LT(median(refined_errors), 0.5 * median(lattice_errors));
}

// The fused grid against a second formulation: every candidate's pose composed with each
// scan's motion and looked up at its nearest pose cell (the tracker shifts whole heading slices).
TEST(PoseTracker, FusedGridIsEachScansGridAtThePoseOdometryGivesThen) {
  const ProbabilityGrid world = floor_map();
  GlobalLocConfig config = floor_config();
  config.refine_levels = 0;
  const LocalizationMap lmap(world, 0.65, 0.196, config);
  SimRandom random(31);
  const std::vector<Pose2> path = {
      {4.0, 5.0, 0.3}, {4.7, 5.3, 0.5}, {5.3, 5.9, 1.1}, {5.5, 6.6, 1.4}};
  PoseSearchOptions options;
  options.threads = 2;
  PoseTracker tracker(lmap, options, path.size());
  std::vector<std::vector<std::int32_t>> grids;
  for (std::size_t s = 0; s < path.size(); ++s) {
    const Scan scan = simulate_scan(world, lidar_sensor(40, 2.0 * kPi, 10.0),
                                    RangeNoiseConfig{0.01, 0.0, 0.0}, path[s], 300 + s);
    const std::vector<RangeReading> readings = readings_of(scan, 0, 10.0);
    tracker.add_scan(readings, readings, s == 0 ? Pose2{} : relative(path[s - 1], path[s]));
    PoseScores scores;
    search_pose_grid(lmap, readings, readings, Pose2{}, options, &scores);
    grids.push_back(scores.index_sum);
  }
  const PoseScores fused = tracker.fused_scores();
  const Pose2 corner = lmap.pose_of(0, 0, 0);
  const double r = lmap.config().pose_res;
  std::size_t checked = 0;
  for (int k = 0; k < lmap.headings(); ++k)
    for (int j = 0; j < lmap.height(); ++j)
      for (int i = 0; i < lmap.width(); ++i) {
        if (!lmap.is_candidate(i, j)) {
          ASSERT_EQ(fused.index_sum[lmap.index(i, j, k)], std::numeric_limits<std::int32_t>::min());
          continue;
        }
        std::int64_t sum = grids.back()[lmap.index(i, j, k)];
        for (std::size_t s = 0; s + 1 < path.size(); ++s) {
          const Pose2 then = compose(lmap.pose_of(i, j, k), relative(path.back(), path[s]));
          const long long a = std::llround((then.x - corner.x) / r);
          const long long b = std::llround((then.y - corner.y) / r);
          const long long c = ((std::llround(then.theta / lmap.heading_bin()) % 64) + 64) % 64;
          if (a < 0 || b < 0 || a >= lmap.width() || b >= lmap.height()) continue;
          if (!lmap.is_candidate(int(a), int(b))) continue;
          sum += grids[s][lmap.index(int(a), int(b), int(c))];
        }
        ASSERT_EQ(fused.index_sum[lmap.index(i, j, k)], sum) << i << ' ' << j << ' ' << k;
        ++checked;
      }
  EXPECT_EQ(checked, lmap.candidate_cells());
}

TEST(PoseTracker, OneScanGivesTheSingleScanSearch) {
  const ProbabilityGrid world = floor_map();
  const LocalizationMap lmap(world, 0.65, 0.196, floor_config());
  const Scan scan = simulate_scan(world, lidar_sensor(60, 2.0 * kPi, 10.0),
                                  RangeNoiseConfig{0.02, 0.0, 0.0}, Pose2{7.3, 4.1, 2.0}, 5);
  const std::vector<RangeReading> readings = readings_of(scan, 0, 10.0);
  PoseSearchOptions options;
  options.hypotheses = 4;
  PoseTracker tracker(lmap, options, 3);
  tracker.add_scan(readings, readings, Pose2{});
  const PoseSearchResult a = tracker.search(Pose2{0.1, 0.0, 0.0});
  const PoseSearchResult b =
      search_pose_grid(lmap, readings, readings, Pose2{0.1, 0.0, 0.0}, options);
  ASSERT_EQ(a.hypotheses.size(), b.hypotheses.size());
  for (std::size_t h = 0; h < a.hypotheses.size(); ++h) {
    EXPECT_EQ(a.hypotheses[h].score, b.hypotheses[h].score);
    EXPECT_EQ(a.hypotheses[h].robot.x, b.hypotheses[h].robot.x);
    EXPECT_EQ(a.hypotheses[h].robot.y, b.hypotheses[h].robot.y);
    EXPECT_EQ(a.hypotheses[h].robot.theta, b.hypotheses[h].robot.theta);
  }
  EXPECT_EQ(a.ambiguous, b.ambiguous);
  // max_scans bounds the fused scans, and the memory they take is checked up front.
  tracker.add_scan(readings, readings, Pose2{0.3, 0.0, 0.0});
  tracker.add_scan(readings, readings, Pose2{0.3, 0.0, 0.0});
  EXPECT_THROW(tracker.add_scan(readings, readings, Pose2{0.3, 0.0, 0.0}), std::invalid_argument);
  GlobalLocConfig small = floor_config();
  small.memory_limit = lmap.memory_bytes() + 5 * 4 * lmap.candidate_cells();
  const LocalizationMap limited(world, 0.65, 0.196, small);
  EXPECT_NO_THROW(PoseTracker(limited, options, 5));
  EXPECT_THROW(PoseTracker(limited, options, 6), std::invalid_argument);
}

// A 24 x 2 m corridor closed at both ends, with an alcove near its east end. Seen with a 4 m
// sensor from its middle, every place along it looks the same; driving east, the alcove comes
// into view.
ProbabilityGrid corridor() {
  ProbabilityGrid g(GridGeometry{500, 80, 0.05, 0.0, 0.0}, 0.5);
  for (int j = 0; j < 80; ++j)
    for (int i = 0; i < 500; ++i) {
      const double x = (i + 0.5) * 0.05, y = (j + 0.5) * 0.05;
      const bool inside = x > 0.5 && x < 24.5 && y > 1.0 && y < 3.0;
      const bool alcove = x > 20.0 && x < 21.0 && y >= 3.0 && y < 3.8;
      const bool wall = !(inside || alcove) && x > 0.3 && x < 24.7 && y > 0.8 && y < 4.0;
      g.at(i, j) = inside || alcove ? 0.0 : wall ? 1.0 : 0.5;
    }
  return g;
}

// The corridor's pose grid, for a sensor of 4 m range.
LocalizationMap corridor_map(const ProbabilityGrid& world) {
  GlobalLocConfig config;
  config.sensor.max_range = 4.0;
  return LocalizationMap(world, 0.65, 0.196, config);
}

TEST(PoseTracker, ACorridorOneScanCannotPlaceIsPlacedAfterAShortDrive) {
  const ProbabilityGrid world = corridor();
  const LocalizationMap lmap = corridor_map(world);
  PoseSearchOptions options;
  options.hypotheses = 2;
  options.threads = 3;
  PoseTracker tracker(lmap, options, 20);
  Pose2 truth{12.0, 2.0, 0.0};
  std::size_t scans = 0;
  PoseSearchResult r;
  bool ambiguous_at_first = false;
  SimRandom odometry_noise(8);
  for (Pose2 previous = truth; scans < 20; ++scans) {
    const Scan scan = simulate_scan(world, lidar_sensor(90, 2.0 * kPi, 4.0),
                                    RangeNoiseConfig{0.02, 0.0, 0.0}, truth, 700 + scans);
    const std::vector<RangeReading> readings = readings_of(scan, 0, 4.0);
    // Odometry a few centimetres and a fraction of a degree off the true motion.
    Pose2 motion = relative(previous, truth);
    if (scans > 0) {
      motion.x += odometry_noise.uniform(-0.03, 0.03);
      motion.y += odometry_noise.uniform(-0.03, 0.03);
      motion.theta += odometry_noise.uniform(-0.01, 0.01);
    }
    tracker.add_scan(readings, readings, motion);
    r = tracker.search(Pose2{});
    if (scans == 0) {
      ambiguous_at_first = r.ambiguous;
      const PoseSearchResult alone = search_pose_grid(lmap, readings, readings, Pose2{}, options);
      EXPECT_TRUE(alone.ambiguous);
    }
    if (!r.ambiguous) break;
    previous = truth;
    truth = compose(truth, Pose2{0.6, 0.0, 0.0});
  }
  std::printf("[tracker] unambiguous after %zu scans, at x %.2f (truth %.2f)\n", scans + 1,
              r.estimate.robot.x, truth.x);
  EXPECT_TRUE(ambiguous_at_first);
  EXPECT_FALSE(r.ambiguous);
  // The alcove enters the 4 m range from x = 16: some 7 scans of 0.6 m from x = 12.
  EXPECT_GE(scans + 1, 4u);
  EXPECT_LE(scans + 1, 15u);
  EXPECT_LE(std::hypot(r.estimate.robot.x - truth.x, r.estimate.robot.y - truth.y), 0.15);
  EXPECT_LE(std::abs(wrap_angle(r.estimate.robot.theta - truth.theta)), 2.0 * kPi / 180.0);
}

// The same corridor driven in 0.2 m steps, as a log gives the scans: the first fused, then each
// that odometry puts 0.5 m from the last fused (every third), until the answer is unambiguous;
// the answers against a PoseTracker fed those scans by hand (a second formulation), and nothing
// taken once done.
TEST(SequenceLocalizer, FusesTheScansAStepApartUntilTheAnswerIsUnambiguous) {
  const ProbabilityGrid world = corridor();
  const LocalizationMap lmap = corridor_map(world);
  PoseSearchOptions options;
  options.hypotheses = 2;
  SequenceOptions sequence;
  sequence.max_scans = 20;
  SequenceLocalizer localizer(lmap, options, sequence);
  PoseTracker by_hand(lmap, options, 20);
  std::optional<Scan> last_fused;
  std::size_t offered = 0;
  Pose2 truth{12.0, 2.0, 0.0};
  PoseSearchResult answer;
  for (; offered < 60 && !localizer.done(); ++offered) {
    Scan scan = simulate_scan(world, lidar_sensor(90, 2.0 * kPi, 4.0),
                              RangeNoiseConfig{0.02, 0.0, 0.0}, truth, 900 + offered);
    scan.robot = truth;  // odometry: the true motion
    const std::optional<PoseSearchResult> found = localizer.offer(scan);
    EXPECT_EQ(found.has_value(), offered % 3 == 0) << offered;
    if (found) {
      const std::vector<RangeReading> readings = readings_of(scan, 60, 4.0),
                                      whole = readings_of(scan, 0, 4.0);
      by_hand.add_scan(
          readings, whole,
          last_fused ? relative(last_fused->sensor_pose(), scan.sensor_pose()) : Pose2{});
      last_fused = scan;
      const PoseSearchResult expected = by_hand.search(scan.sensor_mount);
      EXPECT_EQ(found->ambiguous, expected.ambiguous) << offered;
      EXPECT_EQ(found->estimate.robot.x, expected.estimate.robot.x) << offered;
      EXPECT_EQ(found->estimate.robot.theta, expected.estimate.robot.theta) << offered;
      answer = *found;
    }
    truth = compose(truth, Pose2{0.2, 0.0, 0.0});
  }
  std::printf("[sequence] unambiguous after %zu scans fused of %zu offered\n", localizer.scans(),
              offered);
  ASSERT_TRUE(localizer.done());
  EXPECT_FALSE(answer.ambiguous);
  EXPECT_GE(localizer.scans(), 2u);  // one scan cannot place it (the test above)
  EXPECT_EQ(localizer.scans(), by_hand.scans());
  const Pose2 at_answer = compose(truth, Pose2{-0.2, 0.0, 0.0});
  EXPECT_LE(
      std::hypot(answer.estimate.robot.x - at_answer.x, answer.estimate.robot.y - at_answer.y),
      0.15);
  Scan more = simulate_scan(world, lidar_sensor(90, 2.0 * kPi, 4.0),
                            RangeNoiseConfig{0.02, 0.0, 0.0}, truth, 999);
  more.robot = compose(truth, Pose2{1.0, 0.0, 0.0});
  EXPECT_FALSE(localizer.offer(more).has_value());
}

TEST(SequenceLocalizer, StopsAtMaxScansAndNamesABadStep) {
  const ProbabilityGrid world = corridor();
  const LocalizationMap lmap = corridor_map(world);
  SequenceOptions sequence;
  sequence.max_scans = 1;
  SequenceLocalizer localizer(lmap, PoseSearchOptions{}, sequence);
  Scan scan = simulate_scan(world, lidar_sensor(90, 2.0 * kPi, 4.0),
                            RangeNoiseConfig{0.02, 0.0, 0.0}, Pose2{12.0, 2.0, 0.0}, 5);
  scan.robot = Pose2{12.0, 2.0, 0.0};
  const std::optional<PoseSearchResult> found = localizer.offer(scan);
  ASSERT_TRUE(found.has_value());
  EXPECT_TRUE(found->ambiguous);  // the corridor's middle, one scan
  EXPECT_TRUE(localizer.done());
  for (const auto& [field, bad] :
       {std::pair{"step_position", SequenceOptions{60, 0, 10, -0.1, 0.2}},
        std::pair{"step_heading", SequenceOptions{60, 0, 10, 0.5, std::nan("")}}}) {
    try {
      check_sequence_options(bad);
      ADD_FAILURE() << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_TRUE(std::string(e.what()).starts_with(field)) << e.what();
    }
  }
}

}  // namespace
}  // namespace intgrid
