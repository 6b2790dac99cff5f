// The submap SLAM on 400-scan segments of the Freiburg benchmark's Intel and ACES logs
// (benchmark_segment.hpp): short enough to run under the sanitizers (a few seconds in Release),
// long enough to reach every part of the SLAM: several submaps grown as the robot explores, loop
// closures by branch and bound, and graph optimizations. The 2000-scan segments are
// submap_slam_benchmark_test.cpp's (label long).
//
// Intel's segment is scans 1100 to 1499, not the first 400: from the log's 1357th scan on, a
// submap that grew by the range instead of the ISM's whole reach wrote out of bounds (17e8725;
// ASan found it only on the 2000-scan segment). Putting the growth back to z / c + 1 in
// LocalGrid::insert makes this segment's run abort under ASan (a heap-buffer-overflow in
// fuse_into, in 6 s); the first 400 scans, and 1000 to 1399, pass with it.
#include <gtest/gtest.h>

#include <filesystem>

#include "benchmark_segment.hpp"
#include "data_dir.hpp"

namespace intgrid::slam {
namespace {

using test::present;
using test::run_segment;
using test::Segment;

constexpr std::size_t kShortSegmentScans = 400;
constexpr std::size_t kIntelSegmentFirstScan = 1100;

// Every stage ran in both arithmetics, and the rotation, which the odometry gets wrong first,
// is better than the odometry's.
void expect_every_stage_ran_and_rotation_improved(const Segment& s) {
  ASSERT_GT(s.odometry.matched, 20u);
  for (const SubmapSlamStats& stats : {s.stats_int, s.stats_double}) {
    EXPECT_EQ(stats.scans, kShortSegmentScans);
    EXPECT_GE(stats.submaps, 3u);
    EXPECT_GT(stats.loop_closures, 0u);
    EXPECT_GT(stats.optimizations, 0u);
  }
  // The memory estimate's figure for the loop search's pyramid cache (submaps taken as large as
  // the map) bounds what the cache held.
  EXPECT_LE(static_cast<double>(s.stats_int.peak_pyramid_bytes),
            pyramid_cache_bytes(SubmapSlamConfig{}, core::Arithmetic::integer, s.map_cells_int));
  EXPECT_LE(
      static_cast<double>(s.stats_double.peak_pyramid_bytes),
      pyramid_cache_bytes(SubmapSlamConfig{}, core::Arithmetic::floating, s.map_cells_double));
  EXPECT_GT(s.stats_int.peak_pyramid_bytes, 0u);
  for (const RelationError& e : {s.slam_int, s.slam_double}) {
    EXPECT_EQ(e.matched, s.odometry.matched);
    EXPECT_LT(e.rot_mean_deg, s.odometry.rot_mean_deg);
    EXPECT_LT(e.trans_mean, 0.1);
  }
}

TEST(SubmapSlamData, IntelShortSegmentRunsEveryStageAndImprovesTheRotation) {
  if (!present("intel"))
    GTEST_SKIP() << intgrid::test::absent(intgrid::test::benchmark_dir() / "intel.clf");
  expect_every_stage_ran_and_rotation_improved(
      run_segment("intel", kIntelSegmentFirstScan, kShortSegmentScans));
}

TEST(SubmapSlamData, AcesShortSegmentRunsEveryStageAndImprovesTheRotation) {
  if (!present("aces"))
    GTEST_SKIP() << intgrid::test::absent(intgrid::test::benchmark_dir() / "aces.clf");
  expect_every_stage_ran_and_rotation_improved(run_segment("aces", 0, kShortSegmentScans));
}

// The bundled Telecom log (361 beams) and the same scans with every other beam (181): a sensor
// of half the beams scores half as much in its submaps, which the prior and the closure
// threshold are weighed against (E and the submaps' own scores, docs/algorithms.md section 10).
// With both against the full score instead, the 181-beam run closed no loop and ended 0.95 m
// off (0.17 m at 361).
TEST(SubmapSlamData, TelecomAtHalfTheBeamsKeepsItsAccuracy) {
  const std::filesystem::path data = intgrid::test::data_dir();
  const core::Log log = io::read_log(data / "malaga_telecom_loop.log");
  const std::vector<TimedPose> reference =
      scan_poses(io::read_log(data / "malaga_telecom_loop_reference.log"));
  core::Log half = log;
  for (core::Scan& s : half.scans) {
    std::vector<double> every_other;
    for (std::size_t b = 0; b < s.ranges.size(); b += 2) every_other.push_back(s.ranges[b]);
    s.ranges = std::move(every_other);
    s.dangle *= 2;
  }
  SubmapSlamStats full_stats, half_stats;
  const double full =
      absolute_trajectory_error(
          run_submap_slam(log, SubmapSlamConfig{}, core::Arithmetic::integer, &full_stats)
              .trajectory,
          reference)
          .rmse;
  const double halved =
      absolute_trajectory_error(
          run_submap_slam(half, SubmapSlamConfig{}, core::Arithmetic::integer, &half_stats)
              .trajectory,
          reference)
          .rmse;
  std::printf("Telecom: ATE %.3f m at 361 beams, %.3f m at 181\n", full, halved);
  EXPECT_LT(full, 0.2);
  EXPECT_LT(halved, 0.2);
  EXPECT_GT(half_stats.loop_closures, 0u);
}

}  // namespace
}  // namespace intgrid::slam
