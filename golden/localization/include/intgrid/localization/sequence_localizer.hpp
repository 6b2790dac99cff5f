// Global localization from a log's scans as they come: the pose grid over time (PoseTracker) fed
// the scans that odometry puts a step apart, until its answer is unambiguous. `intgrid globloc
// --track` runs it from each selected scan; the localization in a known map (navigation) runs it
// to find the robot at the start and again when it is lost.
#pragma once

#include <cstddef>
#include <numbers>
#include <optional>

#include "intgrid/core/types.hpp"
#include "intgrid/localization/localization_map.hpp"
#include "intgrid/localization/pose_search.hpp"
#include "intgrid/localization/pose_tracker.hpp"

namespace intgrid::localization {

struct SequenceOptions {
  int beams = 60;              // screening readings a scan, spread over it (0: all)
  int verify_beams = 0;        // verification readings a scan (0: all, the whole scan)
  std::size_t max_scans = 10;  // scans fused at most (1..1000)
  // A scan is fused once odometry has moved the sensor this far, or turned it this much, since
  // the scan fused before: a scan from the same place adds its noise, not another view. Set by
  // hand before any measurement (docs/results.md, global localization).
  double step_position = 0.5;                             // m
  double step_heading = 15.0 * std::numbers::pi / 180.0;  // rad
};

// Throws std::invalid_argument naming the field (step_position, step_heading).
void check_sequence_options(const SequenceOptions& options);

class SequenceLocalizer {
 public:
  // The map outlives the localizer. Throws std::invalid_argument naming the field: bad options,
  // or PoseTracker's (max_scans, memory_limit).
  SequenceLocalizer(const LocalizationMap& map, const PoseSearchOptions& search,
                    const SequenceOptions& options);

  // Offers the next scan. The first scan with a usable reading is fused, then each one odometry
  // puts a step from the scan fused before; the answer from every scan fused so far is returned
  // for a fused scan, nothing for a skipped one (too close to the last fused, no usable reading,
  // or done()).
  std::optional<PoseSearchResult> offer(const core::Scan& scan);
  // An unambiguous answer was returned, or max_scans are fused.
  bool done() const { return done_; }
  std::size_t scans() const { return tracker_.scans(); }
  // The fused grid's sums (PoseTracker::fused_scores). Requires a fused scan.
  PoseScores fused_scores() const { return tracker_.fused_scores(); }

 private:
  const LocalizationMap* map_;
  SequenceOptions options_;
  PoseTracker tracker_;
  std::optional<core::Pose2> last_sensor_;  // the odometry's sensor pose at the last fused scan
  bool done_ = false;
};

}  // namespace intgrid::localization
