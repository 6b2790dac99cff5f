// ROS map reading and writing on small maps written by the tests themselves.
#include "intgrid/io/map_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "intgrid/io/input_error.hpp"
#include "test_support.hpp"

using namespace intgrid::core;

using namespace intgrid::io;

namespace intgrid {
namespace {

using test::expect_input_error;
using test::expect_same_geometry;
using test::TempDir;
using ::testing::HasSubstr;

// Line numbers matter: tests point at them.
std::string map_yaml(const std::string& resolution = "0.05",
                     const std::string& origin = "[-1.5, 2.25, 0.0]",
                     const std::string& extra = "") {
  return "image: map.pgm\n"  // line 1
         "resolution: " +
         resolution +
         "\n"  // line 2
         "origin: " +
         origin +
         "\n"                       // line 3
         "negate: 0\n"              // line 4
         "occupied_thresh: 0.65\n"  // line 5
         "free_thresh: 0.196\n" +   // line 6
         extra;
}

// 3 x 2: top row 0 255 128, bottom row 255 0 51.
std::string small_p5() {
  return std::string("P5\n3 2\n255\n").append("\x00\xff\x80\xff\x00\x33", 6);
}

TEST(RosMap, ReadsBinaryPgmBottomRowFirst) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  const RosMap map = read_ros_map(dir.write("map.yaml", map_yaml()));

  const GridGeometry& geometry = map.grid.geometry;
  EXPECT_EQ(geometry.width, 3);
  EXPECT_EQ(geometry.height, 2);
  EXPECT_EQ(geometry.resolution, 0.05);
  EXPECT_EQ(geometry.origin_x, -1.5);
  EXPECT_EQ(geometry.origin_y, 2.25);
  EXPECT_EQ(map.occupied_thresh, 0.65);
  EXPECT_EQ(map.free_thresh, 0.196);
  EXPECT_FALSE(map.negate);
  // grid row 1 is the PGM's top row
  EXPECT_EQ(map.grid.at(0, 1), 1.0);
  EXPECT_EQ(map.grid.at(1, 1), 0.0);
  EXPECT_DOUBLE_EQ(map.grid.at(2, 1), 127.0 / 255.0);
  EXPECT_EQ(map.grid.at(0, 0), 0.0);
  EXPECT_EQ(map.grid.at(1, 0), 1.0);
  EXPECT_DOUBLE_EQ(map.grid.at(2, 0), 204.0 / 255.0);
}

TEST(RosMap, NegateMakesBrightPixelsOccupied) {
  const TempDir dir;
  dir.write("map.pgm", std::string("P5\n2 1\n255\n").append("\x00\x33", 2));
  const std::string yaml =
      "image: map.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 1\n"
      "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
  const RosMap map = read_ros_map(dir.write("map.yaml", yaml));
  EXPECT_TRUE(map.negate);
  EXPECT_EQ(map.grid.at(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(map.grid.at(1, 0), 0.2);
}

TEST(RosMap, ReadsAsciiPgmWithComments) {
  const TempDir dir;
  dir.write("map.pgm", "P2\n# made by hand\n3 2 # width height\n255\n0 255 128\n255 0 51\n");
  const RosMap map = read_ros_map(dir.write("map.yaml", map_yaml()));
  EXPECT_EQ(map.grid.at(0, 1), 1.0);
  EXPECT_DOUBLE_EQ(map.grid.at(2, 0), 204.0 / 255.0);
}

TEST(RosMap, AbsoluteImagePathIsUsedAsIs) {
  const TempDir dir;
  const auto pgm = dir.write("elsewhere.pgm", small_p5());
  std::string yaml = map_yaml();
  yaml.replace(yaml.find("map.pgm"), 7, pgm.string());
  std::filesystem::create_directory(dir / "sub");
  EXPECT_EQ(read_ros_map(dir.write("sub/map.yaml", yaml)).grid.geometry.width, 3);
}

TEST(RosMap, ShortPixelDataNamesExpectedAndActualSizes) {
  const TempDir dir;
  const auto pgm = dir.write("map.pgm", std::string("P5\n3 2\n255\n") + "\x01\x02\x03\x04\x05");
  const auto yaml = dir.write("map.yaml", map_yaml());
  const std::string message = expect_input_error([&] { read_ros_map(yaml); }, pgm, 2, "pixels");
  EXPECT_THAT(message, HasSubstr("= 6 bytes"));
  EXPECT_THAT(message, HasSubstr("found 5"));
}

TEST(RosMap, LongPixelDataIsAnError) {
  const TempDir dir;
  const auto pgm = dir.write("map.pgm", std::string("P5\n3\n2\n255\n") + "1234567");
  const auto yaml = dir.write("map.yaml", map_yaml());
  const std::string message = expect_input_error([&] { read_ros_map(yaml); }, pgm, 3, "pixels");
  EXPECT_THAT(message, HasSubstr("found 7"));
}

TEST(RosMap, AsciiPixelCountMustMatchHeader) {
  const TempDir dir;
  const auto pgm = dir.write("map.pgm", "P2\n3 2\n255\n0 255 128\n255 0\n");
  const auto yaml = dir.write("map.yaml", map_yaml());
  const std::string message = expect_input_error([&] { read_ros_map(yaml); }, pgm, 2, "pixels");
  EXPECT_THAT(message, HasSubstr("= 6 values of pixel data, found 5"));
}

TEST(RosMap, AsciiPixelOutsideByteRangeNamesLine) {
  const TempDir dir;
  const auto pgm = dir.write("map.pgm", "P2\n3 2\n255\n0 255 128\n255 256 0\n");
  const auto yaml = dir.write("map.yaml", map_yaml());
  expect_input_error([&] { read_ros_map(yaml); }, pgm, 5, "pixels");
}

TEST(RosMap, BadMagicIsAnError) {
  const TempDir dir;
  const auto pgm = dir.write("map.pgm", "P6\n3 2\n255\n");
  const auto yaml = dir.write("map.yaml", map_yaml());
  const std::string message = expect_input_error([&] { read_ros_map(yaml); }, pgm, 1, "magic");
  EXPECT_THAT(message, HasSubstr("\"P6\""));
}

TEST(RosMap, SixteenBitPgmIsRejected) {
  const TempDir dir;
  const auto pgm = dir.write("map.pgm", "P5\n3 2\n65535\n");
  const auto yaml = dir.write("map.yaml", map_yaml());
  expect_input_error([&] { read_ros_map(yaml); }, pgm, 3, "maxval");
}

TEST(RosMap, ZeroWidthIsRejected) {
  const TempDir dir;
  const auto pgm = dir.write("map.pgm", "P5\n0 2\n255\n");
  const auto yaml = dir.write("map.yaml", map_yaml());
  expect_input_error([&] { read_ros_map(yaml); }, pgm, 2, "width");
}

TEST(RosMap, HugeHeaderIsRejectedBeforeAllocating) {
  const TempDir dir;
  const auto pgm = dir.write("map.pgm", "P5\n65536 65536\n255\n");
  const auto yaml = dir.write("map.yaml", map_yaml());
  const std::string message = expect_input_error([&] { read_ros_map(yaml); }, pgm, 2, "height");
  EXPECT_THAT(message, HasSubstr("exceeds 2^31"));
}

TEST(RosMap, NegativeResolutionNamesItsLine) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  const auto yaml = dir.write("map.yaml", map_yaml("-0.05"));
  const std::string message =
      expect_input_error([&] { read_ros_map(yaml); }, yaml, 2, "resolution");
  EXPECT_THAT(message, HasSubstr("positive"));
}

TEST(RosMap, NonNumericResolutionIsAnError) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  const auto yaml = dir.write("map.yaml", map_yaml("fine"));
  const std::string message =
      expect_input_error([&] { read_ros_map(yaml); }, yaml, 2, "resolution");
  EXPECT_THAT(message, HasSubstr("\"fine\""));
}

TEST(RosMap, MissingKeyIsNamed) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  std::string text = map_yaml();
  text.erase(text.find("free_thresh"));
  const auto yaml = dir.write("map.yaml", text);
  const std::string message =
      expect_input_error([&] { read_ros_map(yaml); }, yaml, 0, "free_thresh");
  EXPECT_EQ(message, "missing key");
}

TEST(RosMap, RotatedOriginIsRejected) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  const auto yaml = dir.write("map.yaml", map_yaml("0.05", "[-1.5, 2.25, 0.5]"));
  const std::string message = expect_input_error([&] { read_ros_map(yaml); }, yaml, 3, "origin");
  EXPECT_THAT(message, HasSubstr("rotated maps are not supported"));
}

TEST(RosMap, OriginMustHaveThreeElements) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  const auto yaml = dir.write("map.yaml", map_yaml("0.05", "[1, 2]"));
  expect_input_error([&] { read_ros_map(yaml); }, yaml, 3, "origin");
}

TEST(RosMap, FreeThresholdMustBeBelowOccupied) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  std::string text = map_yaml();
  text.replace(text.find("0.196"), 5, "0.7");
  const auto yaml = dir.write("map.yaml", text);
  expect_input_error([&] { read_ros_map(yaml); }, yaml, 6, "free_thresh");
}

TEST(RosMap, ThresholdMustBeAProbability) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  std::string text = map_yaml();
  text.replace(text.find("0.65"), 4, "1.5");
  const auto yaml = dir.write("map.yaml", text);
  expect_input_error([&] { read_ros_map(yaml); }, yaml, 5, "occupied_thresh");
}

TEST(RosMap, UnsupportedModeIsRejected) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  const auto trinary = dir.write("trinary.yaml", map_yaml("0.05", "[0, 0, 0]", "mode: trinary\n"));
  EXPECT_EQ(read_ros_map(trinary).grid.geometry.width, 3);
  const auto raw = dir.write("raw.yaml", map_yaml("0.05", "[0, 0, 0]", "mode: raw\n"));
  expect_input_error([&] { read_ros_map(raw); }, raw, 7, "mode");
}

TEST(RosMap, YamlSyntaxErrorNamesItsLine) {
  const TempDir dir;
  const auto yaml = dir.write("map.yaml", "image: map.pgm\nresolution: 0.05\norigin: [0, 0\n");
  expect_input_error([&] { read_ros_map(yaml); }, yaml, 4, "yaml");
}

TEST(RosMap, MissingImageIsAnInputErrorOnTheImage) {
  const TempDir dir;
  const auto yaml = dir.write("map.yaml", map_yaml());
  const std::string message =
      expect_input_error([&] { read_ros_map(yaml); }, dir / "map.pgm", 0, "file");
  EXPECT_EQ(message, "cannot open: No such file or directory");
}

TEST(RosMap, MissingYamlIsAnInputError) {
  const TempDir dir;
  expect_input_error([&] { read_ros_map(dir / "absent.yaml"); }, dir / "absent.yaml", 0, "file");
}

RosMap gradient_map() {
  RosMap map;
  map.grid = ProbabilityGrid({7, 5, 0.025, -12.345678901234567, 1.0 / 3.0}, 0.0);
  for (std::size_t i = 0; i < map.grid.cells.size(); ++i) {
    map.grid.cells[i] = static_cast<double>(i) / static_cast<double>(map.grid.cells.size() - 1);
  }
  map.occupied_thresh = 0.7;
  map.free_thresh = 0.2;
  return map;
}

TEST(RosMap, WriteThenReadKeepsGeometryAndCellsWithinHalfAStep) {
  const TempDir dir;
  for (const bool negate : {false, true}) {
    SCOPED_TRACE(negate ? "negate 1" : "negate 0");
    RosMap written = gradient_map();
    written.negate = negate;
    write_ros_map(dir / "out.yaml", written);
    const RosMap read = read_ros_map(dir / "out.yaml");

    expect_same_geometry(read.grid.geometry, written.grid.geometry);
    EXPECT_EQ(read.occupied_thresh, 0.7);
    EXPECT_EQ(read.free_thresh, 0.2);
    EXPECT_EQ(read.negate, negate);
    ASSERT_EQ(read.grid.cells.size(), written.grid.cells.size());
    for (std::size_t i = 0; i < written.grid.cells.size(); ++i) {
      // Some cells sit exactly half a pixel step from two pixel values.
      EXPECT_NEAR(read.grid.cells[i], written.grid.cells[i], 1.0 / 510.0 + 1e-12) << "cell " << i;
    }
  }
  EXPECT_THAT(test::read_bytes(dir / "out.yaml"), HasSubstr("image: out.pgm\n"));
  EXPECT_EQ(dir.entry_count(), 2u) << "out.yaml and out.pgm, no temporary files";
}

TEST(RosMap, WritePixelIsRoundedInverseProbability) {
  const TempDir dir;
  RosMap map;
  map.grid = ProbabilityGrid({4, 1, 1.0, 0.0, 0.0}, 0.0);
  map.grid.cells = {0.0, 1.0, 0.5, 0.2};
  write_ros_map(dir / "m.yaml", map);
  // 255 * (1 - P): 255, 0, 127.5 -> 128, 204
  EXPECT_EQ(test::read_bytes(dir / "m.pgm"),
            std::string("P5\n4 1\n255\n").append("\xff\x00\x80\xcc", 4));
}

TEST(RosMap, WriteRejectsGridWhoseCellsDisagreeWithGeometry) {
  const TempDir dir;
  RosMap map = gradient_map();
  map.grid.cells.pop_back();
  EXPECT_THROW(write_ros_map(dir / "bad.yaml", map), std::invalid_argument);
  EXPECT_EQ(dir.entry_count(), 0u);
}

}  // namespace
}  // namespace intgrid
