// The relation metric of the Freiburg SLAM benchmark (Kümmerle et al., "On measuring the
// accuracy of SLAM algorithms", Autonomous Robots 27(4), 2009): a trajectory is scored by how
// well it reproduces known relative motions between pairs of its poses, not by its absolute
// positions, so a trajectory is not penalized twice for one early error.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "intgrid/core/trajectory.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/slam/log_run.hpp"

namespace intgrid::slam {

// The true motion from the robot's pose at t1 to its pose at t2, expressed in the frame of the
// pose at t1 (t1, t2 in seconds, as the trajectory's times).
using core::Relation;

// A relation is off when its translational error exceeds kRelationOffMetres or its rotational
// error kRelationOffDegrees: the bounds of the SLAM's benchmark targets (docs/results.md: at
// most 2% of relations off), which a locally good trajectory meets and a wrong loop closure or a
// lost start does not.
inline constexpr double kRelationOffMetres = 0.3;
inline constexpr double kRelationOffDegrees = 5.0;

// The errors of the matched relations: mean and population standard deviation of the
// translational error (m) and the rotational error (degrees), and of their squares (m^2 and
// deg^2, as Kümmerle et al. report them), the medians, and how many are off. All statistics
// are 0 when nothing matched.
struct RelationError {
  std::size_t matched = 0;
  std::size_t unmatched = 0;  // relations with no trajectory pose within the tolerance of t1 or t2
  std::size_t off = 0;        // matched relations off by more than the bounds above
  double trans_median = 0.0;  // the lower median of an even count
  double rot_median_deg = 0.0;
  double trans_mean = 0.0;
  double trans_std = 0.0;
  double rot_mean_deg = 0.0;
  double rot_std_deg = 0.0;
  double trans_sq_mean = 0.0;
  double trans_sq_std = 0.0;
  double rot_sq_mean = 0.0;
  double rot_sq_std = 0.0;
};

// The benchmark's default time tolerance between a relation's timestamp and a pose's.
inline constexpr double kRelationTolerance = 0.01;

// Scores trajectory (sorted by t) against relations. For each relation the poses nearest t1 and
// t2 are looked up; if either lies farther than tolerance_s from its time the relation is
// unmatched. Otherwise the estimated motion is d = pose(t1)^-1 * pose(t2), the error transform
// e = motion^-1 * d, the translational error |(e.x, e.y)| and the rotational error
// |wrap(e.theta)| in degrees. Throws std::invalid_argument if the trajectory is not sorted by t
// (or holds a NaN time) or tolerance_s is negative or NaN.
RelationError score_relations(std::span<const TimedPose> trajectory,
                              std::span<const Relation> relations,
                              double tolerance_s = kRelationTolerance);

// One relation's error, as score_relations measures it; matched is false (and the errors 0)
// when no pose lies within the tolerance of t1 or t2.
struct RelationResult {
  Relation relation;
  bool matched = false;
  double trans_error = 0.0;    // m
  double rot_error_deg = 0.0;  // degrees
  bool off() const {
    return matched && (trans_error > kRelationOffMetres || rot_error_deg > kRelationOffDegrees);
  }
};

// Each relation's error, in the relations' order (score_relations' statistics are these
// summarized). Throws as score_relations does.
std::vector<RelationResult> relation_errors(std::span<const TimedPose> trajectory,
                                            std::span<const Relation> relations,
                                            double tolerance_s = kRelationTolerance);

// The statistics of RelationError over per-relation results.
RelationError summarize_relations(std::span<const RelationResult> results);

// Where a trajectory fails: a run of off relations in the order of their t1, which goes on
// across at most kStretchGap matched relations that are not off (one good relation inside a
// bad stretch does not split it). Its relations span t1 in [t1_first, t1_last] and t2 in
// [t2_min, t2_max]: a stretch whose t2 lie long after its t1 links an early part of the
// trajectory to a later one (a loop closed wrongly, or not closed).
struct RelationStretch {
  double t1_first = 0.0, t1_last = 0.0;
  double t2_min = 0.0, t2_max = 0.0;
  std::size_t relations = 0;  // matched relations from its first off one to its last
  std::size_t off = 0;
  double trans_max = 0.0;    // m
  double rot_max_deg = 0.0;  // degrees
};
inline constexpr std::size_t kStretchGap = 2;

// The stretches, worst first: most off relations, then the largest translational error.
std::vector<RelationStretch> worst_stretches(std::span<const RelationResult> results);

}  // namespace intgrid::slam
