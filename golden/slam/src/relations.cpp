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

// The lower median (0 for no values).
double lower_median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>((values.size() - 1) / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

std::vector<RelationResult> relation_errors(std::span<const TimedPose> trajectory,
                                            std::span<const Relation> relations,
                                            double tolerance_s) {
  if (!(tolerance_s >= 0.0)) core::fail<std::invalid_argument>("tolerance_s must be >= 0 (s)");
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    if (std::isnan(trajectory[i].t))
      core::fail<std::invalid_argument>("trajectory: pose " + std::to_string(i) +
                                        " has a NaN time");
    if (i > 0 && trajectory[i].t < trajectory[i - 1].t)
      core::fail<std::invalid_argument>("trajectory: not sorted by time at pose " +
                                        std::to_string(i));
  }
  std::vector<RelationResult> out;
  out.reserve(relations.size());
  for (const Relation& relation : relations) {
    RelationResult r{relation};
    const std::optional<core::Pose2> a = pose_near(trajectory, relation.t1, tolerance_s);
    const std::optional<core::Pose2> b =
        a ? pose_near(trajectory, relation.t2, tolerance_s) : std::nullopt;
    if (a && b) {
      const core::Pose2 estimated = core::relative(*a, *b);
      const core::Pose2 e = core::relative(relation.motion, estimated);  // motion^-1 * estimated
      r.matched = true;
      r.trans_error = std::hypot(e.x, e.y);
      r.rot_error_deg = std::abs(core::wrap_angle(e.theta)) * 180.0 / std::numbers::pi;
    }
    out.push_back(r);
  }
  return out;
}

RelationError summarize_relations(std::span<const RelationResult> results) {
  RelationError r;
  std::vector<double> trans, rot, trans_sq, rot_sq;
  for (const RelationResult& result : results) {
    if (!result.matched) {
      ++r.unmatched;
      continue;
    }
    const double t = result.trans_error, deg = result.rot_error_deg;
    trans.push_back(t);
    rot.push_back(deg);
    trans_sq.push_back(t * t);
    rot_sq.push_back(deg * deg);
    ++r.matched;
    if (result.off()) ++r.off;
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
  r.trans_median = lower_median(trans);
  r.rot_median_deg = lower_median(rot);
  return r;
}

RelationError score_relations(std::span<const TimedPose> trajectory,
                              std::span<const Relation> relations, double tolerance_s) {
  return summarize_relations(relation_errors(trajectory, relations, tolerance_s));
}

std::vector<RelationStretch> worst_stretches(std::span<const RelationResult> results) {
  std::vector<const RelationResult*> matched;
  for (const RelationResult& r : results)
    if (r.matched) matched.push_back(&r);
  std::stable_sort(matched.begin(), matched.end(),
                   [](const RelationResult* a, const RelationResult* b) {
                     return a->relation.t1 < b->relation.t1;
                   });
  std::vector<RelationStretch> stretches;
  for (std::size_t i = 0; i < matched.size();) {
    if (!matched[i]->off()) {
      ++i;
      continue;
    }
    // From this off relation to the last off one before more than kStretchGap good ones.
    std::size_t last = i;
    for (std::size_t j = i + 1; j < matched.size() && j - last <= kStretchGap + 1; ++j)
      if (matched[j]->off()) last = j;
    RelationStretch s;
    s.t1_first = matched[i]->relation.t1;
    s.t1_last = matched[last]->relation.t1;
    s.t2_min = s.t2_max = matched[i]->relation.t2;
    for (std::size_t k = i; k <= last; ++k) {
      const RelationResult& r = *matched[k];
      ++s.relations;
      if (r.off()) ++s.off;
      s.t2_min = std::min(s.t2_min, r.relation.t2);
      s.t2_max = std::max(s.t2_max, r.relation.t2);
      s.trans_max = std::max(s.trans_max, r.trans_error);
      s.rot_max_deg = std::max(s.rot_max_deg, r.rot_error_deg);
    }
    stretches.push_back(s);
    i = last + 1;
  }
  std::stable_sort(stretches.begin(), stretches.end(),
                   [](const RelationStretch& a, const RelationStretch& b) {
                     return a.off != b.off ? a.off > b.off : a.trans_max > b.trans_max;
                   });
  return stretches;
}

}  // namespace intgrid::slam
