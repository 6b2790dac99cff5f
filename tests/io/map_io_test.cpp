// ROS map reading and writing on small maps written by the tests themselves.
#include "intgrid/io/map_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "intgrid/io/image_io.hpp"
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

// A file name with a control character (found by the fuzzer: a NUL in it cut the message that
// named the image short) is refused where the YAML states it.
TEST(RosMap, ImageNameWithAControlCharacterNamesTheYamlField) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  for (const std::string& name :
       {std::string("map.pg0") + '\0' + "0i_0", std::string("map") + '\x01' + ".pgm"}) {
    std::string yaml = map_yaml();
    yaml.replace(yaml.find("map.pgm"), 7, name);
    const auto path = dir.write("map.yaml", yaml);
    const std::string message = expect_input_error([&] { read_ros_map(path); }, path, 1, "image");
    EXPECT_THAT(message, HasSubstr("control character")) << message;
    EXPECT_EQ(message.find('\0'), std::string::npos);
  }
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

// Negative, denormal or absurdly coarse resolutions name their line; the bounds themselves read.
TEST(RosMap, ResolutionOutsideItsRangeNamesItsLine) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  for (const char* resolution : {"-0.05", "0", "1e-320", "0.00009", "100.5"}) {
    SCOPED_TRACE(resolution);
    const auto yaml = dir.write("map.yaml", map_yaml(resolution));
    const std::string message =
        expect_input_error([&] { read_ros_map(yaml); }, yaml, 2, "resolution");
    EXPECT_THAT(message, HasSubstr("must lie in [0.0001, 100]"));
  }
  for (const char* resolution : {"0.0001", "100"}) {
    const auto yaml = dir.write("map.yaml", map_yaml(resolution));
    EXPECT_EQ(read_ros_map(yaml).grid.geometry.resolution, std::stod(resolution));
  }
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

TEST(RosMap, EveryMapServerModeIsAccepted) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  for (const char* mode : {"trinary", "scale", "raw"}) {
    SCOPED_TRACE(mode);
    const auto yaml =
        dir.write("map.yaml", map_yaml("0.05", "[0, 0, 0]", std::string("mode: ") + mode + "\n"));
    EXPECT_EQ(read_ros_map(yaml).grid.geometry.width, 3);
  }
}

TEST(RosMap, UnknownModeNamesLineAndField) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  const auto yaml = dir.write("map.yaml", map_yaml("0.05", "[0, 0, 0]", "mode: ternary\n"));
  const std::string message = expect_input_error([&] { read_ros_map(yaml); }, yaml, 7, "mode");
  EXPECT_THAT(message, HasSubstr("\"ternary\""));
  EXPECT_THAT(message, HasSubstr("trinary, scale or raw"));
}

TEST(RosMap, ModeNamesAreCaseSensitiveAsInMapServer) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  const auto yaml = dir.write("map.yaml", map_yaml("0.05", "[0, 0, 0]", "mode: Trinary\n"));
  expect_input_error([&] { read_ros_map(yaml); }, yaml, 7, "mode");
}

TEST(RosMap, ModeMustBeASingleValue) {
  const TempDir dir;
  dir.write("map.pgm", small_p5());
  const auto yaml = dir.write("map.yaml", map_yaml("0.05", "[0, 0, 0]", "\nmode: [trinary]\n"));
  const std::string message = expect_input_error([&] { read_ros_map(yaml); }, yaml, 8, "mode");
  EXPECT_THAT(message, HasSubstr("single value"));
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

// CRC-32 (IEEE 802.3, reflected, as zlib and PNG compute it), bit by bit: the test's own
// formulation of the checksum intgrid's YAML carries.
std::uint32_t bitwise_crc32(std::string_view bytes) {
  std::uint32_t crc = 0xffffffffu;
  for (const char c : bytes) {
    crc ^= static_cast<std::uint8_t>(c);
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

// A run stopped after renaming the new image and before the YAML leaves the old YAML beside the
// new image: the YAML's image_crc32 (line 2) no longer matches, and the pair is refused instead
// of read as a wrong map.
TEST(RosMap, AnImageThatIsNotTheOneWrittenWithItsYamlIsRefused) {
  ASSERT_EQ(bitwise_crc32("123456789"), 0xcbf43926u);  // the CRC-32 check value
  const TempDir dir;
  RosMap first = gradient_map();
  write_ros_map(dir / "m.yaml", first);
  const std::string first_yaml = test::read_bytes(dir / "m.yaml");
  char crc[9];
  std::snprintf(crc, sizeof crc, "%08x", bitwise_crc32(test::read_bytes(dir / "m.pgm")));
  EXPECT_THAT(first_yaml, HasSubstr("image: m.pgm\nimage_crc32: " + std::string(crc) + "\n"));
  EXPECT_NO_THROW(read_ros_map(dir / "m.yaml"));

  RosMap second = first;
  for (double& p : second.grid.cells) p = 1.0 - p;
  write_ros_map(dir / "m.yaml", second);
  dir.write("m.yaml", first_yaml);  // the old YAML back
  const std::string what =
      expect_input_error([&] { read_ros_map(dir / "m.yaml"); }, dir / "m.yaml", 2, "image_crc32");
  EXPECT_THAT(what, HasSubstr("is not the CRC-32 of " + (dir / "m.pgm").string()));

  dir.write("m.yaml", map_yaml("0.05", "[0, 0, 0]", "image_crc32: 12345g78\n"));
  dir.write("map.pgm", small_p5());
  expect_input_error([&] { read_ros_map(dir / "m.yaml"); }, dir / "m.yaml", 7, "image_crc32");
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

// ---- Modes, on PGM maps ----

constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();

std::string p5(int width, int height, const std::vector<std::uint8_t>& pixels) {
  std::string out = "P5\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
  out.append(pixels.begin(), pixels.end());
  return out;
}

std::string mode_yaml(const std::string& image, const std::string& mode, bool negate,
                      const std::string& occupied = "0.65", const std::string& free = "0.196") {
  std::string yaml = "image: " + image +
                     "\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: " + (negate ? "1" : "0") +
                     "\noccupied_thresh: " + occupied + "\nfree_thresh: " + free + "\n";
  if (!mode.empty()) yaml += "mode: " + mode + "\n";
  return yaml;
}

// Exactly equal, or both NaN.
bool same_cell(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || a == b;
}

void expect_row(const ProbabilityGrid& grid, const std::vector<double>& expected) {
  ASSERT_EQ(grid.geometry.height, 1);
  ASSERT_EQ(grid.cells.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_TRUE(same_cell(grid.cells[i], expected[i]))
        << "cell " << i << ": " << grid.cells[i] << ", expected " << expected[i];
  }
}

// Around both default thresholds: (255 - v) / 255 for these is 1, .808, .804, .651, .647, .498,
// .353, .349, .19608, .19216, 0 against occupied_thresh .65 and free_thresh .196.
const std::vector<std::uint8_t> kThresholdPixels = {0,   49,  50,  89,  90, 128,
                                                    165, 166, 205, 206, 255};

RosMap read_one_row(const TempDir& dir, const std::vector<std::uint8_t>& pixels,
                    const std::string& mode, bool negate, const std::string& occupied = "0.65",
                    const std::string& free = "0.196") {
  dir.write("row.pgm", p5(static_cast<int>(pixels.size()), 1, pixels));
  return read_ros_map(dir.write("row.yaml", mode_yaml("row.pgm", mode, negate, occupied, free)));
}

TEST(RosMapMode, WithoutModeCellsKeepTheImagesProbability) {
  const TempDir dir;
  std::vector<double> expected;
  for (const std::uint8_t v : kThresholdPixels) expected.push_back(1.0 - v / 255.0);
  expect_row(read_one_row(dir, kThresholdPixels, "", false).grid, expected);
}

TEST(RosMapMode, TrinaryGivesOccupiedFreeOrUnknown) {
  const TempDir dir;
  const double u = kUnknown;
  expect_row(read_one_row(dir, kThresholdPixels, "trinary", false).grid,
             {1, 1, 1, 1, u, u, u, u, u, 0, 0});
  // negate: p = v / 255
  expect_row(read_one_row(dir, kThresholdPixels, "trinary", true).grid,
             {0, 0, u, u, u, u, u, 1, 1, 1, 1});
}

TEST(RosMapMode, ScaleKeepsTheProbabilityBetweenTheThresholds) {
  const TempDir dir;
  expect_row(read_one_row(dir, kThresholdPixels, "scale", false).grid,
             {1, 1, 1, 1, 165 / 255.0, 127 / 255.0, 90 / 255.0, 89 / 255.0, 50 / 255.0, 0, 0});
  expect_row(read_one_row(dir, kThresholdPixels, "scale", true).grid,
             {0, 0, 50 / 255.0, 89 / 255.0, 90 / 255.0, 128 / 255.0, 165 / 255.0, 1, 1, 1, 1});
}

TEST(RosMapMode, ThresholdsAreStrictAsInMapServer) {
  const TempDir dir;
  // (255 - v) / 255: 153/255 = 0.6 and 51/255 = 0.2 exactly, on the thresholds, then just past.
  const std::vector<std::uint8_t> pixels = {102, 204, 101, 205};
  expect_row(read_one_row(dir, pixels, "trinary", false, "0.6", "0.2").grid,
             {kUnknown, kUnknown, 1, 0});
  expect_row(read_one_row(dir, pixels, "scale", false, "0.6", "0.2").grid, {0.6, 0.2, 1, 0});
}

TEST(RosMapMode, RawIsThePercentOccupiedAndIgnoresNegate) {
  const TempDir dir;
  const std::vector<std::uint8_t> pixels = {0, 1, 50, 99, 100, 101, 200, 255};
  const std::vector<double> expected = {0,   1 / 100.0, 50 / 100.0, 99 / 100.0,
                                        1.0, kUnknown,  kUnknown,   kUnknown};
  expect_row(read_one_row(dir, pixels, "raw", false).grid, expected);
  expect_row(read_one_row(dir, pixels, "raw", true).grid, expected);
}

// ---- PNG maps ----

// Writes a PNG with libpng's full API, so that every colour type, bit depth, palette, tRNS
// chunk and interlacing can be made. Rows are packed as PNG stores them.
struct PngSpec {
  int width = 0;
  int height = 0;
  int color_type = PNG_COLOR_TYPE_GRAY;
  int bit_depth = 8;
  bool interlaced = false;
  std::vector<png_color> palette;
  std::vector<png_byte> palette_alpha;      // tRNS of a palette image
  std::optional<png_color_16> transparent;  // tRNS of a grey or RGB image
  std::vector<std::vector<png_byte>> rows;
};

void append_to_string(png_structp png, png_bytep data, png_size_t length) {
  static_cast<std::string*>(png_get_io_ptr(png))
      ->append(reinterpret_cast<const char*>(data), length);
}

// Only plain data between the setjmp and libpng's longjmp.
bool encode_png(png_structp png, png_infop info, const PngSpec& spec, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_IHDR(png, info, static_cast<png_uint_32>(spec.width),
               static_cast<png_uint_32>(spec.height), spec.bit_depth, spec.color_type,
               spec.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (!spec.palette.empty()) {
    png_set_PLTE(png, info, spec.palette.data(), static_cast<int>(spec.palette.size()));
  }
  if (!spec.palette_alpha.empty()) {
    png_set_tRNS(png, info, spec.palette_alpha.data(), static_cast<int>(spec.palette_alpha.size()),
                 nullptr);
  }
  if (spec.transparent) png_set_tRNS(png, info, nullptr, 0, &*spec.transparent);
  png_write_info(png, info);
  png_write_image(png, rows);  // all Adam7 passes if interlaced
  png_write_end(png, nullptr);
  return true;
}

std::string png_file_bytes(const PngSpec& spec) {
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_set_write_fn(png, &out, append_to_string, nullptr);
  std::vector<png_bytep> rows;
  for (const auto& row : spec.rows) rows.push_back(const_cast<png_bytep>(row.data()));
  const bool ok = encode_png(png, info, spec, rows.data());
  png_destroy_write_struct(&png, &info);
  if (!ok) throw std::runtime_error("the test could not encode its PNG");
  return out;
}

// How a test map is stored in a PNG.
struct PngKind {
  const char* name;
  int color_type;
  int bit_depth;
  bool transparency = false;  // an alpha channel with transparent pixels, or a tRNS chunk
  bool interlaced = false;
};

int colour_channels(const PngKind& kind) {
  return (kind.color_type & PNG_COLOR_MASK_COLOR) != 0 && kind.color_type != PNG_COLOR_TYPE_PALETTE
             ? 3
             : 1;
}

bool has_alpha_channel(const PngKind& kind) {
  return (kind.color_type & PNG_COLOR_MASK_ALPHA) != 0;
}

// The 8-bit grey levels a sample of bit_depth < 8 (or a palette of 2^bit_depth entries) holds.
int level_step(int bit_depth) {
  return bit_depth >= 8 ? 1 : 255 / ((1 << bit_depth) - 1);
}

// The grey of each pixel as a PGM of the same map holds it, row 0 at the top: deterministic,
// spread over 0..255 and not symmetric, so a flipped, shifted or mis-averaged image shows.
constexpr int kTestWidth = 13;  // odd, so packed sub-byte rows end in a partial byte
constexpr int kTestHeight = 7;

std::vector<std::uint8_t> test_levels(int bit_depth) {
  std::vector<std::uint8_t> levels;
  std::uint32_t state = 12345;
  const int step = level_step(bit_depth);
  for (int i = 0; i < kTestWidth * kTestHeight; ++i) {
    state = state * 1103515245u + 12345u;
    const int v = static_cast<int>((state >> 16) % 256);
    levels.push_back(static_cast<std::uint8_t>(
        (v + step / 2) / step * step > 255 ? 255 : (v + step / 2) / step * step));
  }
  return levels;
}

// Alpha channel of the pixel with index i: some fully and some slightly transparent.
std::uint8_t test_alpha(int i) {
  return i % 5 == 0 ? 0 : i % 5 == 1 ? 254 : 255;
}

struct EncodedPng {
  std::string bytes;
  std::vector<bool> opaque;  // per pixel, row 0 at the top
};

// Packs sample values of bit_depth bits into a PNG row.
std::vector<png_byte> pack_row(const std::vector<int>& samples, int bit_depth) {
  std::vector<png_byte> row;
  if (bit_depth == 16) {
    for (const int sample : samples) {
      row.push_back(static_cast<png_byte>(sample >> 8));
      row.push_back(static_cast<png_byte>(sample & 0xff));
    }
  } else if (bit_depth == 8) {
    for (const int sample : samples) row.push_back(static_cast<png_byte>(sample));
  } else {
    row.assign((samples.size() * static_cast<std::size_t>(bit_depth) + 7) / 8, 0);
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const std::size_t bit = i * static_cast<std::size_t>(bit_depth);
      const int shift = 8 - bit_depth - static_cast<int>(bit % 8);
      row[bit / 8] = static_cast<png_byte>(row[bit / 8] | (samples[i] << shift));
    }
  }
  return row;
}

EncodedPng encode_levels(const PngKind& kind, const std::vector<std::uint8_t>& levels) {
  PngSpec spec;
  spec.width = kTestWidth;
  spec.height = kTestHeight;
  spec.color_type = kind.color_type;
  spec.bit_depth = kind.bit_depth;
  spec.interlaced = kind.interlaced;
  const bool sixteen = kind.bit_depth == 16;
  const int max = sixteen ? 65535 : 255;
  const int step = level_step(kind.bit_depth);

  // A palette's entry e holds grey 255 - e * step as a colour whose channels average to it, so
  // that reading indices instead of colours shows.
  const int entries = 1 << std::min(kind.bit_depth, 8);
  if (kind.color_type == PNG_COLOR_TYPE_PALETTE) {
    for (int e = 0; e < entries; ++e) {
      const int grey = 255 - e * step;
      const int d = std::min({e % 4, grey, 255 - grey});
      spec.palette.push_back({static_cast<png_byte>(grey + d), static_cast<png_byte>(grey - d),
                              static_cast<png_byte>(grey)});
      if (kind.transparency) spec.palette_alpha.push_back(test_alpha(e));
    }
  }

  EncodedPng encoded;
  std::vector<std::vector<int>> colours;  // the samples of each pixel's colour channels
  for (int i = 0; i < kTestWidth * kTestHeight; ++i) {
    const int grey = levels[static_cast<std::size_t>(i)];
    const int base = sixteen ? grey * 257 : grey / step;
    if (kind.color_type == PNG_COLOR_TYPE_PALETTE) {
      colours.push_back({(255 - grey) / step});
    } else if (colour_channels(kind) == 3) {
      // Unequal channels with the grey as their mean.
      const int d = std::min({(i * 7) % 5 * (sixteen ? 1000 : 1), base, max - base});
      colours.push_back({base + d, base - d, base});
    } else {
      colours.push_back({base});
    }
  }
  if (kind.transparency && !has_alpha_channel(kind) && kind.color_type != PNG_COLOR_TYPE_PALETTE) {
    // tRNS: the colour of pixel 0 is transparent wherever it appears.
    const std::vector<int>& c = colours[0];
    png_color_16 colour{};
    if (c.size() == 1) {
      colour.gray = static_cast<png_uint_16>(c[0]);
    } else {
      colour.red = static_cast<png_uint_16>(c[0]);
      colour.green = static_cast<png_uint_16>(c[1]);
      colour.blue = static_cast<png_uint_16>(c[2]);
    }
    spec.transparent = colour;
  }

  for (int y = 0; y < kTestHeight; ++y) {
    std::vector<int> samples;
    for (int x = 0; x < kTestWidth; ++x) {
      const int i = y * kTestWidth + x;
      const std::vector<int>& c = colours[static_cast<std::size_t>(i)];
      samples.insert(samples.end(), c.begin(), c.end());
      bool opaque = true;
      if (has_alpha_channel(kind)) {
        const int alpha = kind.transparency ? test_alpha(i) : 255;
        samples.push_back(sixteen ? (alpha == 255 ? 65535 : alpha * 257) : alpha);
        opaque = alpha == 255;
      } else if (kind.transparency && kind.color_type == PNG_COLOR_TYPE_PALETTE) {
        opaque = test_alpha(c[0]) == 255;
      } else if (kind.transparency) {
        opaque = c != colours[0];
      }
      encoded.opaque.push_back(opaque);
    }
    spec.rows.push_back(pack_row(samples, kind.bit_depth));
  }
  encoded.bytes = png_file_bytes(spec);
  return encoded;
}

class PngMap : public ::testing::TestWithParam<PngKind> {};

// The PNG against the same map written as a PGM: the PGM path is the oracle. Transparent
// pixels are unknown except in raw mode, which ignores alpha.
TEST_P(PngMap, ReadsAsTheSameMapWrittenAsPgm) {
  const PngKind& kind = GetParam();
  const TempDir dir;
  const std::vector<std::uint8_t> levels = test_levels(kind.bit_depth);
  dir.write("map.pgm", p5(kTestWidth, kTestHeight, levels));
  const EncodedPng png = encode_levels(kind, levels);
  dir.write("map.png", png.bytes);
  if (kind.transparency) {
    ASSERT_NE(std::count(png.opaque.begin(), png.opaque.end(), false), 0) << "nothing transparent";
    ASSERT_NE(std::count(png.opaque.begin(), png.opaque.end(), true), 0) << "nothing opaque";
  }

  for (const std::string mode : {"", "trinary", "scale", "raw"}) {
    for (const bool negate : {false, true}) {
      SCOPED_TRACE("mode \"" + mode + "\", negate " + (negate ? "1" : "0"));
      const RosMap oracle = read_ros_map(dir.write("pgm.yaml", mode_yaml("map.pgm", mode, negate)));
      const RosMap map = read_ros_map(dir.write("png.yaml", mode_yaml("map.png", mode, negate)));
      expect_same_geometry(map.grid.geometry, oracle.grid.geometry);
      ASSERT_EQ(map.grid.cells.size(), oracle.grid.cells.size());
      for (int iy = 0; iy < kTestHeight; ++iy) {
        for (int ix = 0; ix < kTestWidth; ++ix) {
          const std::size_t pixel =
              static_cast<std::size_t>((kTestHeight - 1 - iy) * kTestWidth + ix);
          const double expected =
              png.opaque[pixel] || mode == "raw" ? oracle.grid.at(ix, iy) : kUnknown;
          EXPECT_TRUE(same_cell(map.grid.at(ix, iy), expected))
              << "cell (" << ix << ", " << iy << "): " << map.grid.at(ix, iy) << ", expected "
              << expected;
        }
      }
      // The oracle itself must tell the cases apart for the comparison to mean something.
      if (kind.bit_depth >= 8 && !negate) {
        const auto count = [&](auto predicate) {
          return std::count_if(oracle.grid.cells.begin(), oracle.grid.cells.end(), predicate);
        };
        const auto is_nan = [](double p) { return std::isnan(p); };
        const auto is_fraction = [](double p) { return p > 0.0 && p < 1.0; };
        if (mode == "trinary") {
          EXPECT_GT(count(is_nan), 0);
          EXPECT_GT(count([](double p) { return p == 0.0; }), 0);
          EXPECT_GT(count([](double p) { return p == 1.0; }), 0);
        } else if (mode == "scale") {
          EXPECT_GT(count(is_fraction), 0);
          EXPECT_GT(count([](double p) { return p == 1.0; }), 0);
        } else if (mode == "raw") {
          EXPECT_GT(count(is_nan), 0);
          EXPECT_GT(count(is_fraction), 0);
        } else {
          EXPECT_EQ(count(is_nan), 0);
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    RosMapPng, PngMap,
    ::testing::Values(
        PngKind{"grey1", PNG_COLOR_TYPE_GRAY, 1}, PngKind{"grey2", PNG_COLOR_TYPE_GRAY, 2},
        PngKind{"grey4", PNG_COLOR_TYPE_GRAY, 4}, PngKind{"grey8", PNG_COLOR_TYPE_GRAY, 8},
        PngKind{"grey16", PNG_COLOR_TYPE_GRAY, 16},
        PngKind{"grey8_trns", PNG_COLOR_TYPE_GRAY, 8, true},
        PngKind{"grey16_trns", PNG_COLOR_TYPE_GRAY, 16, true},
        PngKind{"grey_alpha8", PNG_COLOR_TYPE_GRAY_ALPHA, 8, true},
        PngKind{"grey_alpha16", PNG_COLOR_TYPE_GRAY_ALPHA, 16, true},
        PngKind{"grey_alpha8_opaque", PNG_COLOR_TYPE_GRAY_ALPHA, 8},
        PngKind{"rgb8", PNG_COLOR_TYPE_RGB, 8}, PngKind{"rgb16", PNG_COLOR_TYPE_RGB, 16},
        PngKind{"rgb8_trns", PNG_COLOR_TYPE_RGB, 8, true},
        PngKind{"rgba8", PNG_COLOR_TYPE_RGB_ALPHA, 8, true},
        PngKind{"rgba16", PNG_COLOR_TYPE_RGB_ALPHA, 16, true},
        PngKind{"rgba8_opaque", PNG_COLOR_TYPE_RGB_ALPHA, 8},
        PngKind{"palette1", PNG_COLOR_TYPE_PALETTE, 1},
        PngKind{"palette4", PNG_COLOR_TYPE_PALETTE, 4},
        PngKind{"palette8", PNG_COLOR_TYPE_PALETTE, 8},
        PngKind{"palette8_trns", PNG_COLOR_TYPE_PALETTE, 8, true},
        PngKind{"grey8_interlaced", PNG_COLOR_TYPE_GRAY, 8, false, true},
        PngKind{"rgba16_interlaced", PNG_COLOR_TYPE_RGB_ALPHA, 16, true, true}),
    [](const ::testing::TestParamInfo<PngKind>& kind) { return std::string(kind.param.name); });

TEST(RosMapPng, ProjectsOwnWritePngReadsAsItsGrey) {
  const TempDir dir;
  const std::vector<std::uint8_t> levels = test_levels(8);
  dir.write("map.pgm", p5(kTestWidth, kTestHeight, levels));
  RgbImage image(kTestWidth, kTestHeight);
  for (int i = 0; i < kTestWidth * kTestHeight; ++i) {
    const std::uint8_t v = levels[static_cast<std::size_t>(i)];
    image.set(i % kTestWidth, i / kTestWidth, {v, v, v});
  }
  write_png(dir / "map.png", image);
  for (const std::string mode : {"", "trinary", "scale", "raw"}) {
    SCOPED_TRACE("mode \"" + mode + "\"");
    const RosMap oracle = read_ros_map(dir.write("pgm.yaml", mode_yaml("map.pgm", mode, false)));
    const RosMap map = read_ros_map(dir.write("png.yaml", mode_yaml("map.png", mode, false)));
    ASSERT_EQ(map.grid.cells.size(), oracle.grid.cells.size());
    for (std::size_t i = 0; i < map.grid.cells.size(); ++i) {
      EXPECT_TRUE(same_cell(map.grid.cells[i], oracle.grid.cells[i])) << "cell " << i;
    }
  }
}

std::string grey8_png() {
  return encode_levels(PngKind{"grey8", PNG_COLOR_TYPE_GRAY, 8}, test_levels(8)).bytes;
}

TEST(RosMapPng, PngIsKnownBySignatureNotByName) {
  const TempDir dir;
  const std::vector<std::uint8_t> levels = test_levels(8);
  dir.write("pgm.yaml", mode_yaml("pgm.png", "", false));
  dir.write("png.yaml", mode_yaml("png.pgm", "", false));
  dir.write("pgm.png", p5(kTestWidth, kTestHeight, levels));
  dir.write("png.pgm", grey8_png());
  const RosMap from_pgm = read_ros_map(dir / "pgm.yaml");
  const RosMap from_png = read_ros_map(dir / "png.yaml");
  EXPECT_TRUE(from_png.grid.cells == from_pgm.grid.cells);
  EXPECT_DOUBLE_EQ(from_pgm.grid.at(0, kTestHeight - 1), 1.0 - levels[0] / 255.0);
}

TEST(RosMapPng, NeitherPngNorPgmIsAMagicError) {
  const TempDir dir;
  const auto image = dir.write("map.png", "GIF89a...");
  const auto yaml = dir.write("map.yaml", mode_yaml("map.png", "", false));
  const std::string message = expect_input_error([&] { read_ros_map(yaml); }, image, 1, "magic");
  EXPECT_THAT(message, HasSubstr("PNG signature"));
}

// A PNG's chunks: offset of each chunk's length field, by type.
std::size_t chunk_offset(const std::string& png, const std::string& type) {
  std::size_t offset = 8;
  while (offset + 8 <= png.size()) {
    const auto byte = [&](std::size_t i) {
      return static_cast<std::uint32_t>(static_cast<unsigned char>(png[i]));
    };
    const std::uint32_t length =
        byte(offset) << 24 | byte(offset + 1) << 16 | byte(offset + 2) << 8 | byte(offset + 3);
    if (png.compare(offset + 4, 4, type) == 0) return offset;
    offset += 12 + length;
  }
  throw std::runtime_error("no " + type + " chunk");
}

std::uint32_t crc32(std::string_view bytes) {
  std::uint32_t crc = 0xffffffffu;
  for (const char c : bytes) {
    crc ^= static_cast<unsigned char>(c);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string be32(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
          static_cast<char>(v)};
}

std::string chunk(const std::string& type, const std::string& data) {
  return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(crc32(type + data));
}

const std::string kPngSignature("\x89PNG\r\n\x1a\n", 8);

std::string ihdr(std::uint32_t width, std::uint32_t height) {
  return chunk("IHDR", be32(width) + be32(height) + std::string("\x08\x00\x00\x00\x00", 5));
}

TEST(RosMapPng, TruncatedPngNamesFileAndWhereItEnds) {
  const TempDir dir;
  const std::string png = grey8_png();
  const auto yaml = dir.write("map.yaml", mode_yaml("map.png", "trinary", false));
  const std::size_t idat = chunk_offset(png, "IDAT");
  const std::size_t iend = chunk_offset(png, "IEND");
  const std::vector<std::pair<std::size_t, std::string>> cuts = {
      {20, "header"},         // inside IHDR
      {idat, "header"},       // before the image data
      {idat + 20, "pixels"},  // inside it
      {iend, "pixels"},       // all of it, but not the end chunk
      {png.size() - 1, "pixels"}};
  for (const auto& [size, field] : cuts) {
    SCOPED_TRACE("cut to " + std::to_string(size) + " bytes");
    const auto image = dir.write("map.png", png.substr(0, size));
    const std::string message = expect_input_error([&] { read_ros_map(yaml); }, image, 0, field);
    EXPECT_THAT(message, HasSubstr("truncated PNG"));
    EXPECT_THAT(message, HasSubstr("ends after " + std::to_string(size) + " bytes"));
  }
}

TEST(RosMapPng, CorruptPngNamesFileAndLibpngsReason) {
  const TempDir dir;
  const std::string png = grey8_png();
  const auto yaml = dir.write("map.yaml", mode_yaml("map.png", "", false));

  std::string bad_crc = png;
  bad_crc[chunk_offset(png, "IDAT") + 10] ^= 0x01;
  auto image = dir.write("map.png", bad_crc);
  std::string message = expect_input_error([&] { read_ros_map(yaml); }, image, 0, "pixels");
  EXPECT_THAT(message, HasSubstr("corrupt PNG"));
  EXPECT_THAT(message, HasSubstr("CRC"));

  std::string bad_header = png;
  bad_header[8 + 8 + 2] ^= 0x01;  // a byte of the width
  image = dir.write("map.png", bad_header);
  message = expect_input_error([&] { read_ros_map(yaml); }, image, 0, "header");
  EXPECT_THAT(message, HasSubstr("IHDR"));

  // Bad compressed data behind a correct CRC: zlib's complaint.
  const std::size_t idat = chunk_offset(png, "IDAT");
  const auto length = static_cast<std::size_t>(static_cast<unsigned char>(png[idat + 2]) << 8 |
                                               static_cast<unsigned char>(png[idat + 3]));
  std::string data = png.substr(idat + 8, length);
  data[0] = '\x00';  // the zlib header's method byte
  image = dir.write("map.png",
                    png.substr(0, idat) + chunk("IDAT", data) + png.substr(idat + 12 + length));
  message = expect_input_error([&] { read_ros_map(yaml); }, image, 0, "pixels");
  EXPECT_THAT(message, HasSubstr("corrupt PNG"));
}

TEST(RosMapPng, HugePngIsRejectedBeforeDecoding) {
  const TempDir dir;
  const auto image = dir.write(
      "map.png", kPngSignature + ihdr(65536, 65536) + chunk("IDAT", "") + chunk("IEND", ""));
  const auto yaml = dir.write("map.yaml", mode_yaml("map.png", "", false));
  const std::string message = expect_input_error([&] { read_ros_map(yaml); }, image, 0, "height");
  EXPECT_THAT(message, HasSubstr("exceeds 2^31"));
}

TEST(RosMapPng, PngWiderThanLibpngsDefaultLimitIsNotRejectedForItsSize) {
  const TempDir dir;
  // 2^20 + 1 columns, above libpng's default 10^6; the image data is missing, so decoding
  // fails, but on the pixels, not the size.
  const auto image = dir.write(
      "map.png", kPngSignature + ihdr((1u << 20) + 1, 1) + chunk("IDAT", "") + chunk("IEND", ""));
  const auto yaml = dir.write("map.yaml", mode_yaml("map.png", "", false));
  expect_input_error([&] { read_ros_map(yaml); }, image, 0, "pixels");
}

TEST(RosMapPng, ZeroWidthPngIsAHeaderError) {
  const TempDir dir;
  const auto image =
      dir.write("map.png", kPngSignature + ihdr(0, 4) + chunk("IDAT", "") + chunk("IEND", ""));
  const auto yaml = dir.write("map.yaml", mode_yaml("map.png", "", false));
  const std::string message = expect_input_error([&] { read_ros_map(yaml); }, image, 0, "header");
  EXPECT_THAT(message, HasSubstr("corrupt PNG"));
}

}  // namespace
}  // namespace intgrid
