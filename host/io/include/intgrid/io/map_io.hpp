// ROS map_server maps: a YAML file describing an 8-bit PGM image whose first row is the top of
// the map. Every problem in an input file is an InputError naming file, line and field.
#pragma once

#include <cstdint>
#include <filesystem>

#include "intgrid/core/grid.hpp"

namespace intgrid::io {

struct RosMap {
  core::ProbabilityGrid grid;  // P(occupied) per cell; row 0 is the bottom of the map
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  bool negate = false;
};

// Reads the YAML (keys image, resolution, origin [x, y, 0], negate, occupied_thresh,
// free_thresh; optional mode trinary or scale) and its PGM (binary P5 or ASCII P2, maxval 255).
// A relative image path is taken from the YAML's directory. Pixel v gives P = (255 - v) / 255,
// or v / 255 when negate is 1.
RosMap read_ros_map(const std::filesystem::path& yaml);

// Writes yaml and, beside it, a binary PGM of the same stem with extension .pgm, each atomically
// (the PGM first, so the YAML never names a missing image). Reading back gives every cell within
// 1/510. Throws std::invalid_argument for an unusable grid or thresholds, std::runtime_error if
// writing fails.
void write_ros_map(const std::filesystem::path& yaml, const RosMap& map);

// The PGM pixel of a cell with P(occupied) p (clamped to [0, 1]; NaN, which carries no
// information, gives the unknown value 128): round(255 * (1 - p)), or round(255 * p) if negate.
std::uint8_t probability_to_pixel(double p, bool negate = false);

}  // namespace intgrid::io
