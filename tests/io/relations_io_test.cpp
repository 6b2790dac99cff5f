// The benchmark's relations files (io/relations_io.hpp): what is read, with line numbers, and
// every bad line named by file, line and field; the TUM trajectory writer, read back.
#include "intgrid/io/relations_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "intgrid/io/input_error.hpp"
#include "test_support.hpp"

namespace intgrid {
namespace {

using io::read_relations;
using io::RelationRecord;
using test::expect_input_error;
using test::TempDir;

TEST(RelationsIo, ReadsRelationsWithTheirLinesSkippingCommentsAndBlankLines) {
  const TempDir dir;
  const auto file = dir.write("r.relations",
                              "# t1 t2 x y z roll pitch yaw\n"
                              "976052905.167303 976052911.885496 -0.056990 -0.128430 0.000000 "
                              "0.000000 0.000000 -1.682210\n"
                              "\n"
                              "   \t\n"
                              "  # an indented comment\n"
                              "1.5\t2.5 +1 2 0 0 0 0.25\r\n"
                              "3 4 1e-3 -2E1 7 0.5 -0.5 -3");  // no final newline
  const std::vector<RelationRecord> r = read_relations(file);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0].line, 2u);
  EXPECT_EQ(r[0].relation.t1, 976052905.167303);
  EXPECT_EQ(r[0].relation.t2, 976052911.885496);
  EXPECT_EQ(r[0].relation.motion, (core::Pose2{-0.056990, -0.128430, -1.682210}));
  EXPECT_EQ(r[1].line, 6u);
  EXPECT_EQ(r[1].relation.t1, 1.5);
  EXPECT_EQ(r[1].relation.t2, 2.5);
  EXPECT_EQ(r[1].relation.motion, (core::Pose2{1, 2, 0.25}));
  EXPECT_EQ(r[2].line, 7u);
  EXPECT_EQ(r[2].relation.motion, (core::Pose2{1e-3, -20, -3}));  // z, roll, pitch not used

  const std::vector<core::Relation> plain = io::relations_of(r);
  ASSERT_EQ(plain.size(), 3u);
  EXPECT_EQ(plain[2].t1, 3.0);
}

TEST(RelationsIo, EachBadFieldIsNamedWithItsFileAndLine) {
  const TempDir dir;
  const char* const names[] = {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"};
  for (std::size_t bad = 0; bad < 8; ++bad) {
    for (const char* value : {"x1", "nan", "-inf", "1.0.0"}) {
      std::string line;
      for (std::size_t i = 0; i < 8; ++i) {
        if (i > 0) line += ' ';
        line += i == bad ? value : "1";
      }
      const auto file = dir.write("bad.relations", "# header\n1 2 0 0 0 0 0 0\n" + line + "\n");
      const std::string message =
          expect_input_error([&] { read_relations(file); }, file, 3, names[bad]);
      EXPECT_NE(message.find(value), std::string::npos) << message;
    }
  }
}

TEST(RelationsIo, MissingAndExtraFieldsAreNamed) {
  const TempDir dir;
  auto file = dir.write("short.relations", "1 2 0.5 0.1 0 0\n");
  std::string message = expect_input_error([&] { read_relations(file); }, file, 1, "pitch");
  EXPECT_NE(message.find("missing"), std::string::npos) << message;
  file = dir.write("t1only.relations", "\n7\n");
  expect_input_error([&] { read_relations(file); }, file, 2, "t2");
  file = dir.write("long.relations", "1 2 0 0 0 0 0 0 extra 9\n");
  message = expect_input_error([&] { read_relations(file); }, file, 1, "yaw");
  EXPECT_NE(message.find("2 unexpected field(s) after yaw, starting with \"extra\""),
            std::string::npos)
      << message;
}

TEST(RelationsIo, AFileWithoutRelationsOrAMissingFileIsAnError) {
  const TempDir dir;
  for (const char* content : {"", "\n\n", "# only a comment\n  \n"}) {
    const auto file = dir.write("empty.relations", content);
    const std::string message =
        expect_input_error([&] { read_relations(file); }, file, 0, "relations");
    EXPECT_NE(message.find("no relation"), std::string::npos) << message;
  }
  expect_input_error([&] { read_relations(dir / "missing.relations"); }, dir / "missing.relations",
                     0, "file");
}

TEST(TrajectoryIo, ReadsTheSlamTrajectoryAndNamesEveryBadField) {
  const TempDir dir;
  const auto good =
      dir.write("trajectory.txt", "# t x y theta\n1.5 0.25 -3 0.1\n\n2 1e-3 4 -3.1\r\n");
  const std::vector<core::TimedPose> poses = io::read_trajectory(good);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].t, 1.5);
  EXPECT_EQ(poses[0].pose.x, 0.25);
  EXPECT_EQ(poses[1].pose.y, 4.0);
  EXPECT_EQ(poses[1].pose.theta, -3.1);
  const char* const names[] = {"t", "x", "y", "theta"};
  for (std::size_t bad = 0; bad < 4; ++bad) {
    std::string line;
    for (std::size_t i = 0; i < 4; ++i) line += i == bad ? "nan " : "5 ";
    const auto file = dir.write("bad.txt", "1 0 0 0\n" + line + "\n");
    expect_input_error([&] { io::read_trajectory(file); }, file, 2, names[bad]);
  }
  auto file = dir.write("short.txt", "1 0 0\n");
  expect_input_error([&] { io::read_trajectory(file); }, file, 1, "theta");
  file = dir.write("long.txt", "1 0 0 0 7\n");
  expect_input_error([&] { io::read_trajectory(file); }, file, 1, "theta");
  file = dir.write("backwards.txt", "2 0 0 0\n1 0 0 0\n");
  expect_input_error([&] { io::read_trajectory(file); }, file, 2, "t");
  file = dir.write("empty.txt", "# nothing\n");
  expect_input_error([&] { io::read_trajectory(file); }, file, 0, "poses");
}

TEST(TumTrajectory, WritesOneLinePerPoseThatReadsBackExactly) {
  const TempDir dir;
  const std::vector<core::TimedPose> trajectory = {
      {1137834225.713386, {0.1, -2.5, 0.0}},
      {1137834226.1, {1.0 / 3.0, 4.0, std::numbers::pi / 2}},
      {1137834227.25, {-7.0, 1e-9, -3.0}},
      {1137834228.5, {0, 0, 5.0}}};  // past pi: written wrapped, qw >= 0
  const auto file = dir / "t.tum";
  io::write_tum_trajectory(file, trajectory);
  EXPECT_EQ(dir.entry_count(), 1u) << "no temporary file left";

  std::ifstream in(file);
  std::string line;
  std::size_t i = 0;
  while (std::getline(in, line)) {
    ASSERT_LT(i, trajectory.size()) << line;
    std::istringstream fields(line);
    double t, x, y, z, qx, qy, qz, qw;
    ASSERT_TRUE(fields >> t >> x >> y >> z >> qx >> qy >> qz >> qw) << line;
    std::string rest;
    EXPECT_FALSE(fields >> rest) << line;
    const core::TimedPose& p = trajectory[i];
    EXPECT_EQ(t, p.t) << line;
    EXPECT_EQ(x, p.pose.x) << line;
    EXPECT_EQ(y, p.pose.y) << line;
    EXPECT_EQ(z, 0.0);
    EXPECT_EQ(qx, 0.0);
    EXPECT_EQ(qy, 0.0);
    EXPECT_NEAR(qz * qz + qw * qw, 1.0, 1e-15);
    EXPECT_GE(qw, 0.0);
    const double yaw = 2.0 * std::atan2(qz, qw);
    EXPECT_NEAR(core::wrap_angle(yaw - p.pose.theta), 0.0, 1e-15) << line;
    ++i;
  }
  EXPECT_EQ(i, trajectory.size());
  EXPECT_EQ(test::read_bytes(file).substr(0, 18), "1137834225.713386 ");

  io::write_tum_trajectory(dir / "empty.tum", {});
  EXPECT_EQ(test::read_bytes(dir / "empty.tum"), "");
}

}  // namespace
}  // namespace intgrid
