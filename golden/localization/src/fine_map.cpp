#include "intgrid/localization/fine_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "intgrid/core/failure.hpp"
#include "intgrid/localization/claim_table.hpp"

namespace intgrid::localization {
namespace {
constexpr std::int64_t kOne = std::int64_t{1} << FineMap::kPositionBits;  // one cell

// Chebyshev distance transform of the occupied cells (two passes, 8-neighbour unit steps), capped.
void chebyshev_clearance(std::vector<std::uint8_t>& d, int w, int h, int cap) {
  const auto at = [&](int x, int y) -> std::uint8_t& {
    return d[std::size_t(y) * std::size_t(w) + std::size_t(x)];
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int v = at(x, y);
      if (x > 0) v = std::min(v, at(x - 1, y) + 1);
      if (y > 0)
        for (int dx = -1; dx <= 1; ++dx)
          if (x + dx >= 0 && x + dx < w) v = std::min(v, at(x + dx, y - 1) + 1);
      at(x, y) = static_cast<std::uint8_t>(std::min(v, cap));
    }
  for (int y = h - 1; y >= 0; --y)
    for (int x = w - 1; x >= 0; --x) {
      int v = at(x, y);
      if (x + 1 < w) v = std::min(v, at(x + 1, y) + 1);
      if (y + 1 < h)
        for (int dx = -1; dx <= 1; ++dx)
          if (x + dx >= 0 && x + dx < w) v = std::min(v, at(x + dx, y + 1) + 1);
      at(x, y) = static_cast<std::uint8_t>(std::min(v, cap));
    }
}
}  // namespace

FineMap::FineMap(const core::ProbabilityGrid& map, double occupied_threshold, double free_threshold,
                 int headings)
    : geometry_(map.geometry), headings_(headings) {
  core::check_geometry(geometry_);
  if (map.cells.size() != geometry_.size())
    core::fail<std::invalid_argument>("map: its cell count differs from its geometry");
  if (headings < 4 || headings > 65536)
    core::fail<std::invalid_argument>("headings must be 4..65536, got " + std::to_string(headings));
  // Positions in fixed point and the rays' distances stay far inside 64 bits below 2^31 cells.
  if (geometry_.width >= (1 << 30) || geometry_.height >= (1 << 30))
    core::fail<std::invalid_argument>("map: 2^30 cells or more along an axis");
  const int w = geometry_.width, h = geometry_.height;
  std::vector<std::uint8_t> clearance(geometry_.size(), kMaxClearance);
  for (std::size_t q = 0; q < clearance.size(); ++q)
    if (map.cells[q] >= occupied_threshold) clearance[q] = 0;
  chebyshev_clearance(clearance, w, h, kMaxClearance);
  cells_.resize(geometry_.size());
  for (std::size_t q = 0; q < cells_.size(); ++q)
    cells_[q] =
        static_cast<std::uint8_t>(clearance[q] | (map.cells[q] <= free_threshold ? kFreeBit : 0));

  directions_.resize(std::size_t(headings));
  for (int d = 0; d < headings; ++d) {
    Direction& dir = directions_[std::size_t(d)];
    const double angle = 2.0 * std::numbers::pi * d / headings;
    const double c = std::cos(angle), s = std::sin(angle);
    dir.x_major = std::abs(c) >= std::abs(s);
    dir.sign = (dir.x_major ? c : s) > 0.0 ? 1 : -1;
    dir.slope = std::llround(std::ldexp(dir.x_major ? s / c : c / s, kSlopeBits));
    dir.secant = std::llround(std::ldexp(1.0 / std::max(std::abs(c), std::abs(s)), 16));
  }
}

std::size_t FineMap::bytes_for(const core::GridGeometry& geometry, int headings) {
  return geometry.size() + std::size_t(headings) * sizeof(Direction);
}

double FineMap::heading_bin() const {
  return 2.0 * std::numbers::pi / headings_;
}

double FineMap::units_per_metre() const {
  return double(kOne) / geometry_.resolution;
}

FinePose FineMap::fine_pose(const core::Pose2& sensor) const {
  const double u = units_per_metre();
  const long long k = std::llround(sensor.theta / heading_bin()) % headings_;
  return {std::llround((sensor.x - geometry_.origin_x) * u),
          std::llround((sensor.y - geometry_.origin_y) * u), int(k < 0 ? k + headings_ : k)};
}

core::Pose2 FineMap::pose_of(const FinePose& p) const {
  const double u = units_per_metre();
  return {geometry_.origin_x + double(p.x) / u, geometry_.origin_y + double(p.y) / u,
          core::wrap_angle(p.k * heading_bin())};
}

bool FineMap::is_free(const FinePose& p) const {
  const std::int64_t ix = p.x >> kPositionBits, iy = p.y >> kPositionBits;
  if (ix < 0 || iy < 0 || ix >= geometry_.width || iy >= geometry_.height) return false;
  return (cells_[geometry_.index(int(ix), int(iy))] & kFreeBit) != 0;
}

int FineMap::clearance(int ix, int iy) const {
  return cells_[geometry_.index(ix, iy)] & ~kFreeBit & 0xFF;
}

std::int64_t FineMap::first_hit(std::int64_t x, std::int64_t y, int d, std::int64_t limit) const {
  const Direction& dir = directions_[std::size_t(d)];
  const std::int64_t major0 = dir.x_major ? x : y, minor0 = dir.x_major ? y : x;
  const std::int64_t major_len = dir.x_major ? geometry_.width : geometry_.height;
  const std::int64_t minor_len = dir.x_major ? geometry_.height : geometry_.width;
  const auto w = std::size_t(geometry_.width);
  // The first column whose centre lies ahead of the point, and how far ahead (16 fractional
  // bits, along the major axis).
  std::int64_t u = major0 >> kPositionBits;
  std::int64_t along = ((u << kPositionBits) + kOne / 2 - major0) * dir.sign;
  if (along <= 0) u += dir.sign, along += kOne;
  // The ray's minor coordinate at that column's centre (kSlopeBits fractional bits) and its
  // distance from the point (16 + 16 fractional bits); each column adds one step of both.
  std::int64_t minor =
      (minor0 << (kSlopeBits - kPositionBits)) + ((along * dir.sign * dir.slope) >> kPositionBits);
  std::int64_t distance = along * dir.secant;
  const std::int64_t minor_step = dir.sign * dir.slope, distance_step = dir.secant << kPositionBits;
  const std::int64_t bound = limit << (2 * kPositionBits - kDistanceBits);
  while (u >= 0 && u < major_len && distance <= bound) {
    const std::int64_t v = minor >> kSlopeBits;
    if (v < 0 || v >= minor_len) break;
    const std::size_t q =
        dir.x_major ? std::size_t(v) * w + std::size_t(u) : std::size_t(u) * w + std::size_t(v);
    // A column moves the ray at most one cell along the minor axis, so after j columns it is at
    // most j cells (Chebyshev) from here: none of the next clearance - 1 columns is occupied.
    const int skip = cells_[q] & ~kFreeBit & 0xFF;
    if (skip == 0) return distance >> (2 * kPositionBits - kDistanceBits);
    u += dir.sign * skip;
    minor += minor_step * skip;
    distance += distance_step * skip;
  }
  return kNoHit;
}

bool FineMap::near_occupied(std::int64_t x, std::int64_t y, int d, std::int64_t distance) const {
  const Direction& dir = directions_[std::size_t(d)];
  // Along the major axis, distance / secant; along the minor, that times the slope.
  const std::int64_t major = ((distance << (2 * kPositionBits - kDistanceBits)) / dir.secant);
  const std::int64_t minor = (major * dir.slope) >> kSlopeBits;
  const std::int64_t ex = x + (dir.x_major ? dir.sign * major : dir.sign * minor);
  const std::int64_t ey = y + (dir.x_major ? dir.sign * minor : dir.sign * major);
  const std::int64_t ix = ex >> kPositionBits, iy = ey >> kPositionBits;
  if (ix < 0 || iy < 0 || ix >= geometry_.width || iy >= geometry_.height) return false;
  return clearance(int(ix), int(iy)) <= 1;
}

bool FineMap::runs_along_a_wall(std::int64_t x, std::int64_t y, int d, std::int64_t from,
                                std::int64_t to) const {
  // One step a cell along the ray: each point within a cell of an occupied one.
  constexpr std::int64_t kStep = std::int64_t{1} << kDistanceBits;
  for (std::int64_t at = from; at < to; at += kStep)
    if (!near_occupied(x, y, d, at)) return false;
  return near_occupied(x, y, d, to);
}

FineClaims FineMap::claims(double z, double bearing, double sigma_eff, int seps_levels,
                           int veto_levels) const {
  FineClaims out;
  const long long shift = std::llround(bearing / heading_bin()) % headings_;
  out.shift = int(shift < 0 ? shift + headings_ : shift);
  out.claim = claim_table<std::int32_t>(z, sigma_eff, geometry_.resolution, seps_levels,
                                        veto_levels, std::numeric_limits<std::size_t>::max() - 1)
                  .claim;
  out.range = std::llround(std::ldexp(z / geometry_.resolution, kDistanceBits));
  return out;
}

std::int32_t FineMap::score(std::span<const FineClaims> readings, const FinePose& pose,
                            bool grazing_hits) const {
  if (!is_free(pose)) return std::numeric_limits<std::int32_t>::min();
  std::int32_t sum = 0;
  constexpr std::int64_t kHalf = std::int64_t{1} << (kDistanceBits - 1);
  for (const FineClaims& r : readings) {
    const auto last = static_cast<std::int64_t>(r.claim.size()) - 1;
    const std::int64_t hit =
        first_hit(pose.x, pose.y, (pose.k + r.shift) % headings_, last << kDistanceBits);
    std::int64_t n = hit == kNoHit ? last : std::min(last, (hit + kHalf) >> kDistanceBits);
    // A wall met at a grazing angle is entered cell / sin(angle) before its surface: the reading
    // ends on the wall the ray is already in, and scores as if it hit there.
    if (grazing_hits && hit != kNoHit && hit < r.range &&
        runs_along_a_wall(pose.x, pose.y, (pose.k + r.shift) % headings_, hit, r.range))
      n = std::min(last, (r.range + kHalf) >> kDistanceBits);
    sum += r.claim[std::size_t(n)];
  }
  return sum;
}

}  // namespace intgrid::localization
