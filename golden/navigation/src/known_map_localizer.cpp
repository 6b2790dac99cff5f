#include "intgrid/navigation/known_map_localizer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "intgrid/core/failure.hpp"

namespace intgrid::navigation {

const char* state_name(LocalizerState state) {
  switch (state) {
    case LocalizerState::locating:
      return "locating";
    case LocalizerState::tracking:
      return "tracking";
    case LocalizerState::lost:
      return "lost";
    case LocalizerState::recovering:
      return "recovering";
  }
  return "?";
}

void check_known_map_localizer_config(const KnownMapLocalizerConfig& c) {
  slam::check_submap_slam_config(c.tracking);
  localization::check_global_loc_config(c.global);
  localization::check_pose_search_options(c.search);
  localization::check_sequence_options(c.sequence);
  core::require_field(
      std::isfinite(c.lost.fit_share) && c.lost.fit_share > 0.0 && c.lost.fit_share < 1.0,
      "lost.fit_share", "must be in (0, 1)");
  core::require_field(c.lost.scans >= 1 && c.lost.scans <= 1000, "lost.scans", "must be 1..1000");
  core::require_field(c.lost.recent >= 1 && c.lost.recent <= 100000, "lost.recent",
                      "must be 1..100000");
  core::require_field(std::isfinite(c.verify_every) && c.verify_every > 0.0, "verify_every",
                      "must be finite and > 0");
  core::require_field(c.contest_scans >= 1 && c.contest_scans <= 1000, "contest_scans",
                      "must be 1..1000");
}

KnownMapLocalizer::KnownMapLocalizer(const core::ProbabilityGrid& map, double occupied_threshold,
                                     double free_threshold, const KnownMapLocalizerConfig& config,
                                     core::Arithmetic arithmetic,
                                     std::optional<core::Pose2> initial)
    : config_((check_known_map_localizer_config(config), config)),
      arithmetic_(arithmetic),
      indices_(slam::map_indices(map, config.tracking)),
      pose_grid_map_(map, occupied_threshold, free_threshold, config.global) {
  if (initial) start_tracking(*initial, true);
}

KnownMapLocalizer::~KnownMapLocalizer() = default;

void KnownMapLocalizer::start_tracking(const core::Pose2& pose, bool verified) {
  tracker_.emplace(config_.tracking, arithmetic_, indices_, pose);
  search_.reset();
  check_.reset();
  challenger_.reset();
  misfits_ = 0;
  was_tracking_ = true;
  verified_ = verified;
  travel_ = 0.0;
}

bool KnownMapLocalizer::same_place(const core::Pose2& a, const core::Pose2& b) const {
  return std::hypot(a.x - b.x, a.y - b.y) < config_.search.separation &&
         std::abs(core::wrap_angle(a.theta - b.theta)) < config_.search.separation_heading;
}

void KnownMapLocalizer::verify(const core::Scan& scan, LocalizerStep& step) {
  if (previous_odometry_) {
    const core::Pose2 d = core::relative(*previous_odometry_, scan.robot);
    travel_ += std::hypot(d.x, d.y);
  }
  previous_odometry_ = scan.robot;
  if (challenger_) {  // the contest goes on: both poses tracked, their scans' evidence summed
    const slam::MapFix fix = challenger_->localize(scan);
    contest(fix, step.fix);
    if (contested_ < config_.contest_scans) return;
    if (challenger_evidence_ > incumbent_evidence_) {
      tracker_.swap(challenger_);
      step.fix = fix;
      step.pose = fix.pose;
      step.refixed = true;
    }
    verified_ = true;
    step.verified = true;
    challenger_.reset();
    travel_ = 0.0;
    return;
  }
  // A check begins once the robot has moved a step since the fix (the scans it then fuses are
  // not the fix's own view again), and every verify_every metres after.
  const double begin_after = verified_ ? config_.verify_every : config_.sequence.step_position;
  if (!check_ && travel_ >= begin_after)
    check_.emplace(pose_grid_map_, config_.search, config_.sequence);
  if (!check_) return;
  const std::optional<localization::PoseSearchResult> found = check_->offer(scan);
  if (!found || found->ambiguous) {
    if (check_->done()) {  // no unambiguous answer: the next check decides
      check_.reset();
      travel_ = 0.0;
    }
    return;
  }
  check_.reset();
  travel_ = 0.0;
  const core::Pose2 answer = found->estimate.robot;
  if (same_place(answer, *step.pose)) {  // the global answer confirms the tracking
    verified_ = true;
    step.verified = true;
    return;
  }
  // Elsewhere: a contest. The answer is tracked beside the pose for contest_scans matched scans;
  // the one whose scans fit the map better (their summed evidence) goes on.
  challenger_.emplace(config_.tracking, arithmetic_, indices_, answer);
  challenger_evidence_ = incumbent_evidence_ = 0.0;
  contested_ = 0;
  contest(challenger_->localize(scan), step.fix);
}

void KnownMapLocalizer::contest(const slam::MapFix& challenger, const slam::MapFix& incumbent) {
  if (!challenger.matched || !incumbent.matched) return;
  challenger_evidence_ += challenger.evidence;
  incumbent_evidence_ += incumbent.evidence;
  ++contested_;
}

bool KnownMapLocalizer::fits(double fit) {
  if (static_cast<int>(fits_.size()) >= config_.lost.scans) {
    std::vector<double> recent(fits_.begin(), fits_.end());
    const auto middle = recent.begin() + static_cast<std::ptrdiff_t>(recent.size() / 2);
    std::nth_element(recent.begin(), middle, recent.end());
    if (fit < config_.lost.fit_share * *middle) return false;
  }
  fits_.push_back(fit);
  if (static_cast<int>(fits_.size()) > config_.lost.recent) fits_.pop_front();
  return true;
}

LocalizerStep KnownMapLocalizer::localize(const core::Scan& scan) {
  LocalizerStep step;
  if (tracker_) {
    step.fix = tracker_->localize(scan);
    step.state = LocalizerState::tracking;
    step.pose = step.fix.pose;
    step.verified = verified_;
    if (step.fix.matched) misfits_ = fits(step.fix.fit) ? 0 : misfits_ + 1;
    if (misfits_ >= config_.lost.scans) {
      step.state = LocalizerState::lost;
      step.pose.reset();
      step.verified = false;
      tracker_.reset();
      check_.reset();
      challenger_.reset();
      return step;
    }
    verify(scan, step);
    return step;
  }
  step.state = was_tracking_ ? LocalizerState::recovering : LocalizerState::locating;
  if (!search_) search_.emplace(pose_grid_map_, config_.search, config_.sequence);
  const std::optional<localization::PoseSearchResult> found = search_->offer(scan);
  step.fused_scans = search_->scans();
  if (found && !found->ambiguous) {
    start_tracking(found->estimate.robot, false);
    previous_odometry_ = scan.robot;
    step.fix = tracker_->localize(scan);
    step.state = LocalizerState::tracking;
    step.pose = step.fix.pose;
    if (step.fix.matched) fits(step.fix.fit);
  } else if (search_->done()) {
    search_.reset();  // max_scans fused, still ambiguous: start again from the next scan
  }
  return step;
}

}  // namespace intgrid::navigation
