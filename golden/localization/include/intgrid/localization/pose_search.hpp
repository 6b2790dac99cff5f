// The pose grid's search for the places a scan fits: hypotheses, their verification and
// refinement, and the answer with its ambiguity.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "intgrid/core/types.hpp"
#include "intgrid/localization/global_loc_config.hpp"
#include "intgrid/localization/localization_map.hpp"
#include "intgrid/localization/range_reading.hpp"

namespace intgrid::localization {

// Every pose cell's score after all readings, and what made it.
struct PoseScores {
  GlobalMethod method = GlobalMethod::pose_grid;
  std::vector<std::int32_t> index_sum;  // pose_grid: S_eps sums; non-candidates hold INT32_MIN
  std::vector<double> posterior;        // baselines: normalized; non-candidates hold 0
};

struct GlobalEstimate {
  core::Pose2 sensor;  // the pose grid's estimate: best cell (ties: their mean)
  core::Pose2 robot;   // the sensor pose stepped back by the mounting pose
  double score = 0.0;  // pose_grid: the best index sum; baselines: the best cell's posterior
  std::size_t ties = 1;
  std::size_t readings_used = 0;     // the usable readings (finite, positive, below max_range)
  std::size_t readings_dropped = 0;  // baselines: readings that zeroed every candidate
};

// One place a scan fits: the best pose of its neighbourhood, at least `separation` (or
// `separation_heading`) from every better hypothesis.
struct PoseHypothesis {
  // refine_levels > 0: the refined pose; else the mean of the pose cells tied at `score` around
  // the hypothesis's cell.
  core::Pose2 sensor;
  core::Pose2 robot;                 // the sensor pose stepped back by the mounting pose
  std::int32_t screening_score = 0;  // index sum of the screening readings at its screening cell
  std::int32_t score = 0;            // index sum of the verification readings at `sensor`
  std::size_t ties = 1;              // poses tied at `score` among those its last step compared
};

struct PoseSearchOptions {
  int hypotheses = 1;  // reported, best first
  // The best screening hypotheses verified: refined on the map's own cells (refine_levels > 0)
  // or rescored over their neighbourhood on the lattice (one cell and one heading bin around),
  // with the verification readings. The screening's coarse claims cannot tell apart places that
  // look alike at 5.6 degrees and 0.2 m; sharper claims and the whole scan often can.
  int verified = 32;
  double separation = 1.0;             // m: two hypotheses differ by at least this in position,
  double separation_heading = 0.5236;  // or this in heading (rad, 30 degrees)
  // The answer is ambiguous when a second hypothesis scores within this many S_eps levels per
  // verification reading of a scan (their mean over the fused scans when tracking) of the best:
  // a user should wait for another scan.
  double ambiguity_levels = 0.5;
  int threads = 1;  // the screening's headings and the hypotheses split across threads; any
                    // count, the same result
};

struct PoseSearchResult {
  GlobalEstimate estimate;                 // the best hypothesis
  std::vector<PoseHypothesis> hypotheses;  // best first, at most max(hypotheses, 1)
  bool ambiguous = false;
  std::size_t verification_readings = 0;  // over every fused scan
};

// Throws std::invalid_argument naming the field.
void check_pose_search_options(const PoseSearchOptions& options);

// The pose grid's search: every candidate pose cell scored with the screening readings (the
// candidate form), the best cells grouped into hypotheses `separation` apart, the best
// `verified` of them verified with the verification readings (refined, see GlobalLocConfig's
// refine_levels), ranked by that score. Readings that are not usable are dropped, as
// localize_global does. `scores`, when given, receives the screening scores in the PoseScores
// layout.
PoseSearchResult search_pose_grid(const LocalizationMap& map,
                                  std::span<const RangeReading> screening,
                                  std::span<const RangeReading> verification,
                                  const core::Pose2& sensor_mount, const PoseSearchOptions& options,
                                  PoseScores* scores = nullptr);

// The refinement from a given sensor pose instead of a screening cell: the pose within the first
// level's reach of it (0.3 m and one heading bin at the defaults) that the readings fit best, and
// the verification readings' score there (screening_score 0). It checks a reference: when a
// reference pose, so refined, scores below the search's answer, the map agrees with the answer,
// not with the reference. Throws std::invalid_argument when refine_levels is 0 or the pose is
// not finite; score is INT32_MIN when no pose there is free.
PoseHypothesis refine_pose(const LocalizationMap& map, std::span<const RangeReading> screening,
                           std::span<const RangeReading> verification, const core::Pose2& sensor,
                           const core::Pose2& sensor_mount);

}  // namespace intgrid::localization
