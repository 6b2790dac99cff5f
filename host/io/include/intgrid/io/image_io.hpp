// Pictures for people: an RGB image, a PNG writer, and drawing in world coordinates over a
// rendered occupancy grid.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/types.hpp"

namespace intgrid::io {

struct Rgb {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
};

// 8-bit RGB pixels, row 0 at the top, 3 bytes a pixel.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;

  RgbImage() = default;
  // Throws std::invalid_argument unless both sizes are positive.
  RgbImage(int width, int height, Rgb fill = {255, 255, 255});

  bool contains(int x, int y_from_top) const {
    return x >= 0 && y_from_top >= 0 && x < width && y_from_top < height;
  }
  // Points outside the image are ignored, so drawing clips at the border.
  void set(int x, int y_from_top, Rgb color);
  // Requires contains(x, y_from_top).
  Rgb get(int x, int y_from_top) const;
};

// Writes image as an 8-bit RGB PNG, atomically. Throws std::invalid_argument if the pixel
// buffer does not match the size, std::runtime_error if encoding or writing fails.
void write_png(const std::filesystem::path& file, const RgbImage& image);

// How a probability of occupancy becomes a colour.
enum class ProbabilityScale {
  // grey = 255 * (1 - p), as map_server reads it: black occupied, white free.
  grey,
  // White at 1/2, toward blue for free and red for occupied, linear in p - 1/2 and saturated
  // from |p - 1/2| = kDivergingSaturation on: large-FOV ISMs barely leave 1/2.
  diverging,
};
inline constexpr double kDivergingSaturation = 0.1;

// The colour of p on scale; NaN (no cell there, e.g. outside a sensor's FOV) takes the
// scale's background colour, which no probability has.
Rgb probability_color(double p, ProbabilityScale scale);

// pixels_per_cell x pixels_per_cell pixels per cell, coloured on scale, the top image row the
// top of the map. Throws std::invalid_argument unless pixels_per_cell >= 1.
RgbImage render_probability_grid(const core::ProbabilityGrid& grid,
                                 ProbabilityScale scale = ProbabilityScale::grey,
                                 int pixels_per_cell = 1);

// Copies picture into canvas with its top-left corner at (x, y_from_top), clipped to canvas.
void draw_image(RgbImage& canvas, const RgbImage& picture, int x, int y_from_top);

// Draws straight lines between consecutive poses (x, y only) in the image of a grid with
// geometry, clipped to the image; poses with non-finite coordinates break the line.
void draw_polyline_world(RgbImage& image, const core::GridGeometry& geometry,
                         const std::vector<core::Pose2>& poses, Rgb color);

// Draws a filled disc of radius_px pixels (0 = one pixel) around the world point (x, y).
void draw_marker_world(RgbImage& image, const core::GridGeometry& geometry, double x, double y,
                       int radius_px, Rgb color);

}  // namespace intgrid::io
