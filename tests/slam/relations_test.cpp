// The Freiburg benchmark's relation metric (slam/relations.hpp) on small hand-computed cases:
// a trajectory that reproduces its relations, pure translation errors seen in a turned frame, a
// rotation error and its wrap, unmatched relations, the nearest pose and the tolerance's edge.
#include "intgrid/slam/relations.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace {

using intgrid::core::Pose2;
using intgrid::slam::Relation;
using intgrid::slam::RelationError;
using intgrid::slam::score_relations;
using intgrid::slam::TimedPose;

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = 180.0 / kPi;

void expect_all_zero(const RelationError& e) {
  EXPECT_EQ(e.trans_mean, 0.0);
  EXPECT_EQ(e.trans_std, 0.0);
  EXPECT_EQ(e.rot_mean_deg, 0.0);
  EXPECT_EQ(e.rot_std_deg, 0.0);
  EXPECT_EQ(e.trans_sq_mean, 0.0);
  EXPECT_EQ(e.trans_sq_std, 0.0);
  EXPECT_EQ(e.rot_sq_mean, 0.0);
  EXPECT_EQ(e.rot_sq_std, 0.0);
}

TEST(Relations, ATrajectoryThatReproducesItsRelationsScoresZero) {
  // (0,0,0) -> (1,0,0) -> (1,1,pi/2): the motions are (1,0,0), then (0,1,pi/2) in the frame of
  // (1,0,0), and (1,1,pi/2) from the start.
  const std::vector<TimedPose> trajectory = {
      {0.0, {0, 0, 0}}, {1.0, {1, 0, 0}}, {2.0, {1, 1, kPi / 2}}};
  const std::vector<Relation> relations = {
      {0.0, 1.0, {1, 0, 0}}, {1.0, 2.0, {0, 1, kPi / 2}}, {0.0, 2.0, {1, 1, kPi / 2}}};
  const RelationError e = score_relations(trajectory, relations);
  EXPECT_EQ(e.matched, 3u);
  EXPECT_EQ(e.unmatched, 0u);
  EXPECT_NEAR(e.trans_mean, 0.0, 1e-12);
  EXPECT_NEAR(e.rot_mean_deg, 0.0, 1e-12);
  EXPECT_NEAR(e.trans_sq_mean, 0.0, 1e-24);
}

TEST(Relations, TranslationErrorsAreMeasuredInThePoseFrame) {
  // The robot heads along +y: from (2,3,pi/2) to (2,4,pi/2) is 1 m straight ahead, (1,0,0) in
  // its own frame. Against true motions (1,0.3,0) and (0.5,0,0) the errors are 0.3 m and 0.5 m:
  // mean 0.4, std 0.1; squared 0.09 and 0.25: mean 0.17, std 0.08. No rotation error.
  const std::vector<TimedPose> trajectory = {{10.0, {2, 3, kPi / 2}}, {11.0, {2, 4, kPi / 2}}};
  const std::vector<Relation> relations = {{10.0, 11.0, {1, 0.3, 0}}, {10.0, 11.0, {0.5, 0, 0}}};
  const RelationError e = score_relations(trajectory, relations);
  EXPECT_EQ(e.matched, 2u);
  EXPECT_EQ(e.unmatched, 0u);
  EXPECT_NEAR(e.trans_mean, 0.4, 1e-12);
  EXPECT_NEAR(e.trans_std, 0.1, 1e-12);
  EXPECT_NEAR(e.trans_sq_mean, 0.17, 1e-12);
  EXPECT_NEAR(e.trans_sq_std, 0.08, 1e-12);
  EXPECT_NEAR(e.rot_mean_deg, 0.0, 1e-12);
  EXPECT_NEAR(e.rot_std_deg, 0.0, 1e-12);
}

TEST(Relations, TheErrorIsTheTrueMotionInverseTimesTheEstimate) {
  // Estimated motion (1,0,0), true motion (0,0,pi/2): e = true^-1 * estimated = (0,-1,-pi/2),
  // so 1 m and 90 degrees. (The other order, estimated^-1 * true, would give (-1,0,pi/2): the
  // same magnitudes, as they must be.)
  const std::vector<TimedPose> trajectory = {{0.0, {0, 0, 0}}, {1.0, {1, 0, 0}}};
  const std::vector<Relation> relations = {{0.0, 1.0, {0, 0, kPi / 2}}};
  const RelationError e = score_relations(trajectory, relations);
  EXPECT_EQ(e.matched, 1u);
  EXPECT_NEAR(e.trans_mean, 1.0, 1e-12);
  EXPECT_NEAR(e.rot_mean_deg, 90.0, 1e-12);
  EXPECT_NEAR(e.rot_sq_mean, 8100.0, 1e-9);
  EXPECT_NEAR(e.trans_std, 0.0, 1e-12);
  EXPECT_NEAR(e.rot_std_deg, 0.0, 1e-12);
}

TEST(Relations, RotationErrorsAreWrappedAndInDegrees) {
  // A pure turn of 0.1 rad against a true straight motion: 0.1 rad = 5.7296 deg. A turn of
  // 3.1 rad against a true -3.1 rad: the difference 6.2 rad wraps to 2 pi - 6.2 = 0.0832 rad.
  const std::vector<TimedPose> trajectory = {
      {0.0, {0, 0, 0}}, {1.0, {0, 0, 0.1}}, {2.0, {0, 0, 3.1}}};
  const std::vector<Relation> relations = {{0.0, 1.0, {0, 0, 0}}, {0.0, 2.0, {0, 0, -3.1}}};
  const RelationError e = score_relations(trajectory, relations);
  ASSERT_EQ(e.matched, 2u);
  const double a = 0.1 * kDeg, b = (2 * kPi - 6.2) * kDeg;
  EXPECT_NEAR(e.rot_mean_deg, (a + b) / 2, 1e-9);
  EXPECT_NEAR(e.rot_std_deg, std::abs(a - b) / 2, 1e-9);
  EXPECT_NEAR(e.rot_sq_mean, (a * a + b * b) / 2, 1e-9);
  EXPECT_NEAR(e.rot_sq_std, std::abs(a * a - b * b) / 2, 1e-9);
  EXPECT_NEAR(e.trans_mean, 0.0, 1e-12);
}

TEST(Relations, RelationsWithoutPosesAreCountedUnmatchedAndLeftOutOfTheStatistics) {
  const std::vector<TimedPose> trajectory = {{0.0, {0, 0, 0}}, {1.0, {1, 0, 0}}};
  const std::vector<Relation> relations = {
      {0.0, 1.0, {0.8, 0, 0}},  // matched: 0.2 m
      {0.0, 0.5, {0, 0, 0}},    // t2 between two poses, 0.5 s from either
      {-1.0, 1.0, {0, 0, 0}},   // t1 before the trajectory
      {1.0, 5.0, {0, 0, 0}},    // t2 after it
      {0.02, 1.0, {0, 0, 0}}};  // t1 0.02 s from a pose: past the default 0.01 s
  const RelationError e = score_relations(trajectory, relations);
  EXPECT_EQ(e.matched, 1u);
  EXPECT_EQ(e.unmatched, 4u);
  EXPECT_NEAR(e.trans_mean, 0.2, 1e-12);
  EXPECT_NEAR(e.trans_std, 0.0, 1e-12);

  const RelationError none = score_relations({}, relations);
  EXPECT_EQ(none.matched, 0u);
  EXPECT_EQ(none.unmatched, relations.size());
  expect_all_zero(none);
  const RelationError empty = score_relations(trajectory, {});
  EXPECT_EQ(empty.matched + empty.unmatched, 0u);
  expect_all_zero(empty);
}

TEST(Relations, ThePoseNearestEachTimeIsUsed) {
  // Poses at 1.0 and 1.004: a relation at 1.003 takes the second (1 m away from the first), one
  // at 1.001 the first.
  const std::vector<TimedPose> trajectory = {
      {0.0, {0, 0, 0}}, {1.0, {1, 0, 0}}, {1.004, {2, 0, 0}}};
  EXPECT_NEAR(
      score_relations(trajectory, std::vector<Relation>{{0.0, 1.003, {2, 0, 0}}}).trans_mean, 0.0,
      1e-12);
  EXPECT_NEAR(
      score_relations(trajectory, std::vector<Relation>{{0.0, 1.001, {2, 0, 0}}}).trans_mean, 1.0,
      1e-12);
}

TEST(Relations, ATimeExactlyAtTheToleranceMatchesAndJustPastItDoesNot) {
  // Times and tolerance exact in binary: 0.25 from the pose at 0 matches, the next double does
  // not; likewise 0.75 (0.25 before the pose at 1).
  const std::vector<TimedPose> trajectory = {{0.0, {0, 0, 0}}, {1.0, {1, 0, 0}}};
  const double past = std::nextafter(0.25, 1.0);
  const std::vector<Relation> relations = {
      {0.25, 0.75, {1, 0, 0}}, {past, 1.0, {1, 0, 0}}, {0.0, std::nextafter(0.75, 0.0), {1, 0, 0}}};
  const RelationError e = score_relations(trajectory, relations, 0.25);
  EXPECT_EQ(e.matched, 1u);
  EXPECT_EQ(e.unmatched, 2u);
  // Zero tolerance: only exact times.
  EXPECT_EQ(score_relations(trajectory, std::vector<Relation>{{0.0, 1.0, {1, 0, 0}}}, 0.0).matched,
            1u);
  // The default, 0.01 s, on a pose at 100 s: 5 ms off matches, 15 ms off does not.
  const std::vector<TimedPose> late = {{100.0, {0, 0, 0}}, {101.0, {1, 0, 0}}};
  const RelationError d = score_relations(
      late, std::vector<Relation>{{100.005, 101.0, {1, 0, 0}}, {100.015, 101.0, {1, 0, 0}}});
  EXPECT_EQ(d.matched, 1u);
  EXPECT_EQ(d.unmatched, 1u);
}

TEST(Relations, AnUnsortedTrajectoryOrABadToleranceIsRefused) {
  const std::vector<TimedPose> unsorted = {{1.0, {0, 0, 0}}, {0.5, {1, 0, 0}}};
  const std::vector<Relation> relations = {{0.5, 1.0, {1, 0, 0}}};
  EXPECT_THROW(score_relations(unsorted, relations), std::invalid_argument);
  const std::vector<TimedPose> nan_time = {{0.0, {0, 0, 0}}, {std::nan(""), {1, 0, 0}}};
  EXPECT_THROW(score_relations(nan_time, relations), std::invalid_argument);
  const std::vector<TimedPose> sorted = {{0.5, {0, 0, 0}}, {1.0, {1, 0, 0}}};
  EXPECT_THROW(score_relations(sorted, relations, -0.01), std::invalid_argument);
  EXPECT_THROW(score_relations(sorted, relations, std::nan("")), std::invalid_argument);
  // Equal times are sorted.
  const std::vector<TimedPose> ties = {{0.5, {0, 0, 0}}, {0.5, {0, 0, 0}}, {1.0, {1, 0, 0}}};
  EXPECT_EQ(score_relations(ties, relations).matched, 1u);
}

}  // namespace

// A straight trajectory one metre a second, and relations (i, i+1) whose true motion is
// (1 + e_i, 0, 0): relation i's translational error is exactly |e_i|.
struct LineCase {
  std::vector<TimedPose> trajectory;
  std::vector<Relation> relations;
};

LineCase line_with_errors(const std::vector<double>& errors) {
  LineCase c;
  for (std::size_t i = 0; i <= errors.size(); ++i)
    c.trajectory.push_back({double(i), {double(i), 0, 0}});
  for (std::size_t i = 0; i < errors.size(); ++i)
    c.relations.push_back({double(i), double(i + 1), {1.0 + errors[i], 0, 0}});
  return c;
}

TEST(Relations, MediansAndTheOffCountFollowEachRelationsError) {
  const std::vector<double> errors = {0.05, -0.4, 0.01, 0.31, -0.02, 0.29, 0.2};
  const LineCase c = line_with_errors(errors);
  const std::vector<intgrid::slam::RelationResult> results =
      intgrid::slam::relation_errors(c.trajectory, c.relations);
  ASSERT_EQ(results.size(), errors.size());
  std::vector<double> magnitudes;
  std::size_t off = 0;
  for (std::size_t i = 0; i < errors.size(); ++i) {
    EXPECT_TRUE(results[i].matched);
    EXPECT_NEAR(results[i].trans_error, std::abs(errors[i]), 1e-12);
    EXPECT_EQ(results[i].off(), std::abs(errors[i]) > 0.3) << i;
    magnitudes.push_back(std::abs(errors[i]));
    off += std::abs(errors[i]) > 0.3 ? 1 : 0;
  }
  std::sort(magnitudes.begin(), magnitudes.end());
  const RelationError e = score_relations(c.trajectory, c.relations);
  EXPECT_EQ(e.off, off);
  EXPECT_EQ(e.off, 2u);  // 0.4 and 0.31, not 0.29
  EXPECT_NEAR(e.trans_median, magnitudes[(magnitudes.size() - 1) / 2], 1e-12);
  // The summary of the per-relation results is the score.
  const RelationError s = intgrid::slam::summarize_relations(results);
  EXPECT_EQ(s.matched, e.matched);
  EXPECT_EQ(s.trans_mean, e.trans_mean);
  EXPECT_EQ(s.rot_sq_std, e.rot_sq_std);
}

TEST(Relations, ARotationPastFiveDegreesIsOffAndUnmatchedRelationsAreNever) {
  const std::vector<TimedPose> trajectory = {{0.0, {0, 0, 0}}, {1.0, {1, 0, 0}}};
  const std::vector<Relation> relations = {
      {0.0, 1.0, {1, 0, 6.0 / kDeg}}, {0.0, 1.0, {1, 0, 4.0 / kDeg}}, {0.0, 9.0, {100, 0, 0}}};
  const auto results = intgrid::slam::relation_errors(trajectory, relations);
  EXPECT_TRUE(results[0].off());
  EXPECT_FALSE(results[1].off());
  EXPECT_FALSE(results[2].matched);
  EXPECT_FALSE(results[2].off());
  const RelationError e = score_relations(trajectory, relations);
  EXPECT_EQ(e.off, 1u);
  EXPECT_NEAR(e.rot_median_deg, 4.0, 1e-9);  // the lower median of {4, 6}
}

TEST(Relations, StretchesRunAcrossAtMostTwoGoodRelationsAndTheWorstComesFirst) {
  // By t1: good, OFF 0.5, good, good, OFF 0.4, good, good, good, OFF 0.8, OFF 0.35, good.
  const std::vector<double> errors = {0.0, 0.5, 0.0, 0.0, 0.4, 0.0, 0.0, 0.0, 0.8, 0.35, 0.0};
  LineCase c = line_with_errors(errors);
  // The file's order is not the time order: the stretches are found in t1 order.
  std::swap(c.relations[0], c.relations[9]);
  std::swap(c.relations[3], c.relations[5]);
  const auto stretches =
      intgrid::slam::worst_stretches(intgrid::slam::relation_errors(c.trajectory, c.relations));
  ASSERT_EQ(stretches.size(), 2u);
  // Both hold two off relations; the one with the larger error comes first.
  EXPECT_EQ(stretches[0].off, 2u);
  EXPECT_EQ(stretches[0].relations, 2u);
  EXPECT_EQ(stretches[0].t1_first, 8.0);
  EXPECT_EQ(stretches[0].t1_last, 9.0);
  EXPECT_EQ(stretches[0].t2_max, 10.0);
  EXPECT_NEAR(stretches[0].trans_max, 0.8, 1e-12);
  EXPECT_EQ(stretches[1].off, 2u);
  EXPECT_EQ(stretches[1].relations, 4u);  // OFF, good, good, OFF
  EXPECT_EQ(stretches[1].t1_first, 1.0);
  EXPECT_EQ(stretches[1].t1_last, 4.0);
  EXPECT_EQ(stretches[1].t2_min, 2.0);
  EXPECT_EQ(stretches[1].t2_max, 5.0);
  EXPECT_NEAR(stretches[1].trans_max, 0.5, 1e-12);
}
