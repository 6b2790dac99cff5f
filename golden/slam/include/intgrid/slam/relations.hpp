// The relation metric of the Freiburg SLAM benchmark (Kümmerle et al., "On measuring the
// accuracy of SLAM algorithms", Autonomous Robots 27(4), 2009): a trajectory is scored by how
// well it reproduces known relative motions between pairs of its poses, not by its absolute
// positions, so a trajectory is not penalized twice for one early error.
#pragma once

#include <cstddef>
#include <span>

#include "intgrid/core/types.hpp"
#include "intgrid/slam/log_run.hpp"

namespace intgrid::slam {

// The true motion from the robot's pose at t1 to its pose at t2, expressed in the frame of the
// pose at t1 (t1, t2 in seconds, as the trajectory's times).
struct Relation {
  double t1 = 0.0;
  double t2 = 0.0;
  core::Pose2 motion;
};

// The errors of the matched relations: mean and population standard deviation of the
// translational error (m) and the rotational error (degrees), and of their squares (m^2 and
// deg^2, as Kümmerle et al. report them). All statistics are 0 when nothing matched.
struct RelationError {
  std::size_t matched = 0;
  std::size_t unmatched = 0;  // relations with no trajectory pose within the tolerance of t1 or t2
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

}  // namespace intgrid::slam
