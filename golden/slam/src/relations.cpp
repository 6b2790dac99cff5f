#include "intgrid/slam/relations.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "intgrid/core/failure.hpp"

namespace intgrid::slam {
namespace {

// The pose nearest time t (the earlier one on a tie), if within tolerance.
std::optional<core::Pose2> pose_near(std::span<const TimedPose> trajectory, double t,
                                     double tolerance) {
  const auto after = std::lower_bound(trajectory.begin(), trajectory.end(), t,
                                      [](const TimedPose& p, double time) { return p.t < time; });
  auto best = trajectory.end();
  if (after != trajectory.end()) best = after;
  if (after != trajectory.begin()) {
    const auto before = std::prev(after);
    if (best == trajectory.end() || t - before->t <= best->t - t) best = before;
  }
  if (best == trajectory.end() || !(std::abs(best->t - t) <= tolerance)) return std::nullopt;
  return best->pose;
}

struct MeanStd {
  double mean = 0.0;
  double std = 0.0;
};

// Mean and population standard deviation (two passes); zeros for no values.
MeanStd mean_std(const std::vector<double>& values) {
  MeanStd m;
  if (values.empty()) return m;
  const double n = static_cast<double>(values.size());
  for (const double v : values) m.mean += v;
  m.mean /= n;
  double squares = 0.0;
  for (const double v : values) squares += (v - m.mean) * (v - m.mean);
  m.std = std::sqrt(squares / n);
  return m;
}

}  // namespace

RelationError score_relations(std::span<const TimedPose> trajectory,
                              std::span<const Relation> relations, double tolerance_s) {
  if (!(tolerance_s >= 0.0)) core::fail<std::invalid_argument>("tolerance_s must be >= 0 (s)");
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    if (std::isnan(trajectory[i].t))
      core::fail<std::invalid_argument>("trajectory: pose " + std::to_string(i) +
                                        " has a NaN time");
    if (i > 0 && trajectory[i].t < trajectory[i - 1].t)
      core::fail<std::invalid_argument>("trajectory: not sorted by time at pose " +
                                        std::to_string(i));
  }

  RelationError r;
  std::vector<double> trans, rot, trans_sq, rot_sq;
  for (const Relation& relation : relations) {
    const std::optional<core::Pose2> a = pose_near(trajectory, relation.t1, tolerance_s);
    const std::optional<core::Pose2> b =
        a ? pose_near(trajectory, relation.t2, tolerance_s) : std::nullopt;
    if (!a || !b) {
      ++r.unmatched;
      continue;
    }
    const core::Pose2 estimated = core::relative(*a, *b);
    const core::Pose2 e = core::relative(relation.motion, estimated);  // motion^-1 * estimated
    const double t = std::hypot(e.x, e.y);
    const double deg = std::abs(core::wrap_angle(e.theta)) * 180.0 / std::numbers::pi;
    trans.push_back(t);
    rot.push_back(deg);
    trans_sq.push_back(t * t);
    rot_sq.push_back(deg * deg);
    ++r.matched;
  }
  const MeanStd mt = mean_std(trans), mr = mean_std(rot), mts = mean_std(trans_sq),
                mrs = mean_std(rot_sq);
  r.trans_mean = mt.mean;
  r.trans_std = mt.std;
  r.rot_mean_deg = mr.mean;
  r.rot_std_deg = mr.std;
  r.trans_sq_mean = mts.mean;
  r.trans_sq_std = mts.std;
  r.rot_sq_mean = mrs.mean;
  r.rot_sq_std = mrs.std;
  return r;
}

}  // namespace intgrid::slam
