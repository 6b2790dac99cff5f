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
};

// Throws std::invalid_argument naming the field (lost.fit_share, ...; tracking.*, global.*,
// search.*, sequence.* as their own checks name them).
void check_known_map_localizer_config(const KnownMapLocalizerConfig& config);

struct LocalizerStep {
  LocalizerState state = LocalizerState::locating;
  std::optional<core::Pose2> pose;  // the robot's in the map's frame; none while not tracking
  slam::MapFix fix;                 // tracking and lost: the match in the map
  std::size_t fused_scans = 0;      // locating and recovering: the scans fused so far
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
  void start_tracking(const core::Pose2& pose);
  bool fits(double fit);

  KnownMapLocalizerConfig config_;
  core::Arithmetic arithmetic_;
  core::Grid<std::int8_t> indices_;  // the map in the tracking's S_eps indices
  localization::LocalizationMap pose_grid_map_;
  std::optional<localization::SequenceLocalizer> search_;
  std::optional<slam::MapLocalizer> tracker_;
  bool was_tracking_ = false;
  std::deque<double> fits_;  // the recent fitting scans' fits
  int misfits_ = 0;          // matched scans in a row that did not fit
};

}  // namespace intgrid::navigation
