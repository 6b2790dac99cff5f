// The map reader and writer on the bundled ROS maps, and a picture of the telecom map.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "data_dir.hpp"
#include "intgrid/io/image_io.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/io/map_io.hpp"
#include "test_support.hpp"

using namespace intgrid::core;

using namespace intgrid::io;

namespace intgrid {
namespace {

const std::filesystem::path kDataDir = test::data_dir();

TEST(BundledMaps, RoomMapGeometry) {
  const RosMap map = read_ros_map(kDataDir / "malaga_room_map.yaml");
  const GridGeometry& geometry = map.grid.geometry;
  EXPECT_EQ(geometry.width, 700);
  EXPECT_EQ(geometry.height, 650);
  EXPECT_EQ(geometry.resolution, 0.04);
  EXPECT_EQ(geometry.origin_x, -10.0);
  EXPECT_EQ(geometry.origin_y, -10.0);
  EXPECT_EQ(map.occupied_thresh, 0.65);
  EXPECT_EQ(map.free_thresh, 0.196);
  EXPECT_FALSE(map.negate);
  // The first PGM byte (top-left) is 0x80, unknown; it is the top row of the grid.
  EXPECT_DOUBLE_EQ(map.grid.at(0, 649), 127.0 / 255.0);
}

TEST(BundledMaps, TelecomMapGeometry) {
  const GridGeometry geometry = read_ros_map(kDataDir / "malaga_telecom_map.yaml").grid.geometry;
  EXPECT_EQ(geometry.width, 1700);
  EXPECT_EQ(geometry.height, 1740);
  EXPECT_EQ(geometry.resolution, 0.05);
  EXPECT_EQ(geometry.origin_x, -45.0);
  EXPECT_EQ(geometry.origin_y, -51.0);
}

// The bundled map's YAML with image and an optional mode in place of its own.
std::string room_yaml(const std::filesystem::path& image, const std::string& mode) {
  std::string yaml = "image: " + image.string() +
                     "\nresolution: 0.04\norigin: [-10, -10, 0.0]\nnegate: 0\n"
                     "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
  if (!mode.empty()) yaml += "mode: " + mode + "\n";
  return yaml;
}

bool same_cell(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || a == b;
}

TEST(BundledMaps, RoomMapAsPngReadsAsItsPgmInEveryMode) {
  const test::TempDir dir;
  const RosMap linear = read_ros_map(kDataDir / "malaga_room_map.yaml");
  const GridGeometry& geometry = linear.grid.geometry;
  RgbImage image(geometry.width, geometry.height);
  for (int iy = 0; iy < geometry.height; ++iy) {
    for (int ix = 0; ix < geometry.width; ++ix) {
      const std::uint8_t v = probability_to_pixel(linear.grid.at(ix, iy));
      image.set(ix, geometry.height - 1 - iy, {v, v, v});
    }
  }
  write_png(dir / "room.png", image);
  for (const std::string mode : {"", "trinary", "scale", "raw"}) {
    SCOPED_TRACE("mode \"" + mode + "\"");
    const RosMap pgm =
        read_ros_map(dir.write("pgm.yaml", room_yaml(kDataDir / "malaga_room_map.pgm", mode)));
    const RosMap png = read_ros_map(dir.write("png.yaml", room_yaml(dir / "room.png", mode)));
    test::expect_same_geometry(png.grid.geometry, pgm.grid.geometry);
    ASSERT_EQ(png.grid.cells.size(), pgm.grid.cells.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < pgm.grid.cells.size(); ++i) {
      differing += !same_cell(png.grid.cells[i], pgm.grid.cells[i]);
    }
    EXPECT_EQ(differing, 0u);
    if (mode.empty()) {
      EXPECT_TRUE(pgm.grid.cells == linear.grid.cells);
    }
  }
}

// On the real map, trinary and scale against the thresholds applied to the mode-less grid.
TEST(BundledMaps, RoomMapTrinaryAndScaleFollowTheThresholds) {
  const test::TempDir dir;
  const auto pgm = kDataDir / "malaga_room_map.pgm";
  const RosMap linear = read_ros_map(kDataDir / "malaga_room_map.yaml");
  const RosMap trinary = read_ros_map(dir.write("trinary.yaml", room_yaml(pgm, "trinary")));
  const RosMap scale = read_ros_map(dir.write("scale.yaml", room_yaml(pgm, "scale")));
  std::size_t occupied = 0, free = 0, unknown = 0, wrong = 0;
  for (std::size_t i = 0; i < linear.grid.cells.size(); ++i) {
    const double p = linear.grid.cells[i];
    // No pixel of the map lies within rounding of the thresholds, so either formula decides.
    const double expected = p > 0.65 ? 1.0 : p < 0.196 ? 0.0 : std::nan("");
    occupied += expected == 1.0;
    free += expected == 0.0;
    unknown += std::isnan(expected);
    wrong += !same_cell(trinary.grid.cells[i], expected);
    const double kept = std::isnan(expected) ? p : expected;
    wrong += !(std::abs(scale.grid.cells[i] - kept) <= 1e-15);
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(occupied, 0u);
  EXPECT_GT(free, 0u);
  EXPECT_GT(unknown, 0u);
}

class BundledMapRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(BundledMapRoundTrip, WriteThenReadIsIdentical) {
  const test::TempDir dir;
  const RosMap original = read_ros_map(kDataDir / (GetParam() + ".yaml"));
  write_ros_map(dir / "copy.yaml", original);
  const RosMap copy = read_ros_map(dir / "copy.yaml");

  test::expect_same_geometry(copy.grid.geometry, original.grid.geometry);
  EXPECT_EQ(copy.occupied_thresh, original.occupied_thresh);
  EXPECT_EQ(copy.free_thresh, original.free_thresh);
  EXPECT_TRUE(copy.grid.cells == original.grid.cells);
  // Same header layout and pixels: the written PGM is the bundled one, byte for byte.
  EXPECT_TRUE(test::read_bytes(dir / "copy.pgm") ==
              test::read_bytes(kDataDir / (GetParam() + ".pgm")));
}

INSTANTIATE_TEST_SUITE_P(BundledMaps, BundledMapRoundTrip,
                         ::testing::Values("malaga_room_map", "malaga_telecom_map"));

TEST(BundledMaps, TelecomMapPictureWithReferenceTrajectory) {
  const test::TempDir dir;
  const RosMap map = read_ros_map(kDataDir / "malaga_telecom_map.yaml");
  RgbImage image = render_probability_grid(map.grid);
  std::vector<Pose2> trajectory;
  for (const Scan& scan : read_log(kDataDir / "malaga_telecom_loop_reference.log").scans) {
    trajectory.push_back(scan.robot);
  }
  const Rgb red{255, 0, 0};
  draw_polyline_world(image, map.grid.geometry, trajectory, red);
  draw_marker_world(image, map.grid.geometry, trajectory[0].x, trajectory[0].y, 6, red);
  write_png(dir / "telecom.png", image);

  const std::string bytes = test::read_bytes(dir / "telecom.png");
  ASSERT_GT(bytes.size(), 24u);
  EXPECT_EQ(bytes.substr(0, 8), "\x89PNG\r\n\x1a\n");
  EXPECT_EQ(bytes.substr(16, 8), std::string("\x00\x00\x06\xa4\x00\x00\x06\xcc", 8))
      << "1700 x 1740";
  // The reference trajectory lies on the map, so the red line is drawn.
  const GridGeometry& geometry = map.grid.geometry;
  const int start_x = geometry.cell_x(trajectory[0].x);
  const int start_y = geometry.height - 1 - geometry.cell_y(trajectory[0].y);
  const Rgb start = image.get(start_x, start_y);
  EXPECT_EQ(start.r, 255);
  EXPECT_EQ(start.g, 0);
}

}  // namespace
}  // namespace intgrid
