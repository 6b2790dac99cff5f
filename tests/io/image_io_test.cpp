// Pictures: PNG output, grid rendering and drawing in world coordinates.
#include "intgrid/io/image_io.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "test_support.hpp"

using namespace intgrid::core;

using namespace intgrid::io;

namespace intgrid {
namespace {

using test::TempDir;

constexpr Rgb kRed{255, 0, 0};

bool same(Rgb a, Rgb b) {
  return a.r == b.r && a.g == b.g && a.b == b.b;
}

std::uint32_t big_endian_u32(const std::string& bytes, std::size_t offset) {
  std::uint32_t value = 0;
  for (std::size_t i = 0; i < 4; ++i)
    value = value << 8 | static_cast<std::uint8_t>(bytes[offset + i]);
  return value;
}

// Decodes a PNG file with libpng into 8-bit RGB.
RgbImage decode_png(const std::filesystem::path& file) {
  png_image description{};
  description.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_file(&description, file.c_str()) == 0) {
    throw std::runtime_error(description.message);
  }
  description.format = PNG_FORMAT_RGB;
  RgbImage image(static_cast<int>(description.width), static_cast<int>(description.height));
  if (png_image_finish_read(&description, nullptr, image.rgb.data(), 0, nullptr) == 0) {
    throw std::runtime_error(description.message);
  }
  return image;
}

int count_pixels(const RgbImage& image, Rgb color) {
  int count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) count += same(image.get(x, y), color) ? 1 : 0;
  }
  return count;
}

TEST(Png, FileHasSignatureHeaderAndPixels) {
  const TempDir dir;
  RgbImage image(5, 3, {10, 20, 30});
  image.set(4, 0, kRed);
  write_png(dir / "out.png", image);

  const std::string bytes = test::read_bytes(dir / "out.png");
  ASSERT_GT(bytes.size(), 33u);
  EXPECT_EQ(bytes.substr(0, 8), "\x89PNG\r\n\x1a\n");
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_EQ(big_endian_u32(bytes, 16), 5u);
  EXPECT_EQ(big_endian_u32(bytes, 20), 3u);
  EXPECT_EQ(bytes[24], 8) << "bit depth";
  EXPECT_EQ(bytes[25], 2) << "colour type RGB";

  const RgbImage decoded = decode_png(dir / "out.png");
  EXPECT_EQ(decoded.rgb, image.rgb);
  EXPECT_EQ(dir.entry_count(), 1u);
}

TEST(Png, InconsistentImageWritesNothing) {
  const TempDir dir;
  RgbImage image(4, 4);
  image.rgb.pop_back();
  EXPECT_THROW(write_png(dir / "bad.png", image), std::invalid_argument);
  EXPECT_EQ(dir.entry_count(), 0u);
  EXPECT_THROW(RgbImage(0, 4), std::invalid_argument);
}

TEST(RgbImage, SetOutsideTheImageIsIgnored) {
  RgbImage image(2, 2);
  image.set(-1, 0, kRed);
  image.set(0, 2, kRed);
  EXPECT_EQ(count_pixels(image, kRed), 0);
  image.set(1, 1, kRed);
  EXPECT_TRUE(same(image.get(1, 1), kRed));
  EXPECT_EQ(image.rgb[9], 255);  // pixel (1, 1) starts at byte (1 * 2 + 1) * 3
}

TEST(RenderProbabilityGrid, TopImageRowIsTopOfTheMap) {
  ProbabilityGrid grid({2, 2, 1.0, 0.0, 0.0}, 0.5);
  grid.at(0, 1) = 1.0;  // top left: occupied
  grid.at(1, 0) = 0.0;  // bottom right: free
  const RgbImage image = render_probability_grid(grid);
  ASSERT_EQ(image.width, 2);
  ASSERT_EQ(image.height, 2);
  EXPECT_TRUE(same(image.get(0, 0), {0, 0, 0}));
  EXPECT_TRUE(same(image.get(1, 1), {255, 255, 255}));
  EXPECT_TRUE(same(image.get(1, 0), {128, 128, 128}));
  EXPECT_TRUE(same(image.get(0, 1), {128, 128, 128}));
}

// 10 x 10 cells of 1 m with the lower-left corner at the world origin.
const GridGeometry kTenByTen{10, 10, 1.0, 0.0, 0.0};

TEST(DrawWorld, PolylineFollowsTheDiagonal) {
  RgbImage image(10, 10);
  draw_polyline_world(image, kTenByTen, {{0.5, 0.5, 0.0}, {9.5, 9.5, 0.0}}, kRed);
  EXPECT_EQ(count_pixels(image, kRed), 10);
  for (int i = 0; i < 10; ++i) EXPECT_TRUE(same(image.get(i, 9 - i), kRed)) << i;
}

TEST(DrawWorld, PolylineJoinsEveryPose) {
  RgbImage image(10, 10);
  draw_polyline_world(image, kTenByTen, {{0.5, 0.5, 0.0}, {0.5, 4.5, 0.0}, {3.5, 4.5, 0.0}}, kRed);
  EXPECT_EQ(count_pixels(image, kRed), 5 + 3);
  EXPECT_TRUE(same(image.get(0, 9), kRed));
  EXPECT_TRUE(same(image.get(3, 5), kRed));
}

TEST(DrawWorld, PolylineIsClippedToTheImage) {
  RgbImage image(10, 10);
  draw_polyline_world(image, kTenByTen, {{-100.0, 5.5, 0.0}, {1e300, 5.5, 0.0}}, kRed);
  EXPECT_EQ(count_pixels(image, kRed), 10);
  for (int x = 0; x < 10; ++x) EXPECT_TRUE(same(image.get(x, 4), kRed)) << x;

  RgbImage across(10, 10);
  draw_polyline_world(across, kTenByTen, {{-1e308, 5.5, 0.0}, {1e308, 5.5, 0.0}}, kRed);
  EXPECT_LE(count_pixels(across, kRed), 10) << "overflowing ends draw nothing or the row";

  RgbImage untouched(10, 10);
  draw_polyline_world(untouched, kTenByTen,
                      {{-50.0, -50.0, 0.0}, {-40.0, 80.0, 0.0}, {NAN, 1.0, 0.0}, {2.0, 2.0, 0.0}},
                      kRed);
  EXPECT_EQ(count_pixels(untouched, kRed), 0);
}

TEST(DrawWorld, MarkerIsADiscOfTheGivenRadius) {
  RgbImage image(10, 10);
  draw_marker_world(image, kTenByTen, 5.5, 4.5, 2, kRed);
  EXPECT_EQ(count_pixels(image, kRed), 13);
  EXPECT_TRUE(same(image.get(5, 5), kRed));
  EXPECT_TRUE(same(image.get(5, 3), kRed));
  EXPECT_FALSE(same(image.get(7, 7), kRed));
}

TEST(DrawWorld, MarkerPartlyOffTheImageIsClipped) {
  RgbImage image(10, 10);
  draw_marker_world(image, kTenByTen, -0.5, 5.5, 1, kRed);
  EXPECT_EQ(count_pixels(image, kRed), 1);
  draw_marker_world(image, kTenByTen, 1e300, 5.5, 1, kRed);
  EXPECT_EQ(count_pixels(image, kRed), 1);
}

}  // namespace
}  // namespace intgrid
