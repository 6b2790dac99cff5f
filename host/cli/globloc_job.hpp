// The `globloc` job: every selected scan of a log localized on its own in a known map, from no
// prior (docs/algorithms.md 7), written as poses, a picture of the first scan's pose grid and the
// run's metrics, scored against a reference log when one is given.
#pragma once

#include <cstddef>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "intgrid/localization/global_localization.hpp"
#include "intgrid/localization/sequence_localizer.hpp"

namespace intgrid::cli {

// A reference pose counts as found when the estimate is this close in position and in heading.
inline constexpr double kGlobLocPositionTolerance = 0.5;                             // m
inline constexpr double kGlobLocHeadingTolerance = 15.0 * std::numbers::pi / 180.0;  // rad

struct GlobLocJobOptions {
  std::filesystem::path map;
  std::filesystem::path log;
  std::filesystem::path out;
  std::optional<std::filesystem::path> reference;             // a log: its scans' robot poses
  std::optional<std::filesystem::path> reference_trajectory;  // t x y theta (slam's trajectory)
  double position_tolerance = kGlobLocPositionTolerance;      // m: found within this
  double heading_tolerance = kGlobLocHeadingTolerance;        // rad: and this
  std::string scans;      // "FIRST:LAST", 0-based and inclusive; empty: every scan
  std::size_t every = 1;  // of the selected scans, localize every every-th
  localization::GlobalMethod method = localization::GlobalMethod::pose_grid;
  localization::GlobalLocConfig config;
  localization::PoseSearchOptions search;  // threads: 0 is every core
  // Each scan's readings (beams, verify_beams: the latter the pose grid's alone) and, with
  // `track`, localization from a sequence (pog only): from each selected scan, up to `track`
  // scans fused (0: each scan on its own) as SequenceLocalizer fuses them; its max_scans is
  // `track`'s.
  localization::SequenceOptions sequence;
  std::size_t track = 0;
  bool progress = true;
};

struct GlobLocScan {
  std::size_t index = 0;        // in the log; with --track, the last scan fused (the answer's)
  std::size_t first_index = 0;  // the scan the localization started from
  std::size_t scans_fused = 1;  // with --track: how many scans it took
  double t = 0.0;               // of scan `index`
  double first_t = 0.0;         // of scan `first_index`
  std::size_t readings = 0;
  localization::GlobalEstimate estimate;
  std::vector<localization::PoseHypothesis> hypotheses;  // the pose grid's, best first
  bool ambiguous = false;  // the pose grid: a second hypothesis nearly as good
  double seconds = 0.0;
  std::optional<core::Pose2> reference;  // the reference log's pose at the same time
  bool found = false;                    // within the tolerances of the reference pose
  // A pose grid's miss, refined: the score of the reference pose refined as the search refines
  // its hypotheses (refine_pose), single scans only. Below the answer's: the map disagrees with
  // the reference there.
  std::optional<std::int32_t> reference_score;
  // A miss: the share of the scan's readings whose endpoints lie within 1.5 map cells of an
  // occupied cell, at the answer and at the reference pose (no localizer's score enters it).
  std::optional<std::pair<double, double>> endpoint_fit;
};

struct GlobLocJobResult {
  std::vector<GlobLocScan> scans;  // the localized scans, in log order
  std::size_t skipped_scans = 0;   // selected scans without a usable reading
  double map_seconds = 0.0;        // preparing the map (LocalizationMap)
  double seconds = 0.0;            // localizing, all scans
  std::size_t matched = 0;         // scans with a reference pose
  std::size_t found = 0;           // of those, within the tolerances
  std::size_t ambiguous = 0;       // scans whose answer is ambiguous
  nlohmann::json metrics;          // what metrics.json holds
};

// Every method, in the order of the tables and CSVs.
inline constexpr localization::GlobalMethod kGlobalMethods[] = {
    localization::GlobalMethod::pose_grid, localization::GlobalMethod::markov,
    localization::GlobalMethod::markov_mixture, localization::GlobalMethod::likelihood_field};

// Name of a method on the command line (pog, markov, markov-mixture, likelihood-field) and in
// tables.
const char* global_method_name(localization::GlobalMethod method);

// Reads the map, the log (and the reference), localizes, writes DIR/poses.txt, pose_grid.png and
// metrics.json, each atomically. Bad inputs are InputErrors naming file and field.
GlobLocJobResult run_globloc_job(const GlobLocJobOptions& options);

}  // namespace intgrid::cli
