// Global localization from a sequence of scans (the multi-measurement pose grid over time).
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "intgrid/core/types.hpp"
#include "intgrid/localization/localization_map.hpp"
#include "intgrid/localization/pose_search.hpp"
#include "intgrid/localization/range_reading.hpp"

namespace intgrid::localization {

// Global localization from a sequence of scans: the multi-measurement pose grid over time,
// motion-compensated by odometry. Each scan's screening sums are kept; the fused grid scores a
// pose cell at the latest scan with the sum, over the fused scans, of each scan's sums at the
// pose cell where odometry puts the sensor then (its heading slice shifted by the rotated
// translation and the turn, each rounded once from that scan's motion, so rounding does not
// accumulate; a place off the candidates adds nothing). Hypotheses, their refinement and the
// ambiguity test then run as search_pose_grid's, each pose scored over every fused scan.
struct ScanEvidence;
class PoseTracker {
 public:
  // Throws std::invalid_argument naming the field: bad options, max_scans outside 1..1000, or
  // memory_limit when max_scans screening grids beside the map's tables would exceed the map's
  // limit (refused before anything is allocated).
  PoseTracker(const LocalizationMap& map, const PoseSearchOptions& options, std::size_t max_scans);
  ~PoseTracker();
  PoseTracker(PoseTracker&&) noexcept;
  PoseTracker& operator=(PoseTracker&&) noexcept;

  // Fuses one scan. `motion`: the sensor's pose at this scan in the frame of the sensor at the
  // scan added before (from odometry; ignored for the first). Throws std::invalid_argument when
  // max_scans are fused already or the motion is not finite.
  void add_scan(std::span<const RangeReading> screening, std::span<const RangeReading> verification,
                const core::Pose2& motion);
  std::size_t scans() const { return evidence_.size(); }
  std::size_t max_scans() const { return max_scans_; }
  // Hypotheses for the sensor at the latest scan, from every fused scan. Requires a scan.
  PoseSearchResult search(const core::Pose2& sensor_mount) const;
  // The fused grid's sums in the PoseScores layout (non-candidates INT32_MIN). Requires a scan.
  PoseScores fused_scores() const;

 private:
  const LocalizationMap* map_;
  PoseSearchOptions options_;
  std::size_t max_scans_;
  std::vector<std::unique_ptr<ScanEvidence>> evidence_;
  std::vector<core::Pose2> sensor_;  // each scan's sensor pose in the first scan's frame
};

}  // namespace intgrid::localization
