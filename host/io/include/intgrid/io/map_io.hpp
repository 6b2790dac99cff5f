// ROS map_server maps: a YAML file describing a PGM or PNG image whose first row is the top of
// the map. Every problem in an input file is an InputError naming file, line and field.
#pragma once

#include <cstdint>
#include <filesystem>

#include "intgrid/core/grid.hpp"

namespace intgrid::io {

struct RosMap {
  // P(occupied) per cell, NaN where the map says unknown; row 0 is the bottom of the map
  core::ProbabilityGrid grid;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  bool negate = false;
};

// Reads the YAML (keys image, resolution, origin [x, y, 0], negate 0 or 1, occupied_thresh,
// free_thresh, optional mode trinary, scale or raw) and its image. A relative image path is taken
// from the YAML's directory.
//
// The image is a PNG if its first 8 bytes are the PNG signature, whatever its name, and a PGM
// otherwise: binary P5 or ASCII P2, maxval 255. PNGs may be grey (1 to 16 bits), grey + alpha,
// RGB, RGBA (8 or 16 bits) or palette (a tRNS chunk counts as alpha), interlaced or not; samples
// are taken as stored, without gamma or colour-profile conversion. Either kind holds at most
// 2^31 pixels. A pixel's value v is the mean of its colour channels (grey, or red, green and
// blue; alpha left out), on 0..255 or, for 16-bit PNGs, 0..65535 (read 255 as 65535 below).
// The pixel is opaque if it has no alpha or its alpha is the maximum; any transparency counts.
//
// What a pixel gives its cell (NaN: unknown, as everywhere in intgrid, so that no threshold
// takes it for free or occupied):
//   no mode   P = (255 - v) / 255, or v / 255 when negate is 1: the image's own probability,
//             the thresholds left to whoever uses the map (the reader's behaviour before modes;
//             PGM maps without a mode read exactly as before). Not opaque: NaN.
//   trinary   map_server's p = (255 - v) / 255, or v / 255 when negate is 1. p > occupied_thresh
//             gives 1, p < free_thresh gives 0, anything else NaN. Not opaque: NaN.
//   scale     as trinary, but a p between the thresholds (inclusive) is kept as it is, where
//             map_server would rescale it to 0..100: keeping p keeps it between the thresholds
//             that users of the map apply again. Not opaque: NaN.
//   raw       the value itself is the occupancy in percent: round(v) (16-bit: round(v * 255 /
//             65535)) in 0..100 gives P = value / 100, above 100 NaN. negate and alpha are
//             ignored, as map_server (ROS 2) does.
// Unlike map_server's trinary mode, alpha is never averaged in with the colour channels.
// A PNG that libpng cannot decode, corrupt or cut short, is an InputError on the image, field
// header or pixels by where it fails; a mode other than the three is one on the YAML's line of
// field mode.
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
