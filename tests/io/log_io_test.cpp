// Log readers and writer on small logs written by the tests themselves.
#include "intgrid/io/log_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "intgrid/io/text_io.hpp"
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

// Values past the readers' plausibility limits are refused naming their field; values at a
// limit are read. Scan line: n angle0 dangle maxrange r_0..r_2 x y theta sx sy stheta t.
TEST(IntgridLog, ImplausiblePosesMountsRangesAndAnglesAreRefused) {
  const TempDir dir;
  const auto line = [](const std::string& angle0, const std::string& max_range,
                       const std::string& x, const std::string& sx) {
    return scan_line_with("3 " + angle0 + " 0.1 " + max_range + " 1 2 3 " + x + " 0 0 " + sx +
                          " 0 0 100.5");
  };
  struct Case {
    std::string text, field;
  };
  for (const Case& c : {Case{line("-1.5", "80", "1e300", "0"), "x"},
                        Case{line("-1.5", "80", "-1000000.5", "0"), "x"},
                        Case{line("-1.5", "80", "0", "6.4e38"), "sx"},
                        Case{line("-1.5", "80", "0", "100.01"), "sx"},
                        Case{line("-1.5", "10000.5", "0", "0"), "maxrange"},
                        Case{line("7", "80", "0", "0"), "angle0"},
                        Case{std::string(kScanLine) + "ODOM 2e6 0 0 101\n", "x"}}) {
    SCOPED_TRACE(c.text);
    const auto file = dir.write("implausible.log", c.text);
    const std::size_t line_number = c.text.find("ODOM") == std::string::npos ? 1 : 2;
    const std::string message =
        expect_input_error([&] { read_intgrid_log(file); }, file, line_number, c.field);
    EXPECT_THAT(message, HasSubstr("past the plausible"));
  }
  const auto at_limits =
      dir.write("limits.log", line("-6.283185307179586", "10000", "-1000000", "100"));
  const Log log = read_intgrid_log(at_limits);
  ASSERT_EQ(log.scans.size(), 1u);
  EXPECT_EQ(log.scans[0].robot.x, -1e6);
  EXPECT_EQ(log.scans[0].sensor_mount.x, 100.0);
  EXPECT_EQ(log.scans[0].max_range, 1e4);
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
  EXPECT_EQ(scan.max_range, 50.0) << "PARAM robot_front_laser_max";
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

TEST(CarmenLog, FileWithoutLaserRecordsHoldsNoScans) {
  const TempDir dir;
  const auto file = dir.write("params.clf",
                              "PARAM robot_front_laser_max 50.0 nohost 0.0\n"
                              "ODOM 1 2 0.5 0.3 0.0 0.0 1000.5 myhost 0.01\n");
  const std::string message = expect_input_error([&] { read_log(file); }, file, 0, "file");
  EXPECT_THAT(message, HasSubstr("no FLASER or ROBOTLASER1 records"));
}

TEST(CarmenLog, BenchmarkBeamCountsSpan180Degrees) {
  const TempDir dir;
  for (const int count : {180, 181, 360, 361}) {
    SCOPED_TRACE(count);
    const auto file = dir.write("beams.clf", carmen_sample(count));
    const Scan scan = read_log(file).scans.at(0);
    ASSERT_EQ(scan.ranges.size(), static_cast<std::size_t>(count));
    EXPECT_DOUBLE_EQ(scan.angle0, -kPi / 2);
    const double last = count % 2 == 1 ? kPi / 2 : kPi / 2 - scan.dangle;
    EXPECT_NEAR(scan.bearing(scan.ranges.size() - 1), last, 1e-12);
    EXPECT_NEAR(scan.dangle, count >= 360 ? kPi / 360 : kPi / 180, 1e-15);
  }
}

// ---- CARMEN: real lines ----

// intel.clf (Freiburg benchmark, Intel Research Lab) lines 10-15: PARAM, PARAM, ODOM, FLASER,
// ODOM, FLASER.
constexpr const char* kIntelHead =
    R"(PARAM robot_frontlaser_offset 0.0 nohost 0
)"
    R"(PARAM robot_rearlaser_offset 0.0 nohost 0
)"
    R"(ODOM 0.000000 0.000000 -0.002458 0.000000 0.000000 0.000000 976052857.337284 nohost 0.000000
)"
    R"(FLASER 180 1.07 1.07 1.08 1.08 1.08 1.08 1.08 1.08 1.08 1.09 1.09 1.09 1.09 1.09 1.10 1.10 1.11 1.11 1.12 1.11 1.12 1.13 1.13 1.14 1.16 1.17 1.17 1.17 1.19 1.20 1.21 1.22 1.23 1.25 1.27 1.28 1.30 1.30 1.31 1.33 1.35 1.37 1.39 1.41 1.43 1.46 1.49 1.51 1.53 1.57 1.59 1.63 1.65 1.69 1.72 1.77 1.81 1.86 1.90 1.94 2.00 2.06 2.12 2.18 2.24 2.32 2.41 2.49 2.58 2.68 2.80 2.92 3.06 3.21 3.37 3.57 3.78 4.01 4.29 4.60 4.95 5.37 5.86 11.16 10.82 10.78 10.71 81.83 11.58 81.83 17.12 81.83 81.83 9.18 81.83 81.83 81.83 81.83 81.83 81.83 81.83 81.83 81.83 81.83 81.83 7.56 7.61 4.12 3.85 3.62 3.43 3.26 3.12 2.98 2.85 2.73 2.62 2.51 2.42 2.34 2.27 2.19 2.14 2.07 2.01 1.95 1.92 1.86 1.82 1.78 1.72 1.69 1.65 1.62 1.58 1.55 1.52 1.50 1.47 1.44 1.44 1.40 1.37 1.35 1.34 1.32 1.30 1.29 1.27 1.24 1.23 1.23 1.21 1.20 1.19 1.18 1.16 1.15 1.15 1.13 1.13 1.12 1.12 1.10 1.11 1.10 1.11 1.09 1.08 1.08 1.07 1.07 1.06 1.06 1.05 1.06 1.05 1.05 1.05 1.05 0.000000 0.000000 -0.002458 0.000000 0.000000 -0.002458 976052857.337530 nohost 0.000246
)"
    R"(ODOM 0.000000 0.000000 -0.002458 0.000000 0.000000 0.000000 976052857.337916 nohost 0.000632
)"
    R"(FLASER 180 1.08 1.07 1.08 1.08 1.07 1.08 1.08 1.08 1.09 1.09 1.09 1.09 1.09 1.09 1.09 1.10 1.11 1.11 1.12 1.11 1.12 1.13 1.13 1.15 1.15 1.17 1.17 1.17 1.19 1.20 1.21 1.22 1.23 1.25 1.26 1.28 1.30 1.29 1.31 1.33 1.35 1.37 1.39 1.41 1.43 1.46 1.48 1.51 1.53 1.57 1.59 1.62 1.65 1.69 1.72 1.77 1.81 1.86 1.90 1.94 2.00 2.06 2.12 2.19 2.24 2.32 2.41 2.49 2.58 2.68 2.79 2.92 3.05 3.21 3.37 3.56 3.79 4.01 4.29 4.59 4.95 5.36 5.86 11.16 10.82 10.78 10.70 14.40 11.58 81.83 17.12 81.83 81.83 9.18 81.83 81.83 81.83 81.83 81.83 81.83 81.83 81.83 81.83 81.83 81.83 7.56 7.60 4.12 3.86 3.63 3.43 3.25 3.11 2.98 2.84 2.71 2.61 2.51 2.42 2.34 2.27 2.19 2.12 2.06 2.02 1.96 1.93 1.85 1.81 1.78 1.72 1.70 1.65 1.61 1.58 1.55 1.53 1.50 1.47 1.44 1.42 1.39 1.37 1.35 1.34 1.32 1.30 1.29 1.27 1.24 1.23 1.23 1.22 1.20 1.20 1.18 1.16 1.16 1.14 1.13 1.13 1.12 1.12 1.10 1.10 1.10 1.09 1.09 1.08 1.08 1.08 1.07 1.07 1.06 1.06 1.06 1.05 1.05 1.05 1.05 0.000000 0.000000 -0.002458 0.000000 0.000000 -0.002458 976052857.348896 nohost 0.011612
)";

// intel.clf lines 85-90: the FLASER of line 90 is 5.9 ms earlier than that of line 87, the
// ODOM of line 89 0.28 s earlier than that of line 88.
constexpr const char* kIntelOutOfOrder =
    R"(ODOM 0.000000 0.000000 -0.002458 0.000000 0.000000 0.000000 976052861.840671 nohost 4.503387
)"
    R"(ODOM 0.000000 0.000000 -0.002458 0.000000 0.000000 0.000000 976052861.941960 nohost 4.604676
)"
    R"(FLASER 180 1.08 1.08 1.08 1.08 1.09 1.09 1.08 1.08 1.08 1.09 1.09 1.09 1.09 1.10 1.10 1.10 1.11 1.11 1.12 1.12 1.13 1.13 1.15 1.15 1.16 1.17 1.17 1.18 1.19 1.20 1.20 1.22 1.23 1.24 1.27 1.28 1.29 1.31 1.33 1.34 1.35 1.37 1.39 1.41 1.44 1.45 1.48 1.51 1.53 1.56 1.59 1.61 1.65 1.69 1.72 1.76 1.81 1.85 1.90 1.95 2.01 2.07 2.13 2.18 2.26 2.32 2.40 2.49 2.57 2.68 2.80 2.92 3.06 3.20 3.36 3.55 3.78 4.02 4.29 4.61 4.95 5.37 5.86 11.18 10.83 10.79 10.72 14.39 11.59 81.83 17.13 81.83 3.50 3.56 3.63 3.54 3.55 81.83 81.83 81.83 81.83 81.83 81.83 81.83 81.83 7.56 7.61 4.13 3.85 3.62 3.44 3.26 3.12 2.99 2.85 2.73 2.62 2.52 2.43 2.34 2.27 2.20 2.13 2.07 2.02 1.96 1.92 1.88 1.82 1.77 1.74 1.69 1.65 1.62 1.58 1.55 1.52 1.49 1.46 1.43 1.42 1.39 1.36 1.35 1.33 1.30 1.29 1.27 1.26 1.24 1.23 1.22 1.21 1.20 1.19 1.18 1.17 1.15 1.14 1.14 1.13 1.12 1.12 1.12 1.11 1.10 1.10 1.08 1.08 1.08 1.07 1.07 1.06 1.06 1.05 1.05 1.05 1.05 1.06 1.06 0.000000 0.000000 -0.002458 0.000000 0.000000 -0.002458 976052862.228180 nohost 4.890896
)"
    R"(ODOM 0.000000 0.000000 -0.002458 0.000000 0.000000 0.000000 976052862.423500 nohost 5.086216
)"
    R"(ODOM 0.000000 0.000000 -0.002458 0.000000 0.000000 0.000000 976052862.139566 nohost 4.802282
)"
    R"(FLASER 180 1.08 1.08 1.08 1.08 1.09 1.08 1.08 1.08 1.08 1.09 1.09 1.09 1.09 1.10 1.10 1.10 1.11 1.11 1.11 1.12 1.13 1.13 1.14 1.15 1.17 1.17 1.17 1.18 1.19 1.20 1.21 1.22 1.23 1.25 1.26 1.28 1.29 1.31 1.32 1.33 1.35 1.37 1.39 1.41 1.43 1.45 1.48 1.51 1.53 1.56 1.59 1.61 1.65 1.69 1.72 1.76 1.81 1.85 1.90 1.95 2.01 2.07 2.12 2.18 2.26 2.32 2.40 2.49 2.57 2.68 2.80 2.91 3.06 3.20 3.36 3.56 3.78 4.02 4.29 4.61 4.95 5.37 5.86 11.18 10.83 10.79 10.72 14.40 11.57 81.83 17.13 81.83 81.83 9.19 81.83 3.60 3.58 3.64 3.96 81.83 81.83 81.83 81.83 81.83 81.83 7.56 7.60 4.12 3.86 3.64 3.43 3.26 3.12 2.99 2.85 2.73 2.62 2.52 2.43 2.35 2.27 2.19 2.13 2.08 2.02 1.96 1.91 1.88 1.83 1.77 1.73 1.70 1.65 1.62 1.58 1.55 1.52 1.49 1.47 1.44 1.42 1.39 1.36 1.34 1.33 1.31 1.29 1.27 1.26 1.24 1.24 1.22 1.21 1.19 1.18 1.18 1.17 1.15 1.14 1.14 1.13 1.12 1.12 1.12 1.11 1.11 1.10 1.09 1.09 1.08 1.07 1.07 1.06 1.07 1.05 1.06 1.05 1.05 1.05 1.06 0.000000 0.000000 -0.002458 0.000000 0.000000 -0.002458 976052862.222313 nohost 4.885029
)";

// aces.clf (Freiburg benchmark, ACES building) lines 10-17: 4 PARAM, ODOM, FLASER, ODOM, FLASER.
constexpr const char* kAcesHead =
    R"(PARAM robot_use_laser on nohost 0
)"
    R"(PARAM simulator_num_readings 180 nohost 0
)"
    R"(PARAM robot_frontlaser_offset 0.0 nohost 0
)"
    R"(PARAM robot_rearlaser_offset 0.0 nohost 0
)"
    R"(ODOM -0.000602 0.012727 -1.570796 0.000000 0.000000 0.000000 70.179699 nohost 0.000000
)"
    R"(FLASER 180 46.56 47.31 12.51 14.71 12.16 12.26 12.21 11.76 10.56 9.46 8.66 7.91 7.31 6.81 6.31 5.96 5.66 5.26 5.06 4.86 4.61 4.41 4.16 4.06 3.86 3.76 3.66 3.51 3.36 3.26 3.21 3.06 3.01 2.96 2.81 2.76 2.74 2.64 2.59 2.59 2.49 2.44 2.39 2.39 2.29 2.29 2.24 2.19 2.19 2.14 2.09 2.09 2.04 2.04 1.99 1.94 1.94 1.94 1.92 1.85 1.92 1.99 2.04 2.14 2.16 2.26 2.36 2.46 2.56 2.66 2.81 2.96 3.16 3.36 3.56 3.76 4.06 4.41 4.81 5.21 5.76 6.26 7.16 8.36 9.91 12.16 18.76 21.76 24.61 30.31 30.31 30.31 16.41 12.71 10.11 8.96 7.36 6.41 5.66 5.16 4.66 4.36 4.41 4.71 4.76 4.76 4.76 2.86 2.71 2.56 2.46 2.36 2.26 2.16 2.06 1.96 1.89 1.84 1.84 1.84 1.89 1.89 1.94 1.94 1.99 2.04 2.04 2.04 2.09 2.14 2.14 2.19 2.24 2.29 2.29 2.34 2.39 2.41 2.51 2.46 2.31 2.31 2.36 2.36 2.41 2.41 2.51 2.61 3.16 3.26 6.91 4.61 50.00 50.00 6.16 6.11 6.06 6.01 6.01 5.91 6.01 5.86 5.81 5.81 5.76 5.76 5.71 5.76 5.61 3.31 5.56 5.51 5.56 5.56 5.56 3.01 6.46 6.36 4.46 6.36 -0.000602 0.012727 -1.570796 -0.000602 0.012727 -1.570796 70.289900 nohost 0.110201
)"
    R"(ODOM -0.000602 0.012727 -1.570796 0.000000 0.000000 0.000000 70.309700 nohost 0.130001
)"
    R"(FLASER 180 46.51 47.26 12.56 14.76 12.16 12.26 12.21 11.76 10.51 9.46 8.61 7.91 7.26 6.81 6.31 6.01 5.66 5.31 5.06 4.81 4.61 4.36 4.21 4.01 3.86 3.76 3.61 3.51 3.36 3.31 3.16 3.11 3.01 2.91 2.86 2.76 2.74 2.69 2.59 2.54 2.49 2.44 2.39 2.34 2.29 2.29 2.24 2.19 2.19 2.14 2.09 2.09 2.04 2.04 1.99 1.99 1.94 1.94 1.92 1.95 1.92 1.94 2.04 2.14 2.16 2.26 2.36 2.46 2.56 2.66 2.81 2.96 3.16 3.36 3.51 3.76 4.06 4.41 4.81 5.26 5.76 6.21 7.16 8.31 9.91 12.11 18.76 21.71 24.61 30.31 30.31 30.36 16.41 12.71 10.11 8.91 7.31 6.36 5.71 5.16 4.66 4.36 4.36 4.71 4.71 4.76 4.81 2.86 2.66 2.56 2.46 2.31 2.21 2.16 2.06 2.01 1.91 1.84 1.84 1.89 1.89 1.94 1.94 1.99 1.99 2.04 2.04 2.04 2.09 2.09 2.14 2.24 2.24 2.24 2.29 2.34 2.44 2.44 2.46 2.41 2.31 2.31 2.36 2.36 2.46 2.41 2.51 2.56 3.11 3.31 6.91 4.61 50.00 50.00 6.16 6.11 6.06 6.06 5.96 5.91 6.01 5.86 5.81 5.81 5.76 5.76 5.71 5.71 5.61 3.26 5.56 5.56 5.51 5.51 5.56 3.01 6.46 6.36 4.41 6.36 -0.000602 0.012727 -1.570796 -0.000602 0.012727 -1.570796 70.410399 nohost 0.230700
)";

// The first two lines of csail.log (MIT CSAIL building, ROBOTLASER1 records, no ODOM), as found
// in github.com/kiran-mohan/SLAM-Algorithms-Octave at 4_Gridmapping/data/csail.log.
constexpr const char* kCsailRobotLaser =
    R"(ROBOTLASER1 0 -1.570796 3.150447 0.008727 80.000000 0.010000 0 361 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 1.64 1.64 1.61 1.61 1.61 1.62 1.68 1.62 3.05 3.03 3.17 3.15 3.28 3.26 3.41 3.40 3.56 3.55 3.56 3.57 3.51 3.52 3.48 3.49 3.46 3.46 3.43 3.43 3.41 3.41 3.39 3.40 3.37 3.37 2.78 3.01 3.32 3.09 5.90 5.85 6.37 6.37 6.25 6.25 6.39 6.28 6.80 6.89 6.54 6.85 6.21 6.21 6.20 6.20 6.19 6.19 6.21 6.21 4.21 4.30 4.19 4.19 4.18 4.19 4.20 4.19 4.19 4.19 4.19 4.20 2.52 2.56 2.49 2.49 4.21 4.20 4.21 4.21 4.22 4.23 4.23 4.23 4.24 4.24 4.25 4.25 4.27 4.27 4.28 4.29 4.29 4.30 4.32 4.32 4.34 4.34 4.36 4.37 4.38 4.39 4.42 4.42 4.44 4.45 3.04 3.04 2.53 2.53 2.63 2.51 4.53 2.79 4.56 4.56 4.72 4.72 4.82 4.79 3.04 3.04 4.91 4.91 2.66 4.96 2.63 2.64 5.06 5.06 5.09 5.08 5.22 5.19 6.89 6.91 6.44 6.47 6.34 6.36 6.22 6.23 6.05 6.08 5.82 5.83 5.74 5.75 5.67 5.68 5.67 5.66 5.67 5.68 5.57 5.58 5.48 5.48 5.38 5.39 5.30 5.31 5.22 5.23 4.47 4.48 4.42 4.44 4.36 4.36 4.29 4.30 4.24 4.25 4.19 4.20 4.13 4.14 4.09 4.09 4.04 4.05 4.00 4.00 3.96 3.96 3.92 3.92 3.88 3.89 3.85 3.86 3.81 3.82 3.78 3.78 3.75 3.75 3.70 3.70 3.68 3.68 3.65 3.66 3.63 3.63 3.60 3.61 3.59 3.59 3.57 3.57 3.54 3.55 3.53 3.53 3.51 3.52 3.53 3.53 3.92 3.91 4.00 4.00 3.98 3.99 3.97 3.97 3.97 3.97 4.46 4.46 5.43 5.43 6.22 6.19 7.66 7.63 6.07 6.07 6.21 6.20 6.08 6.07 6.14 6.14 6.26 6.34 6.19 6.24 11.84 11.84 11.87 11.88 11.58 11.57 2.65 2.65 2.62 2.62 2.63 2.63 2.61 2.61 2.69 2.70 2.83 2.83 3.44 3.45 3.23 3.23 3.25 3.25 3.21 3.22 3.20 3.21 3.18 3.18 3.15 3.15 3.13 3.13 3.10 3.11 3.09 3.08 3.05 3.05 3.05 3.05 3.03 3.03 3.02 3.02 3.00 3.00 2.99 2.99 2.97 2.97 2.97 2.96 2.96 2.96 2.95 2.94 2.94 2.94 2.94 2.94 2.93 2.93 2.92 2.92 2.93 2.93 2.92 2.92 2.92 2.92 2.14 2.12  0 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000 1134864642.914187 b21 0.430003
)"
    R"(ROBOTLASER1 0 -1.570796 3.150447 0.008727 80.000000 0.010000 0 361 4.04 4.05 4.05 4.05 4.06 4.06 4.06 4.07 4.07 4.08 4.08 4.09 4.09 4.11 4.11 4.12 4.12 4.14 4.14 4.16 4.16 2.55 2.68 2.35 2.28 4.24 4.23 4.38 4.26 4.42 4.41 4.29 4.28 4.30 4.31 4.47 4.45 2.79 2.83 4.58 4.58 2.38 2.37 4.67 2.34 4.72 4.70 4.76 4.76 4.80 4.80 4.79 4.79 4.87 4.89 6.66 6.70 6.24 6.54 6.04 6.05 5.96 6.01 5.80 5.84 5.61 5.71 5.44 5.48 5.43 5.54 5.33 5.35 5.41 5.39 5.32 5.35 5.23 5.25 5.13 5.16 5.04 5.06 4.93 4.96 4.32 4.84 4.14 4.16 4.08 4.10 4.02 4.04 3.97 3.99 3.91 3.93 3.87 3.88 3.82 3.83 3.77 3.78 3.70 3.74 3.67 3.69 3.63 3.65 3.59 3.61 3.56 3.57 3.53 3.54 3.49 3.51 3.46 3.48 3.43 3.45 3.41 3.42 3.37 3.39 3.36 3.37 3.33 3.34 3.31 3.32 3.29 3.30 3.27 3.28 3.25 3.26 3.24 3.24 3.22 3.23 3.21 3.21 3.20 3.21 3.21 3.21 3.62 3.53 3.69 3.70 3.68 3.68 3.67 3.67 3.64 3.66 4.16 4.02 5.14 5.13 6.35 6.05 6.11 7.63 5.72 5.78 5.95 5.88 5.80 5.88 5.92 5.84 5.78 5.88 5.92 6.15 11.61 11.62 11.30 11.33 11.49 11.41 11.43 11.42 11.60 11.58 2.43 81.91 2.37 2.37 2.36 10.30 2.42 2.41 2.44 2.44 2.45 2.45 3.20 3.16 3.04 3.07 3.03 3.01 3.01 3.02 2.99 3.00 2.96 2.97 2.96 2.96 2.95 2.94 2.92 2.92 2.91 2.92 2.89 2.90 2.88 2.88 2.86 2.87 2.86 2.86 2.84 2.85 2.84 2.84 2.83 2.84 2.82 2.83 2.83 2.82 2.82 2.82 2.82 2.83 2.81 2.82 2.82 2.82 2.81 2.82 2.81 2.82 2.80 2.81 2.81 2.81 2.81 2.82 2.81 2.82 2.80 2.81 2.72 2.73 2.11 2.13 2.07 2.04 2.25 2.26 2.25 2.25 2.25 2.25 2.25 2.25 2.26 2.27 2.28 2.28 2.29 2.29 1.92 1.92 1.91 1.91 1.90 1.90 1.89 1.90 1.88 1.88 1.89 1.88 1.90 1.91 2.38 2.38 2.44 2.44 2.45 2.45 2.46 2.46 2.48 2.48 2.51 2.51 2.52 2.52 2.56 2.56 2.56 2.57 81.91 2.51 2.41 2.42 2.24 2.26 2.27 2.27 2.30 2.29 2.91 2.89 2.96 2.96 2.98 2.99 3.02 3.04 81.91 81.91 81.91 81.91 81.91 81.91 81.91 81.91 2.65 2.66 81.91 81.91 3.14 3.14 3.10 3.11 3.08 3.07 3.01 3.01 2.96 2.97 2.95 2.95 2.98 2.97 3.07 3.06 3.15 3.14 81.91 81.91  0 0.319678 0.110037 0.994330 0.319678 0.110037 0.994330 0.000000 0.000000 0.000000 0.000000 0.000000 1134864643.764189 b21 1.280005
)";

TEST(CarmenLog, ReadsTheIntelHead) {
  const TempDir dir;
  const auto file = dir.write("intel_head.clf", kIntelHead);
  SkippedRecords skipped;
  const Log log = read_log(file, &skipped);

  ASSERT_EQ(log.odometry.size(), 2u);
  EXPECT_EQ(log.odometry[0].t, 976052857.337284);
  EXPECT_EQ(log.odometry[1].pose.theta, -0.002458);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.reordered_scans, 0u);
  const Scan& scan = log.scans[0];
  EXPECT_EQ(scan.t, 976052857.337530);
  EXPECT_EQ(log.scans[1].t, 976052857.348896);
  ASSERT_EQ(scan.ranges.size(), 180u);
  EXPECT_EQ(scan.ranges.front(), 1.07);
  EXPECT_DOUBLE_EQ(scan.angle0, -kPi / 2);
  EXPECT_DOUBLE_EQ(scan.dangle, kPi / 180);
  EXPECT_EQ(scan.robot, (Pose2{0.0, 0.0, -0.002458}));
  EXPECT_EQ(scan.sensor_mount, Pose2{}) << "the laser pose is the odometry pose";
  // No PARAM states the range; 81.83 is written 29 times in these two scans, nothing near it.
  EXPECT_EQ(scan.max_range, 81.83);
  EXPECT_FALSE(scan.is_valid_range(81.83));
  EXPECT_TRUE(scan.is_valid_range(26.37));
  EXPECT_EQ(skipped, (SkippedRecords{{"PARAM", 2}}));
}

TEST(CarmenLog, AcesSaturatesAtFiftyMetres) {
  const TempDir dir;
  const auto file = dir.write("aces_head.clf", kAcesHead);
  const Log log = read_log(file);
  ASSERT_EQ(log.scans.size(), 2u);
  ASSERT_EQ(log.odometry.size(), 2u);
  const Scan& scan = log.scans[0];
  EXPECT_EQ(scan.max_range, 50.0);
  EXPECT_EQ(scan.ranges[0], 46.56);
  EXPECT_TRUE(scan.is_valid_range(scan.ranges[0]));
  EXPECT_EQ(std::count(scan.ranges.begin(), scan.ranges.end(), 50.0), 2);
  EXPECT_FALSE(scan.is_valid_range(50.0));
  EXPECT_EQ(scan.robot, (Pose2{-0.000602, 0.012727, -1.570796}));
  EXPECT_EQ(scan.sensor_mount, Pose2{});
}

TEST(CarmenLog, MaxRangeParamWinsOverSaturationAndArgumentOverBoth) {
  const TempDir dir;
  const std::string head = kIntelHead;
  const auto front = dir.write("front.clf", head + "PARAM robot_front_laser_max 50.0 nohost 0\n");
  EXPECT_EQ(read_log(front).scans.at(0).max_range, 50.0);
  EXPECT_EQ(read_carmen_log(front, 20.0).scans.at(0).max_range, 20.0);

  const auto laser_module =
      dir.write("laser_module.clf", "PARAM laser_front_laser_max_range 30 nohost 0\n" + head);
  EXPECT_EQ(read_log(laser_module).scans.at(0).max_range, 30.0);

  const auto rear = dir.write("rear.clf", head + "PARAM robot_rear_laser_max 30 nohost 0\n");
  EXPECT_EQ(read_log(rear).scans.at(0).max_range, 81.83) << "the rear laser's is no FLASER's";
}

TEST(CarmenLog, WithoutParamOrSaturationTheDefaultMaxRange) {
  const TempDir dir;
  std::string sample = carmen_sample(181);
  sample.erase(sample.find("PARAM robot_front_laser_max"),
               sample.find("ODOM") - sample.find("PARAM"));
  const Scan scan = read_log(dir.write("default.clf", sample)).scans.at(0);
  EXPECT_EQ(scan.max_range, kCarmenDefaultMaxRange);
  EXPECT_FALSE(scan.is_valid_range(81.9));

  // A far wall: its largest reading repeats, but so do readings just below it.
  const auto wall = dir.write(
      "wall.clf", "FLASER 8 5.0 5.0 5.0 4.99 4.98 4.97 4.9 1.0 0 0 0 0 0 0 10.0 host 10.0\n");
  EXPECT_EQ(read_log(wall).scans.at(0).max_range, kCarmenDefaultMaxRange);

  // One value 3 times and nothing near it: a saturated short-range sensor.
  const auto saturated = dir.write(
      "saturated.clf", "FLASER 8 5.6 5.6 5.6 2.0 2.1 2.2 2.3 1.0 0 0 0 0 0 0 10.0 host 10.0\n");
  EXPECT_EQ(read_log(saturated).scans.at(0).max_range, 5.6);
}

TEST(CarmenLog, MaxRangeParamMustBePositive) {
  const TempDir dir;
  const std::string head = kIntelHead;
  const auto file = dir.write("bad_param.clf", head + "PARAM robot_front_laser_max -1 nohost 0\n");
  expect_input_error([&] { read_log(file); }, file, 7, "param_value");
}

TEST(CarmenLog, ReadsRobotLaser1) {
  const TempDir dir;
  const auto file = dir.write("csail.log", kCsailRobotLaser);
  const Log log = read_log(file);
  EXPECT_TRUE(log.odometry.empty());
  ASSERT_EQ(log.scans.size(), 2u);
  const Scan& first = log.scans[0];
  EXPECT_EQ(first.t, 1134864642.914187);
  EXPECT_EQ(first.angle0, -1.570796);
  EXPECT_EQ(first.dangle, 0.008727);
  EXPECT_EQ(first.max_range, 80.0);
  ASSERT_EQ(first.ranges.size(), 361u);
  EXPECT_EQ(first.ranges.front(), 81.91);
  EXPECT_FALSE(first.is_valid_range(81.91));
  EXPECT_EQ(first.ranges.back(), 2.12);
  EXPECT_NEAR(first.bearing(360), 1.570924, 1e-9);
  EXPECT_EQ(first.robot, Pose2{});
  const Scan& second = log.scans[1];
  EXPECT_EQ(second.t, 1134864643.764189);
  EXPECT_EQ(second.robot, (Pose2{0.319678, 0.110037, 0.994330}));
  EXPECT_EQ(second.sensor_mount, Pose2{});
}

TEST(CarmenLog, RobotLaserReadingCountMustFitFieldOfView) {
  const TempDir dir;
  std::string text = kCsailRobotLaser;
  const std::size_t second_line = text.find('\n') + 1;
  text.replace(text.find("3.150447", second_line), 8, "1.570796");  // 180 steps, 361 readings
  const auto file = dir.write("fov.log", text);
  const std::string message = expect_input_error([&] { read_log(file); }, file, 2, "num_readings");
  EXPECT_THAT(message, HasSubstr("361 readings"));
  EXPECT_THAT(message, HasSubstr("expected 180 or 181"));
}

TEST(CarmenLog, RobotLaserRemissionsAreCounted) {
  const TempDir dir;
  std::string text = kCsailRobotLaser;
  text.replace(text.find(" 2.12  0 "), 9, " 2.12  2 ");  // two remissions eat two pose fields
  const auto file = dir.write("remissions.log", text);
  const std::string message = expect_input_error([&] { read_log(file); }, file, 1, "turn_axis");
  EXPECT_THAT(message, HasSubstr("\"b21\""));
}

// ---- CARMEN: sensor mount ----

std::string flaser_line(double t, const Pose2& laser, const Pose2& odom) {
  std::string line = "FLASER 4 1.0 2.0 3.0 4.0";
  const auto append = [&line](double value) {
    line += ' ';
    line += format_number(value);
  };
  for (const Pose2& pose : {laser, odom}) {
    for (const double value : {pose.x, pose.y, pose.theta}) append(value);
  }
  append(t);
  line += " host";
  append(t);
  line += '\n';
  return line;
}

void expect_near_pose(const Pose2& actual, const Pose2& expected) {
  EXPECT_NEAR(actual.x, expected.x, 1e-9);
  EXPECT_NEAR(actual.y, expected.y, 1e-9);
  EXPECT_NEAR(actual.theta, expected.theta, 1e-9);
}

TEST(CarmenLog, ConstantLaserOffsetIsTheMountEvenAgainstTheParam) {
  const TempDir dir;
  const Pose2 mount{0.2, 0.05, 0.1};
  const Pose2 a{1.0, 2.0, 3.0}, b{-4.0, 0.5, -1.0};
  const auto file = dir.write("mounted.clf", "PARAM robot_frontlaser_offset 0.0 nohost 0\n" +
                                                 flaser_line(10.0, compose(a, mount), a) +
                                                 flaser_line(10.1, compose(b, mount), b));
  const Log log = read_log(file);
  ASSERT_EQ(log.scans.size(), 2u);
  for (const Scan& scan : log.scans) expect_near_pose(scan.sensor_mount, mount);
  EXPECT_EQ(log.scans[1].robot, b);
}

// A laser pose 6.4e38 m from the odometry in every record would be the mount: refused, as are a
// PARAM offset and a maximum range past their limits.
TEST(CarmenLog, ImplausibleMountsAndRangesAreRefused) {
  const TempDir dir;
  const Pose2 a{1.0, 2.0, 3.0}, b{-4.0, 0.5, -1.0};
  const Pose2 far{150.0, 0.0, 0.0};
  const auto far_laser = dir.write(
      "far.clf", flaser_line(10.0, compose(a, far), a) + flaser_line(10.1, compose(b, far), b));
  const std::string message =
      expect_input_error([&] { read_log(far_laser); }, far_laser, 0, "laser pose");
  EXPECT_THAT(message, HasSubstr("150 m from its robot pose"));
  const auto offset = dir.write(
      "offset.clf", "PARAM robot_frontlaser_side_offset 1e9 nohost 0\n" + flaser_line(10.0, a, a));
  expect_input_error([&] { read_log(offset); }, offset, 1, "param_value");
  const auto range = dir.write(
      "range.clf", "PARAM robot_front_laser_max 1e5 nohost 0\n" + flaser_line(10.0, a, a));
  expect_input_error([&] { read_log(range); }, range, 1, "param_value");
}

TEST(CarmenLog, ChangingLaserOffsetFallsBackToTheParamsOrZero) {
  const TempDir dir;
  // The laser pose is a corrected pose, the odometry raw: their difference drifts.
  const std::string scans = flaser_line(10.0, {1.0, 2.0, 3.0}, {1.0, 2.0, 3.0}) +
                            flaser_line(10.1, {1.5, 2.0, 3.0}, {1.2, 2.3, 2.9});
  const auto params = dir.write("params.clf",
                                "PARAM robot_frontlaser_offset 0.3 nohost 0\n"
                                "PARAM robot_frontlaser_side_offset 0.05 nohost 0\n"
                                "PARAM robot_frontlaser_angular_offset 0.1 nohost 0\n" +
                                    scans);
  for (const Scan& scan : read_log(params).scans) {
    EXPECT_EQ(scan.sensor_mount, (Pose2{0.3, 0.05, 0.1}));
  }
  const auto bare = dir.write("bare.clf", scans);
  const Log log = read_log(bare);
  ASSERT_EQ(log.scans.size(), 2u);
  for (const Scan& scan : log.scans) EXPECT_EQ(scan.sensor_mount, Pose2{});
  EXPECT_EQ(log.scans[1].robot, (Pose2{1.2, 2.3, 2.9})) << "the odometry pose is the robot's";
}

// ---- CARMEN: time order ----

TEST(CarmenLog, SlightlyEarlyRecordsAreSortedIntoPlace) {
  const TempDir dir;
  const auto file = dir.write("intel_85_90.clf", kIntelOutOfOrder);
  const Log log = read_log(file);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.reordered_scans, 2u);
  EXPECT_EQ(log.scans[0].t, 976052862.222313);
  EXPECT_EQ(log.scans[1].t, 976052862.228180);
  ASSERT_EQ(log.odometry.size(), 4u);
  const std::vector<double> times{log.odometry[0].t, log.odometry[1].t, log.odometry[2].t,
                                  log.odometry[3].t};
  EXPECT_EQ(times, (std::vector<double>{976052861.840671, 976052861.941960, 976052862.139566,
                                        976052862.423500}));
}

TEST(CarmenLog, EqualTimesKeepTheirOrder) {
  const TempDir dir;
  const auto file = dir.write("ties.clf", flaser_line(10.0, {1, 0, 0}, {1, 0, 0}) +
                                              flaser_line(10.0, {2, 0, 0}, {2, 0, 0}) +
                                              flaser_line(9.5, {3, 0, 0}, {3, 0, 0}));
  const Log log = read_log(file);
  ASSERT_EQ(log.scans.size(), 3u);
  EXPECT_EQ(log.scans[0].robot.x, 3.0);
  EXPECT_EQ(log.scans[1].robot.x, 1.0);
  EXPECT_EQ(log.scans[2].robot.x, 2.0);
  EXPECT_EQ(log.reordered_scans, 3u);
}

TEST(CarmenLog, GoingBackMoreThanASecondIsAnError) {
  const TempDir dir;
  const auto scans =
      dir.write("back.clf", flaser_line(1000.0, {}, {}) + flaser_line(1001.0, {}, {}) +
                                flaser_line(999.5, {}, {}));
  const std::string message =
      expect_input_error([&] { read_log(scans); }, scans, 3, "ipc_timestamp");
  EXPECT_THAT(message, HasSubstr("goes back 1.500 s"));
  EXPECT_THAT(message, HasSubstr("line 2"));

  const auto odometry = dir.write("odometry_back.clf", flaser_line(1000.0, {}, {}) +
                                                           "ODOM 0 0 0 0 0 0 1000.0 host 1000.0\n" +
                                                           "ODOM 0 0 0 0 0 0 998.0 host 1000.1\n");
  expect_input_error([&] { read_log(odometry); }, odometry, 3, "ipc_timestamp");
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
