// The log readers on the bundled Malaga logs and, when present, the Freiburg benchmark logs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <string>

#include "data_dir.hpp"
#include "intgrid/io/log_io.hpp"
#include "test_support.hpp"

using namespace intgrid::core;

using namespace intgrid::io;

namespace intgrid {
namespace {

const std::filesystem::path kDataDir = test::data_dir();
const std::filesystem::path kLoopLog = kDataDir / "malaga_telecom_loop.log";
const std::filesystem::path kReferenceLog = kDataDir / "malaga_telecom_loop_reference.log";

TEST(BundledLog, LoopLogHasItsScansAndOdometry) {
  const Log log = read_log(kLoopLog);
  EXPECT_EQ(log.scans.size(), 225u);
  EXPECT_EQ(log.odometry.size(), 224u);
}

TEST(BundledLog, FirstScanOfTheLoopLog) {
  const Scan scan = read_log(kLoopLog).scans.at(0);
  EXPECT_EQ(scan.ranges.size(), 361u);
  EXPECT_EQ(scan.angle0, -1.570796);
  EXPECT_EQ(scan.dangle, 0.008727);
  EXPECT_EQ(scan.max_range, 80.0);
  EXPECT_EQ(scan.t, 1137834225.713386);
  EXPECT_EQ(scan.ranges.front(), 1.69);
  EXPECT_EQ(scan.ranges.back(), 1.55);
  EXPECT_EQ(scan.robot.x, 0.0);
  EXPECT_EQ(scan.robot.theta, 0.0);
  EXPECT_EQ(scan.sensor_mount.x, 0.78);
  EXPECT_EQ(scan.sensor_mount.y, 0.0);
  EXPECT_EQ(scan.sensor_mount.theta, 0.0);
}

TEST(BundledLog, ScansAndOdometryAreInTimeOrder) {
  const Log log = read_log(kLoopLog);
  EXPECT_TRUE(std::is_sorted(log.scans.begin(), log.scans.end(),
                             [](const Scan& a, const Scan& b) { return a.t < b.t; }));
  EXPECT_TRUE(
      std::is_sorted(log.odometry.begin(), log.odometry.end(),
                     [](const OdometryRecord& a, const OdometryRecord& b) { return a.t < b.t; }));
  EXPECT_EQ(log.scans.back().t, 1137834284.788331);
}

TEST(BundledLog, ReferenceScansAreASubsetOfTheLoop) {
  const Log reference = read_log(kReferenceLog);
  ASSERT_EQ(reference.scans.size(), 99u);
  EXPECT_TRUE(reference.odometry.empty());
  std::set<double> loop_times;
  for (const Scan& scan : read_log(kLoopLog).scans) loop_times.insert(scan.t);
  for (const Scan& scan : reference.scans) EXPECT_EQ(loop_times.count(scan.t), 1u) << scan.t;
}

TEST(BundledLog, WriteThenReadIsExact) {
  const test::TempDir dir;
  const Log original = read_log(kLoopLog);
  write_log(dir / "copy.log", original);
  const Log copy = read_log(dir / "copy.log");
  ASSERT_EQ(copy.scans.size(), original.scans.size());
  ASSERT_EQ(copy.odometry.size(), original.odometry.size());
  for (std::size_t i = 0; i < original.scans.size(); ++i) {
    EXPECT_EQ(copy.scans[i].t, original.scans[i].t);
    EXPECT_EQ(copy.scans[i].ranges, original.scans[i].ranges);
    EXPECT_EQ(copy.scans[i].robot.theta, original.scans[i].robot.theta);
  }
  for (std::size_t i = 0; i < original.odometry.size(); ++i) {
    EXPECT_EQ(copy.odometry[i].t, original.odometry[i].t);
    EXPECT_EQ(copy.odometry[i].pose.x, original.odometry[i].pose.x);
  }
}

// ---- the Freiburg SLAM benchmark (not bundled) ----

using test::absent;
using test::benchmark_dir;

void expect_one_sensor(const Log& log, double max_range) {
  for (const Scan& scan : log.scans) {
    ASSERT_EQ(scan.ranges.size(), 180u);
    ASSERT_EQ(scan.max_range, max_range);
    ASSERT_EQ(scan.sensor_mount, Pose2{});
  }
  EXPECT_TRUE(std::is_sorted(log.scans.begin(), log.scans.end(),
                             [](const Scan& a, const Scan& b) { return a.t < b.t; }));
  EXPECT_TRUE(
      std::is_sorted(log.odometry.begin(), log.odometry.end(),
                     [](const OdometryRecord& a, const OdometryRecord& b) { return a.t < b.t; }));
}

TEST(BenchmarkLog, IntelReadsEveryScanSorted) {
  const std::filesystem::path file = benchmark_dir() / "intel.clf";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << absent(file);
  const Log log = read_log(file);
  EXPECT_EQ(log.scans.size(), 13631u);
  EXPECT_EQ(log.odometry.size(), 26915u);
  // 81.83 is intel.clf's saturation value (68,313 readings; none other above 26.37 m).
  expect_one_sensor(log, 81.83);
  // 631 scans are earlier than the one before (by at most 0.9 s): sorting moves 2,591.
  EXPECT_EQ(log.reordered_scans, 2591u);
}

TEST(BenchmarkLog, AcesReadsEveryScanInOrder) {
  const std::filesystem::path file = benchmark_dir() / "aces.clf";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << absent(file);
  const Log log = read_log(file);
  EXPECT_EQ(log.scans.size(), 7374u);
  EXPECT_EQ(log.odometry.size(), 7375u);
  expect_one_sensor(log, 50.0);  // 50.00 written 11,139 times
  EXPECT_EQ(log.reordered_scans, 0u);
}

}  // namespace
}  // namespace intgrid
