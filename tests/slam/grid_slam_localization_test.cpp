// The grid SLAM's localization: a displaced reading moves the estimate toward the truth.
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
// 4. Localization: map from the origin, then read from a displaced pose with "no motion".
//
// The map is one scan's: its cells are known only along that scan's rays, and a ray of another
// pose that runs through unknown cells (P = 1/2 each) is improbable. With 90 beams (4 degrees
// apart) such a map holds the posterior at the mapped pose whatever the truth (measured: the
// estimate did not move at all, for every displacement below); with 360 beams (1 degree, 5 cm
// apart at 3 m) the walls and the free space are dense enough to localize against.

GridSlamConfig localization_config() {
  GridSlamConfig c = small_config();
  // Pi spreads over the neighbouring cells and headings on a still update.
  c.motion.xy0 = 0.05;
  c.motion.theta0 = 0.02;
  // One scan of a simulated room, whose readings are independent given the map: weighed as such,
  // not with the real log's tempering (GridSlamConfig::tempering).
  c.beam.tempering = 1;
  return c;
}

struct Localized {
  Pose2 estimate;
  SlamPose mode, window;  // the mode's pose and the window's origin (element 0)
  std::size_t localizations = 0;
};

// The room mapped from one pose, then read from the pose displaced by `displacement` while the
// odometry says the robot did not move: the SLAM after those two scans.
template <class Pr>
GridSlamEngine<Pr> map_then_localize(const GridSlamConfig& config, const Pose2& displacement) {
  const World world = room_with_pillar();
  const Pose2 robot{-0.4, 0.3, 0.2};
  const Pose2 truth = compose(robot, displacement);
  Log log;
  log.scans.push_back(make_scan(world, robot, robot, 0.0, 360));
  log.scans.push_back(make_scan(world, truth, robot, 0.1, 360));  // odometry: no motion
  const std::vector<QuantizedScan> scans = quantize(log, config);
  EXPECT_EQ(scans[1].odom_dx_mm, 0);
  EXPECT_EQ(scans[1].odom_dy_mm, 0);
  EXPECT_EQ(scans[1].odom_dtheta, 0);
  const SlamSetup setup = make_slam_setup(config, log.scans[0], 0.0);
  GridSlamEngine<Pr> slam(setup, make_probabilities<Pr>(setup));
  slam.process(scans[0]);
  slam.process(scans[1]);
  return slam;
}

template <class Pr>
Localized localize_once(const Pose2& displacement) {
  const GridSlamEngine<Pr> slam = map_then_localize<Pr>(localization_config(), displacement);
  Localized r;
  r.estimate = pose_of(slam.estimate());
  r.mode = slam.pose_of(mode_of(slam));
  r.window = slam.pose_of(0);
  r.localizations = slam.localizations();
  return r;
}

template <class Pr>
void expect_localization_moves_toward_the_truth(const char* name) {
  const GridSlamConfig config = localization_config();
  const int n = config.window.cells, nt = config.window.headings;
  const double c = config.cell, bin = 2.0 * kPi / config.headings;
  const double unit = 2.0 * kPi / kAngleUnitsPerTurn;  // radians per angle unit
  const long cell_mm = std::lround(c * 1000.0);
  for (const Pose2& truth :
       {Pose2{0.04, -0.03, 0.0175}, Pose2{0.09, -0.04, 0.0175}, Pose2{-0.08, 0.09, -0.012},
        Pose2{0.0, 0.1, 0.0}, Pose2{0.0, 0.0, 0.02}, Pose2{-0.11, -0.07, -0.015}}) {
    const Localized r = localize_once<Pr>(truth);
    EXPECT_EQ(r.localizations, 1u);
    const double before_xy = std::hypot(truth.x, truth.y), before_theta = std::abs(truth.theta);
    const double after_xy = std::hypot(r.estimate.x - truth.x, r.estimate.y - truth.y);
    const double after_theta = std::abs(r.estimate.theta - truth.theta);
    // The estimate comes closer to the truth (or, with the truth at the centre, stays within
    // 1 cm of it).
    if (before_xy > 0.0)
      EXPECT_LT(after_xy, before_xy) << name << " " << truth.x << "," << truth.y;
    else
      EXPECT_LT(after_xy, 0.01) << name;
    if (before_theta > 0.0)
      EXPECT_LT(after_theta, before_theta) << name << " " << truth.theta;
    else
      EXPECT_LT(after_theta, bin) << name;
    // The mode is the grid pose nearest the truth: its cell, and its heading within one bin.
    EXPECT_EQ(r.mode.x_mm, std::lround(truth.x / c) * cell_mm) << name << " " << truth.x;
    EXPECT_EQ(r.mode.y_mm, std::lround(truth.y / c) * cell_mm) << name << " " << truth.y;
    EXPECT_LE(std::abs(static_cast<double>(r.mode.theta) * unit - truth.theta), 1.5 * bin)
        << name << " " << truth.theta;
    std::printf(
        "[slam] localization, %s: truth (%.3f, %.3f, %.4f): position error %.4f -> %.4f m, "
        "heading error %.4f -> %.4f rad; mode (%lld mm, %lld mm, %lld units)\n",
        name, truth.x, truth.y, truth.theta, before_xy, after_xy, before_theta, after_theta,
        static_cast<long long>(r.mode.x_mm), static_cast<long long>(r.mode.y_mm),
        static_cast<long long>(r.mode.theta));
  }
  // Read from the mapped pose itself: the mode stays at the centre of an unmoved window.
  const Localized still = localize_once<Pr>({});
  EXPECT_EQ(still.mode.x_mm, 0) << name;
  EXPECT_EQ(still.mode.y_mm, 0) << name;
  EXPECT_EQ(still.mode.theta, 0) << name;
  EXPECT_EQ(still.window.x_mm, -(n / 2) * cell_mm);
  EXPECT_EQ(still.window.y_mm, -(n / 2) * cell_mm);
  EXPECT_EQ(still.window.theta, -(nt / 2) * (kAngleUnitsPerTurn / config.headings));
  EXPECT_LT(std::hypot(still.estimate.x, still.estimate.y), 0.01) << name;
  EXPECT_LT(std::abs(still.estimate.theta), 0.5 * bin) << name;
  std::printf("[slam] localization, %s, still: estimate (%.4f, %.4f, %.5f)\n", name,
              still.estimate.x, still.estimate.y, still.estimate.theta);
}

TEST(SlamLocalization, EstimateMovesTowardTheTruePoseInDouble) {
  expect_localization_moves_toward_the_truth<DoubleProbabilities>("double");
}

TEST(SlamLocalization, EstimateMovesTowardTheTruePoseInInteger) {
  expect_localization_moves_toward_the_truth<IndexProbabilities>("integer");
}

// A scan's joint likelihood, raised to 1 / tempering, against the log-domain oracle
// exp(sum ln p / k): 2000 beams of 1e-3 to 1 pass far below the smallest double (1e-308) and the
// smallest 16-bit U_gamma index (2^-2048), which a running product of them would reach and keep.
template <class Pr>
void expect_joint_likelihood_survives_underflow(const char* name) {
  const GridSlamConfig config = small_config();
  const Log log = [] {
    Log l;
    l.scans.push_back(make_scan(room_with_pillar(), {}, {}, 0.0, 90));
    return l;
  }();
  const SlamSetup setup = make_slam_setup(config, log.scans[0], 0.0);
  const Pr pr = make_probabilities<Pr>(setup);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-3.0, 0.0);  // log10 p
  typename Pr::Joint joint;
  double log_sum = 0.0;
  for (int beam = 0; beam < 2000; ++beam) {
    const double p = std::pow(10.0, uniform(random));
    if constexpr (std::is_same_v<Pr, IndexProbabilities>) {
      const UIndex i = pr.u.from_probability(p);
      pr.multiply_into(joint, i);
      log_sum += pr.u.to_log(i);  // the index's own value: the oracle sums what was added
    } else {
      pr.multiply_into(joint, p);
      log_sum += std::log(p);
    }
  }
  ASSERT_LT(log_sum, -2000.0) << name;  // below both arithmetics' smallest probability
  for (const int k : {12, 20, 40}) {    // roots a double holds: ln of its smallest is -744
    const typename Pr::P root = pr.root_of(joint, k);
    ASSERT_FALSE(pr.is_zero(root)) << name << " k " << k;
    if constexpr (std::is_same_v<Pr, IndexProbabilities>)
      // Truncating the index sum by k: at most one step, ln(1/gamma).
      EXPECT_NEAR(pr.u.to_log(root), log_sum / k, std::log(2.0) / 16.0 + 1e-9)
          << name << " k " << k;
    else
      EXPECT_NEAR(std::log(root), log_sum / k, 1e-9 * std::abs(log_sum)) << name << " k " << k;
  }
}

TEST(SlamLocalization, JointLikelihoodOfManyBeamsSurvivesUnderflowInDouble) {
  expect_joint_likelihood_survives_underflow<DoubleProbabilities>("double");
}

TEST(SlamLocalization, JointLikelihoodOfManyBeamsSurvivesUnderflowInInteger) {
  expect_joint_likelihood_survives_underflow<IndexProbabilities>("integer");
}

// A localization drops the poses it leaves below pose_prune, and only those: the same scans
// without pruning give the same grid on every kept pose (bit for bit) and something below the
// threshold on every dropped one.
template <class Pr>
void expect_localization_prunes_only_negligible_poses(const char* name) {
  GridSlamConfig pruned = localization_config();
  pruned.window.pose_prune = 1e-6;
  GridSlamConfig kept = pruned;
  kept.window.pose_prune = 0.0;
  const Pose2 displacement{0.04, -0.03, 0.0175};
  const GridSlamEngine<Pr> with = map_then_localize<Pr>(pruned, displacement),
                           without = map_then_localize<Pr>(kept, displacement);
  ASSERT_EQ(with.localizations(), 1u);
  std::size_t dropped = 0;
  for (std::size_t q = 0; q < with.pose_grid().size(); ++q) {
    const double p = probability_of(without, without.pose_grid()[q]);
    if (with.probabilities().is_zero(with.pose_grid()[q])) {
      dropped += p > 0.0;
      EXPECT_LT(p, 1e-6) << name << " pose " << q;
    } else {
      EXPECT_EQ(with.pose_grid()[q], without.pose_grid()[q]) << name << " pose " << q;
    }
  }
  EXPECT_GT(dropped, 0u) << name;
}

TEST(SlamLocalization, PruningDropsOnlyPosesBelowTheThresholdInDouble) {
  expect_localization_prunes_only_negligible_poses<DoubleProbabilities>("double");
}

TEST(SlamLocalization, PruningDropsOnlyPosesBelowTheThresholdInInteger) {
  expect_localization_prunes_only_negligible_poses<IndexProbabilities>("integer");
}

}  // namespace
}  // namespace intgrid
