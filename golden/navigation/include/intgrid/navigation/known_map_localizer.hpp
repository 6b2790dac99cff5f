// Localization in a known map from no prior, scan after scan: the robot found by global
// localization (SequenceLocalizer: the pose grid over the scans as they come, until its answer is
// unambiguous), then tracked (slam::MapLocalizer: the submaps SLAM's localization event against
// the map, integer on the per-scan path); when the scans stop fitting the map, the robot is
// declared lost and found again the same way. The criterion reads the map and the scans only:
// each scan's fit (the share of its hits within a cell of an occupied map cell at the tracked
// pose) against the fits of the scans tracked before it.
#pragma once

#include <cstddef>
#include <deque>
#include <memory>
#include <optional>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/localization/global_loc_config.hpp"
#include "intgrid/localization/localization_map.hpp"
#include "intgrid/localization/pose_search.hpp"
#include "intgrid/localization/sequence_localizer.hpp"
#include "intgrid/slam/map_localizer.hpp"
#include "intgrid/slam/submap_slam.hpp"

namespace intgrid::navigation {

enum class LocalizerState {
  locating,    // no pose yet: global localization fusing the scans
  tracking,    // the pose tracked in the map
  lost,        // this scan ended the tracking: the scans stopped fitting the map
  recovering,  // global localization again, since the robot was lost
};
const char* state_name(LocalizerState state);

struct KnownMapLocalizerConfig {
  slam::SubmapSlamConfig tracking;         // MapLocalizer's; its cell must be the map's
  localization::GlobalLocConfig global;    // the pose grid's
  localization::PoseSearchOptions search;  // threads: 0 is every core
  localization::SequenceOptions sequence;  // how the scans are fused to find the robot
  struct Lost {
    // A matched scan fits when its fit reaches this share of the median fit of the last
    // `recent` scans that fitted; `scans` matched scans in a row that do not fit: lost. Chosen
    // on the bundled log (docs/results.md, localization): tracked in its map, its fits dip to
    // 0.36 of their median for 7 scans; carried off to another place, they stay under 0.14.
    double fit_share = 0.25;
    int scans = 3;
    int recent = 50;
  } lost;
  // While tracking, global localization checks the pose once odometry has moved the robot this
  // far (m) since the last check, and a step after a fix of its own (sequence.step_position): an
  // unambiguous answer within search.separation of the tracked pose confirms it; one elsewhere
  // is tracked beside it for contest_scans matched scans, and the pose whose scans fit the map
  // better (their summed evidence) goes on. Set by hand from the cost: a check is one to a few
  // global localizations (about 65 ms each in the benchmark logs' maps).
  double verify_every = 10.0;
  int contest_scans = 10;
};

// Throws std::invalid_argument naming the field (lost.fit_share, ...; tracking.*, global.*,
// search.*, sequence.* as their own checks name them).
void check_known_map_localizer_config(const KnownMapLocalizerConfig& config);

struct LocalizerStep {
  LocalizerState state = LocalizerState::locating;
  std::optional<core::Pose2> pose;  // the robot's in the map's frame; none while not tracking
  slam::MapFix fix;                 // tracking and lost: the match in the map
  std::size_t fused_scans = 0;      // locating and recovering: the scans fused so far
  // Tracking: the pose was given (initial) or confirmed by a global answer since the last fix.
  bool verified = false;
  bool refixed = false;  // a global answer won a contest against the tracked pose at this scan
};

class KnownMapLocalizer {
 public:
  // map: probabilities in [0, 1] (NaN unknown), with its free and occupied thresholds (a ROS
  // map's); initial: the robot's pose at the first scan, if known (tracking starts there). The
  // map outlives the localizer. Throws std::invalid_argument naming the field.
  KnownMapLocalizer(const core::ProbabilityGrid& map, double occupied_threshold,
                    double free_threshold, const KnownMapLocalizerConfig& config,
                    core::Arithmetic arithmetic, std::optional<core::Pose2> initial);
  ~KnownMapLocalizer();

  // The next scan. Throws std::invalid_argument for a scan the tracking would refuse.
  LocalizerStep localize(const core::Scan& scan);

 private:
  void start_tracking(const core::Pose2& pose, bool verified);
  bool fits(double fit);
  bool same_place(const core::Pose2& a, const core::Pose2& b) const;
  void verify(const core::Scan& scan, LocalizerStep& step);
  // One scan of the contest: both fixes' evidence summed when both were matched.
  void contest(const slam::MapFix& challenger, const slam::MapFix& incumbent);

  KnownMapLocalizerConfig config_;
  core::Arithmetic arithmetic_;
  core::Grid<std::int8_t> indices_;  // the map in the tracking's S_eps indices
  localization::LocalizationMap pose_grid_map_;
  std::optional<localization::SequenceLocalizer> search_;
  std::optional<slam::MapLocalizer> tracker_;
  // While tracking: the check in progress; a global answer tracked beside the pose, with both
  // sums of evidence over the contest's matched scans; the odometry's travel since the last
  // check.
  std::optional<localization::SequenceLocalizer> check_;
  std::optional<slam::MapLocalizer> challenger_;
  double challenger_evidence_ = 0.0, incumbent_evidence_ = 0.0;
  int contested_ = 0;
  std::optional<core::Pose2> previous_odometry_;
  double travel_ = 0.0;
  bool verified_ = false;
  bool was_tracking_ = false;
  std::deque<double> fits_;  // the recent fitting scans' fits
  int misfits_ = 0;          // matched scans in a row that did not fit
};

}  // namespace intgrid::navigation
