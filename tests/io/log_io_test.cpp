// Log readers and writer on small logs written by the tests themselves.
#include "intgrid/io/log_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "test_support.hpp"

using namespace intgrid::core;

using namespace intgrid::io;

namespace intgrid {
namespace {

using test::expect_input_error;
using test::TempDir;
using ::testing::HasSubstr;

constexpr double kPi = std::numbers::pi;

// ODOM on line 1, a 3-beam scan on line 2.
constexpr const char* kOdometryLine = "ODOM 0.5 0.25 0.1 100.25\n";
constexpr const char* kScanLine =
    "RLASER 3 -1.5 1.5 80 1.0 2.0 3.0 0.5 0.25 0.1 0.78 0.05 0.02 100.5\n";

std::string scan_line_with(const std::string& field_values) {
  return "RLASER " + field_values + "\n";
}

TEST(IntgridLog, ReadsEveryScanAndOdometryField) {
  const TempDir dir;
  const auto file = dir.write("small.log", std::string(kOdometryLine) + kScanLine);
  const Log log = read_intgrid_log(file);

  ASSERT_EQ(log.odometry.size(), 1u);
  EXPECT_EQ(log.odometry[0].t, 100.25);
  EXPECT_EQ(log.odometry[0].pose.x, 0.5);
  EXPECT_EQ(log.odometry[0].pose.y, 0.25);
  EXPECT_EQ(log.odometry[0].pose.theta, 0.1);

  ASSERT_EQ(log.scans.size(), 1u);
  const Scan& scan = log.scans[0];
  EXPECT_EQ(scan.t, 100.5);
  EXPECT_EQ(scan.angle0, -1.5);
  EXPECT_EQ(scan.dangle, 1.5);
  EXPECT_EQ(scan.max_range, 80.0);
  EXPECT_EQ(scan.ranges, (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_EQ(scan.robot.x, 0.5);
  EXPECT_EQ(scan.robot.y, 0.25);
  EXPECT_EQ(scan.robot.theta, 0.1);
  EXPECT_EQ(scan.sensor_mount.x, 0.78);
  EXPECT_EQ(scan.sensor_mount.y, 0.05);
  EXPECT_EQ(scan.sensor_mount.theta, 0.02);
}

TEST(IntgridLog, TruncatedScanNamesFirstMissingRange) {
  const TempDir dir;
  const auto file = dir.write("truncated.log",
                              std::string(kOdometryLine) + scan_line_with("3 -1.5 1.5 80 1.0 2.0"));
  const std::string message = expect_input_error([&] { read_intgrid_log(file); }, file, 2, "r_2");
  EXPECT_THAT(message, HasSubstr("missing"));
}

TEST(IntgridLog, TruncatedScanNamesMissingTime) {
  const TempDir dir;
  const auto file =
      dir.write("no_time.log", scan_line_with("3 -1.5 1.5 80 1.0 2.0 3.0 0.5 0.25 0.1 0.78 0 0"));
  expect_input_error([&] { read_intgrid_log(file); }, file, 1, "t");
}

TEST(IntgridLog, UnparsableRangeNamesBeamAndToken) {
  const TempDir dir;
  const auto file = dir.write(
      "bad_number.log",
      std::string(kScanLine) + scan_line_with("3 -1.5 1.5 80 1.0 2.x 3.0 0 0 0 0.78 0 0 101"));
  const std::string message = expect_input_error([&] { read_intgrid_log(file); }, file, 2, "r_1");
  EXPECT_THAT(message, HasSubstr("\"2.x\""));
}

TEST(IntgridLog, ExtraTrailingFieldIsAnError) {
  const TempDir dir;
  const auto file =
      dir.write("extra.log", scan_line_with("3 -1.5 1.5 80 1.0 2.0 3.0 0 0 0 0.78 0 0 100.5 7 8"));
  const std::string message =
      expect_input_error([&] { read_intgrid_log(file); }, file, 1, "RLASER");
  EXPECT_THAT(message, HasSubstr("2 unexpected field(s) after t"));
}

TEST(IntgridLog, BeamCountMustBeASanePositiveInteger) {
  const TempDir dir;
  for (const std::string count : {"0", "-3", "3.5", "abc", "100001"}) {
    SCOPED_TRACE("n = " + count);
    const auto file = dir.write("count.log", scan_line_with(count + " -1.5 1.5 80 1 2 3"));
    expect_input_error([&] { read_intgrid_log(file); }, file, 1, "n");
  }
}

TEST(IntgridLog, MaxRangeMustBeFiniteAndPositive) {
  const TempDir dir;
  for (const std::string max_range : {"0", "-1", "nan", "inf"}) {
    SCOPED_TRACE("maxrange = " + max_range);
    const auto file = dir.write(
        "maxrange.log", scan_line_with("3 -1.5 1.5 " + max_range + " 1 2 3 0 0 0 0.78 0 0 100.5"));
    expect_input_error([&] { read_intgrid_log(file); }, file, 1, "maxrange");
  }
}

TEST(IntgridLog, AngleStepMustBeFinite) {
  const TempDir dir;
  const auto file =
      dir.write("dangle.log", scan_line_with("3 -1.5 nan 80 1 2 3 0 0 0 0.78 0 0 100.5"));
  expect_input_error([&] { read_intgrid_log(file); }, file, 1, "dangle");
}

TEST(IntgridLog, PoseAndTimeMustBeFinite) {
  const TempDir dir;
  const auto nan_heading =
      dir.write("theta.log", scan_line_with("3 -1.5 1.5 80 1 2 3 0 0 nan 0.78 0 0 100.5"));
  expect_input_error([&] { read_intgrid_log(nan_heading); }, nan_heading, 1, "theta");

  const auto infinite_mount =
      dir.write("stheta.log", scan_line_with("3 -1.5 1.5 80 1 2 3 0 0 0 0.78 0 -inf 100.5"));
  expect_input_error([&] { read_intgrid_log(infinite_mount); }, infinite_mount, 1, "stheta");

  const auto infinite_time = dir.write("t.log", std::string(kScanLine) + "ODOM 0 0 0 inf\n");
  expect_input_error([&] { read_intgrid_log(infinite_time); }, infinite_time, 2, "t");
}

TEST(IntgridLog, UnknownRecordTypeIsAnError) {
  const TempDir dir;
  const auto file = dir.write("unknown.log", std::string(kScanLine) + "LASER 1 2 3\n");
  const std::string message =
      expect_input_error([&] { read_intgrid_log(file); }, file, 2, "record type");
  EXPECT_THAT(message, HasSubstr("\"LASER\""));
}

TEST(IntgridLog, EmptyFileHoldsNoScans) {
  const TempDir dir;
  const auto file = dir.write("empty.log", "");
  const std::string message = expect_input_error([&] { read_log(file); }, file, 0, "file");
  EXPECT_THAT(message, HasSubstr("holds no scans"));
}

TEST(IntgridLog, OdometryOnlyHoldsNoScans) {
  const TempDir dir;
  const auto file = dir.write("odometry_only.log", kOdometryLine);
  const std::string message = expect_input_error([&] { read_log(file); }, file, 0, "file");
  EXPECT_THAT(message, HasSubstr("holds no scans"));
}

TEST(LogIo, MissingFileIsAnInputError) {
  const TempDir dir;
  const auto file = dir / "absent.log";
  const std::string message = expect_input_error([&] { read_log(file); }, file, 0, "file");
  EXPECT_EQ(message, "cannot open: No such file or directory");
}

TEST(IntgridLog, InvalidRangesAreKeptAsWritten) {
  const TempDir dir;
  const auto file =
      dir.write("invalid_ranges.log",
                scan_line_with("7 -1.5 0.5 80 nan -1 0 80 -nan inf 1e9 0 0 0 0.78 0 0 100.5"));
  const Log log = read_intgrid_log(file);
  const std::vector<double>& ranges = log.scans.at(0).ranges;
  ASSERT_EQ(ranges.size(), 7u);
  EXPECT_TRUE(std::isnan(ranges[0]));
  EXPECT_EQ(ranges[1], -1.0);
  EXPECT_EQ(ranges[2], 0.0);
  EXPECT_EQ(ranges[3], 80.0);
  EXPECT_TRUE(std::isnan(ranges[4]));
  EXPECT_TRUE(std::signbit(ranges[4]));
  EXPECT_EQ(ranges[5], INFINITY);
  EXPECT_EQ(ranges[6], 1e9);
}

TEST(IntgridLog, CrlfLinesParse) {
  const TempDir dir;
  const auto file =
      dir.write("crlf.log",
                "ODOM 0.5 0.25 0.1 100.25\r\n"
                "RLASER 3 -1.5 1.5 80 1.0 2.0 3.0 0.5 0.25 0.1 0.78 0.05 0.02 100.5\r\n");
  const Log log = read_log(file);
  ASSERT_EQ(log.scans.size(), 1u);
  EXPECT_EQ(log.scans[0].t, 100.5);
  EXPECT_EQ(log.odometry.at(0).t, 100.25);
}

TEST(IntgridLog, CommentAndBlankLinesKeepTheirLineNumbers) {
  const TempDir dir;
  const auto file = dir.write(
      "comments.log", "# a comment\n\n   \n" + std::string(kScanLine) + "ODOM 0 0 zero 101\n");
  expect_input_error([&] { read_log(file); }, file, 5, "theta");
}

// ---- CARMEN ----

// n ranges of 1.5 m, except beam 0 at 2.0 m.
std::string carmen_ranges(int count) {
  std::string ranges = " 2.0";
  for (int i = 1; i < count; ++i) ranges += " 1.5";
  return ranges;
}

// Odometry heading pi/2 at (1, 2); the laser 0.1 m ahead of it, turned the same way.
std::string carmen_sample(int beam_count) {
  return "# CARMEN Logfile\n"
         "PARAM robot_front_laser_max 50.0 nohost 0.0\n"
         "ODOM 1 2 1.5707963267948966 0.3 0.0 0.0 1000.5 myhost 0.01\n"
         "FLASER " +
         std::to_string(beam_count) + carmen_ranges(beam_count) +
         " 1 2.1 1.5707963267948966 1 2 1.5707963267948966 1001.25 myhost 0.02\n"
         "SYNC 1001.3 myhost 0.03\n"
         "PARAM robot_rear_laser_max 50.0 nohost 0.0\n";
}

TEST(CarmenLog, ReadsFlaserAndOdometry) {
  const TempDir dir;
  const auto file = dir.write("intel.clf", carmen_sample(181));
  SkippedRecords skipped;
  const Log log = read_log(file, &skipped);

  ASSERT_EQ(log.odometry.size(), 1u);
  EXPECT_EQ(log.odometry[0].t, 1000.5);
  EXPECT_EQ(log.odometry[0].pose.x, 1.0);
  EXPECT_EQ(log.odometry[0].pose.y, 2.0);

  ASSERT_EQ(log.scans.size(), 1u);
  const Scan& scan = log.scans[0];
  EXPECT_EQ(scan.t, 1001.25);
  EXPECT_EQ(scan.robot.x, 1.0);
  EXPECT_EQ(scan.robot.y, 2.0);
  EXPECT_DOUBLE_EQ(scan.robot.theta, kPi / 2);
  EXPECT_NEAR(scan.sensor_mount.x, 0.1, 1e-12);
  EXPECT_NEAR(scan.sensor_mount.y, 0.0, 1e-12);
  EXPECT_NEAR(scan.sensor_mount.theta, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(scan.angle0, -kPi / 2);
  EXPECT_DOUBLE_EQ(scan.dangle, kPi / 180);
  EXPECT_DOUBLE_EQ(scan.bearing(180), kPi / 2);
  EXPECT_EQ(scan.max_range, 80.0);
  ASSERT_EQ(scan.ranges.size(), 181u);
  EXPECT_EQ(scan.ranges[0], 2.0);
  EXPECT_EQ(scan.ranges[180], 1.5);

  EXPECT_EQ(skipped, (SkippedRecords{{"PARAM", 2}, {"SYNC", 1}}));
}

TEST(CarmenLog, EvenBeamCountLeavesOutTheLastBearing) {
  const TempDir dir;
  const auto file = dir.write("even.clf", carmen_sample(180));
  const Scan scan = read_carmen_log(file).scans.at(0);
  EXPECT_DOUBLE_EQ(scan.dangle, kPi / 180);
  EXPECT_DOUBLE_EQ(scan.bearing(179), kPi / 2 - kPi / 180);
}

TEST(CarmenLog, MaxRangeIsAParameter) {
  const TempDir dir;
  const auto file = dir.write("short_range.clf", carmen_sample(361));
  const Scan scan = read_carmen_log(file, 30.0).scans.at(0);
  EXPECT_EQ(scan.max_range, 30.0);
  EXPECT_DOUBLE_EQ(scan.dangle, kPi / 360);
  EXPECT_THROW(read_carmen_log(file, 0.0), std::invalid_argument);
}

TEST(CarmenLog, OdometryFirstIsRecognisedByItsFieldCount) {
  const TempDir dir;
  const std::string sample = carmen_sample(181);
  const auto file = dir.write("odometry_first.clf", sample.substr(sample.find("ODOM")));
  EXPECT_EQ(read_log(file).scans.size(), 1u);
}

TEST(CarmenLog, TruncatedFlaserNamesMissingField) {
  const TempDir dir;
  std::string sample = carmen_sample(181);
  sample.replace(sample.find(" myhost 0.02"), 12, " myhost");
  const auto file = dir.write("truncated.clf", sample);
  expect_input_error([&] { read_log(file); }, file, 4, "logger_timestamp");
}

TEST(CarmenLog, FileWithoutFlaserHoldsNoScans) {
  const TempDir dir;
  const auto file = dir.write("params.clf", "PARAM robot_front_laser_max 50.0 nohost 0.0\n");
  const std::string message = expect_input_error([&] { read_log(file); }, file, 0, "file");
  EXPECT_THAT(message, HasSubstr("no FLASER records"));
}

// ---- writing ----

void expect_same_double(double actual, double expected) {
  if (std::isnan(expected)) {
    EXPECT_TRUE(std::isnan(actual));
  } else {
    EXPECT_EQ(actual, expected);
  }
}

void expect_same_pose(const Pose2& actual, const Pose2& expected) {
  EXPECT_EQ(actual.x, expected.x);
  EXPECT_EQ(actual.y, expected.y);
  EXPECT_EQ(actual.theta, expected.theta);
}

Log awkward_log() {
  Log log;
  Scan scan;
  scan.t = 1137834225.7133861;
  scan.robot = {1.0 / 3.0, -2e-7, 3.14159265358979};
  scan.sensor_mount = {0.78, 0.0, -0.1};
  scan.angle0 = -std::numbers::pi / 2;
  scan.dangle = std::numbers::pi / 360;
  scan.max_range = 81.91;
  scan.ranges = {0.1, NAN, -1.0, 0.0, 1e-300, 123.456789012345};
  log.scans.push_back(scan);
  scan.t += 0.25;
  log.scans.push_back(scan);
  log.odometry.push_back({scan.t, {0.5, 0.6, 0.7}});  // ties with the second scan
  log.odometry.push_back({scan.t + 1.0, {0.8, 0.9, 1.0}});
  return log;
}

TEST(LogIo, WriteThenReadRoundTripsExactly) {
  const TempDir dir;
  const Log written = awkward_log();
  const auto file = dir / "round_trip.log";
  write_log(file, written);
  const Log read = read_log(file);

  ASSERT_EQ(read.scans.size(), written.scans.size());
  for (std::size_t i = 0; i < written.scans.size(); ++i) {
    const Scan& a = read.scans[i];
    const Scan& b = written.scans[i];
    EXPECT_EQ(a.t, b.t);
    expect_same_pose(a.robot, b.robot);
    expect_same_pose(a.sensor_mount, b.sensor_mount);
    EXPECT_EQ(a.angle0, b.angle0);
    EXPECT_EQ(a.dangle, b.dangle);
    EXPECT_EQ(a.max_range, b.max_range);
    ASSERT_EQ(a.ranges.size(), b.ranges.size());
    for (std::size_t k = 0; k < b.ranges.size(); ++k) expect_same_double(a.ranges[k], b.ranges[k]);
  }
  ASSERT_EQ(read.odometry.size(), written.odometry.size());
  for (std::size_t i = 0; i < written.odometry.size(); ++i) {
    EXPECT_EQ(read.odometry[i].t, written.odometry[i].t);
    expect_same_pose(read.odometry[i].pose, written.odometry[i].pose);
  }
  EXPECT_EQ(dir.entry_count(), 1u) << "no temporary file is left behind";
}

TEST(LogIo, WriteMergesRecordsInTimeOrderOdometryFirst) {
  const TempDir dir;
  const auto file = dir / "order.log";
  write_log(file, awkward_log());
  const std::string text = test::read_bytes(file);
  std::vector<std::string> keywords;
  for (std::size_t start = 0; start < text.size(); start = text.find('\n', start) + 1) {
    keywords.push_back(text.substr(start, text.find(' ', start) - start));
  }
  EXPECT_EQ(keywords, (std::vector<std::string>{"RLASER", "ODOM", "RLASER", "ODOM"}));
}

TEST(LogIo, WriteRejectsScanWithoutRanges) {
  const TempDir dir;
  Log log = awkward_log();
  log.scans[1].ranges.clear();
  EXPECT_THROW(write_log(dir / "bad.log", log), std::invalid_argument);
  EXPECT_EQ(dir.entry_count(), 0u);
}

}  // namespace
}  // namespace intgrid
