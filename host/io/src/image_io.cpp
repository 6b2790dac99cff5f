#include "intgrid/io/image_io.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>

#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/map_io.hpp"

namespace intgrid::io {
namespace {

constexpr std::size_t kChannels = 3;

std::size_t pixel_offset(const RgbImage& image, int x, int y_from_top) {
  return (static_cast<std::size_t>(y_from_top) * static_cast<std::size_t>(image.width) +
          static_cast<std::size_t>(x)) *
         kChannels;
}

void check_size(int width, int height) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("image size must be positive, got " + std::to_string(width) +
                                " x " + std::to_string(height));
  }
}

void check_image(const RgbImage& image) {
  check_size(image.width, image.height);
  const std::size_t expected =
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * kChannels;
  if (image.rgb.size() != expected) {
    throw std::invalid_argument("image holds " + std::to_string(image.rgb.size()) +
                                " bytes, its size needs " + std::to_string(expected));
  }
}

// The PNG file in memory. libpng's simplified API reports errors in the png_image instead of
// by longjmp, which would skip C++ destructors.
std::vector<std::uint8_t> encode_png(const std::filesystem::path& file, const RgbImage& image) {
  png_image description{};
  description.version = PNG_IMAGE_VERSION;
  description.width = static_cast<png_uint_32>(image.width);
  description.height = static_cast<png_uint_32>(image.height);
  description.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> encoded(PNG_IMAGE_PNG_SIZE_MAX(description));
  png_alloc_size_t size = encoded.size();
  const bool encoded_ok = png_image_write_to_memory(&description, encoded.data(), &size, 0,
                                                    image.rgb.data(), 0, nullptr) != 0;
  png_image_free(&description);
  if (!encoded_ok) {
    throw std::runtime_error("cannot write " + file.string() + ": " + description.message);
  }
  encoded.resize(size);
  return encoded;
}

// The cell holding a world point, in image pixels (row counted from the top), as doubles so
// that points far off the map do not overflow an int.
struct PixelPoint {
  double x;
  double y;
};

PixelPoint world_to_pixel(const core::GridGeometry& geometry, double x, double y) {
  const double column = std::floor((x - geometry.origin_x) / geometry.resolution);
  const double row = std::floor((y - geometry.origin_y) / geometry.resolution);
  return {column, geometry.height - 1 - row};
}

bool is_finite(const PixelPoint& p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

// Liang-Barsky: cuts the segment a-b down to the box [0, x_max] x [0, y_max]; false if no part
// of it lies inside.
bool clip_segment(PixelPoint& a, PixelPoint& b, double x_max, double y_max) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double directions[4] = {-dx, dx, -dy, dy};
  const double distances[4] = {a.x, x_max - a.x, a.y, y_max - a.y};
  double enter = 0.0, leave = 1.0;
  for (int side = 0; side < 4; ++side) {
    const double p = directions[side], q = distances[side];
    if (p == 0.0) {
      if (q < 0.0) return false;
      continue;
    }
    const double t = q / p;
    if (p < 0.0) {
      enter = std::max(enter, t);
    } else {
      leave = std::min(leave, t);
    }
  }
  if (!(enter <= leave)) return false;
  const PixelPoint start = a;
  a = {start.x + enter * dx, start.y + enter * dy};
  b = {start.x + leave * dx, start.y + leave * dy};
  return true;
}

void draw_line_pixels(RgbImage& image, int x0, int y0, int x1, int y1, Rgb color) {
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int step_x = x0 < x1 ? 1 : -1, step_y = y0 < y1 ? 1 : -1;
  int error = dx + dy;
  for (;;) {
    image.set(x0, y0, color);
    if (x0 == x1 && y0 == y1) return;
    const int doubled = 2 * error;
    if (doubled >= dy) {
      error += dy;
      x0 += step_x;
    }
    if (doubled <= dx) {
      error += dx;
      y0 += step_y;
    }
  }
}

void draw_segment(RgbImage& image, PixelPoint a, PixelPoint b, Rgb color) {
  // Ends near the double range can overflow the clipping arithmetic to NaN.
  if (!clip_segment(a, b, image.width - 1, image.height - 1) || !is_finite(a) || !is_finite(b)) {
    return;
  }
  const auto pixel = [](double v) { return static_cast<int>(std::lround(v)); };
  draw_line_pixels(image, pixel(a.x), pixel(a.y), pixel(b.x), pixel(b.y), color);
}

}  // namespace

RgbImage::RgbImage(int image_width, int image_height, Rgb fill)
    : width(image_width), height(image_height) {
  check_size(width, height);
  rgb.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * kChannels);
  for (std::size_t i = 0; i < rgb.size(); i += kChannels) {
    rgb[i] = fill.r;
    rgb[i + 1] = fill.g;
    rgb[i + 2] = fill.b;
  }
}

void RgbImage::set(int x, int y_from_top, Rgb color) {
  if (!contains(x, y_from_top)) return;
  const std::size_t offset = pixel_offset(*this, x, y_from_top);
  rgb[offset] = color.r;
  rgb[offset + 1] = color.g;
  rgb[offset + 2] = color.b;
}

Rgb RgbImage::get(int x, int y_from_top) const {
  const std::size_t offset = pixel_offset(*this, x, y_from_top);
  return {rgb[offset], rgb[offset + 1], rgb[offset + 2]};
}

void write_png(const std::filesystem::path& file, const RgbImage& image) {
  check_image(image);
  const std::vector<std::uint8_t> encoded = encode_png(file, image);
  write_file_atomically(
      file, std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

Rgb probability_color(double p, ProbabilityScale scale) {
  if (scale == ProbabilityScale::grey) {
    if (std::isnan(p)) return {190, 215, 240};
    const std::uint8_t grey = probability_to_pixel(p);
    return {grey, grey, grey};
  }
  if (std::isnan(p)) return {150, 150, 150};
  const double t = std::clamp((p - 0.5) / kDivergingSaturation, -1.0, 1.0);
  const Rgb end = t > 0.0 ? Rgb{178, 24, 43} : Rgb{33, 102, 172};
  const auto towards = [w = std::abs(t)](std::uint8_t channel) {
    return static_cast<std::uint8_t>(std::lround(255.0 + w * (channel - 255.0)));
  };
  return {towards(end.r), towards(end.g), towards(end.b)};
}

RgbImage render_probability_grid(const core::ProbabilityGrid& grid, ProbabilityScale scale,
                                 int pixels_per_cell) {
  if (pixels_per_cell < 1) throw std::invalid_argument("pixels per cell must be at least 1");
  const core::GridGeometry& geometry = grid.geometry;
  RgbImage image(geometry.width * pixels_per_cell, geometry.height * pixels_per_cell);
  for (int iy = 0; iy < geometry.height; ++iy) {
    const int top = (geometry.height - 1 - iy) * pixels_per_cell;
    for (int ix = 0; ix < geometry.width; ++ix) {
      const Rgb color = probability_color(grid.at(ix, iy), scale);
      for (int dy = 0; dy < pixels_per_cell; ++dy)
        for (int dx = 0; dx < pixels_per_cell; ++dx)
          image.set(ix * pixels_per_cell + dx, top + dy, color);
    }
  }
  return image;
}

void draw_image(RgbImage& canvas, const RgbImage& picture, int x, int y_from_top) {
  for (int row = 0; row < picture.height; ++row)
    for (int column = 0; column < picture.width; ++column)
      canvas.set(x + column, y_from_top + row, picture.get(column, row));
}

void draw_polyline_world(RgbImage& image, const core::GridGeometry& geometry,
                         const std::vector<core::Pose2>& poses, Rgb color) {
  for (std::size_t i = 0; i + 1 < poses.size(); ++i) {
    const PixelPoint a = world_to_pixel(geometry, poses[i].x, poses[i].y);
    const PixelPoint b = world_to_pixel(geometry, poses[i + 1].x, poses[i + 1].y);
    if (is_finite(a) && is_finite(b)) draw_segment(image, a, b, color);
  }
  if (poses.size() == 1) draw_marker_world(image, geometry, poses[0].x, poses[0].y, 0, color);
}

void draw_marker_world(RgbImage& image, const core::GridGeometry& geometry, double x, double y,
                       int radius_px, Rgb color) {
  const PixelPoint centre = world_to_pixel(geometry, x, y);
  const double radius = std::max(radius_px, 0);
  // Discs wholly off the image are skipped before their centre is cast to int.
  if (!is_finite(centre) || centre.x < -radius || centre.y < -radius ||
      centre.x > image.width - 1 + radius || centre.y > image.height - 1 + radius) {
    return;
  }
  const int cx = static_cast<int>(centre.x), cy = static_cast<int>(centre.y);
  const int r = static_cast<int>(radius);
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      if (dx * dx + dy * dy <= r * r) image.set(cx + dx, cy + dy, color);
    }
  }
}

}  // namespace intgrid::io
