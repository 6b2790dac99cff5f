// Pictures and tables of a sensor's local polar grid. A picture is the fan of its FOV in
// cartesian space, the sensor at the bottom centre looking up, each pixel the colour of the
// polar cell its centre falls in.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <numbers>
#include <ostream>
#include <span>
#include <string_view>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/sectoral_ism.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/io/image_io.hpp"

namespace intgrid::figures {

// Angles in degrees for people; whole degrees make the round trip exactly.
inline double radians(double degrees) {
  return degrees / 180.0 * std::numbers::pi;
}
inline double degrees(double radians) {
  return radians / std::numbers::pi * 180.0;
}

// fov_deg, rings, bins, sectors, cell.
nlohmann::json polar_grid_json(const core::SectoralGrid& grid);

// A world grid of one cell per pixel around a sensor's FOV, and the sensor's pose in it: draw
// over the picture in world coordinates with frame.geometry.
struct PolarFrame {
  core::GridGeometry geometry;
  core::Pose2 sensor;
};

// The frame holding the whole FOV out to the far edge of the last ring, plus a margin of a
// few pixels, at metres_per_pixel. Requires a checked grid; throws std::invalid_argument if
// metres_per_pixel is not positive or the picture would exceed 2^26 pixels.
PolarFrame polar_frame(const core::SectoralGrid& grid, double metres_per_pixel);

// The polar values (ring-major, as sectoral_ism returns them) over frame by the range
// mapping of map_polar; pixels in no polar cell take the scale's background colour.
io::RgbImage render_polar(const PolarFrame& frame, const core::SectoralGrid& grid,
                          std::span<const double> values, io::ProbabilityScale scale);

// Writes one CSV row per polar cell, ring-major: "<prefix>ring,bin,p" with ring and bin
// 1-based and p printed exactly (%.17g), then ",index" when indices are given (one per cell).
void write_polar_csv_rows(std::ostream& csv, std::string_view prefix,
                          const core::SectoralGrid& grid, std::span<const double> p,
                          std::span<const std::int16_t> indices = {});

}  // namespace intgrid::figures
