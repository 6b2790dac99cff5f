// What the simulator's parts share (golden/simulation/src/*.cpp, one part of simulator.hpp a
// file): the field checks, which name the field (core::fail_field), and small grid helpers.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "intgrid/core/failure.hpp"
#include "intgrid/simulation/simulator.hpp"

namespace intgrid::simulation::support {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;
inline constexpr double kSqrt2 = std::numbers::sqrt2;

// ---- Validation helpers: one message naming the field (core::fail_field).

using core::fail_field;

inline std::string number(double v) {
  if (std::isnan(v)) return "nan";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

inline void require_positive(double v, const char* field) {
  if (!(v > 0.0) || !std::isfinite(v))
    fail_field(field, "must be a positive finite number, got " + number(v));
}

inline void require_non_negative(double v, const char* field) {
  if (!(v >= 0.0) || !std::isfinite(v))
    fail_field(field, "must be a finite number >= 0, got " + number(v));
}

inline void require_probability(double v, const char* field) {
  if (!(v >= 0.0 && v <= 1.0))
    fail_field(field, "must be a probability in [0, 1], got " + number(v));
}

inline void require_finite(double v, const char* field) {
  if (!std::isfinite(v)) fail_field(field, "must be finite, got " + number(v));
}

inline void require_finite_pose(const core::Pose2& p, const std::string& field) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.theta))
    fail_field(field, "must have finite x, y and theta");
}

inline std::uint64_t rotl(std::uint64_t x, int k) {
  return (x << k) | (x >> (64 - k));
}

// ---- Grid helpers.

inline void check_world(const core::ProbabilityGrid& world) {
  core::check_geometry(world.geometry);
  if (world.cells.size() != world.geometry.size())
    core::fail<std::invalid_argument>("world: cell count does not match its geometry");
}

// The cell range [lo, hi] whose squares overlap the open interval (a, b) along one axis
// (tolerant to rounding at exact boundaries), at least one cell.
inline std::pair<int, int> overlapped_cells(double a, double b, double origin, double resolution) {
  constexpr double kSlack = 1e-9;
  const int lo = static_cast<int>(std::floor((a - origin) / resolution + kSlack));
  int hi = static_cast<int>(std::ceil((b - origin) / resolution - kSlack)) - 1;
  return {lo, std::max(lo, hi)};
}

// Sets p in every cell overlapping the rectangle [x0, x1] x [y0, y1], clipped to the grid.
inline void fill_rect(core::ProbabilityGrid& g, double x0, double y0, double x1, double y1,
                      double p) {
  const core::GridGeometry& geo = g.geometry;
  auto [ix0, ix1] = overlapped_cells(x0, x1, geo.origin_x, geo.resolution);
  auto [iy0, iy1] = overlapped_cells(y0, y1, geo.origin_y, geo.resolution);
  ix0 = std::max(ix0, 0);
  iy0 = std::max(iy0, 0);
  ix1 = std::min(ix1, geo.width - 1);
  iy1 = std::min(iy1, geo.height - 1);
  for (int iy = iy0; iy <= iy1; ++iy)
    for (int ix = ix0; ix <= ix1; ++ix) g.at(ix, iy) = p;
}

inline bool is_free(double p, double free_threshold) {
  return p < free_threshold;  // false for NaN
}

// The cells a disc occupies: those whose centre it covers, and the one holding its centre.
// Only cells inside the grid are returned (the index range is clipped in double first, so a
// disc far away costs nothing and casts no huge value to int).
inline std::vector<std::pair<int, int>> disc_cells(const core::GridGeometry& g, const Disc& d) {
  std::vector<std::pair<int, int>> cells;
  const auto column = [&](double x) {
    return static_cast<int>(std::clamp(std::floor((x - g.origin_x) / g.resolution), -1.0,
                                       static_cast<double>(g.width)));
  };
  const auto row = [&](double y) {
    return static_cast<int>(std::clamp(std::floor((y - g.origin_y) / g.resolution), -1.0,
                                       static_cast<double>(g.height)));
  };
  const int cx = column(d.x), cy = row(d.y);
  if (g.contains(cx, cy)) cells.emplace_back(cx, cy);
  const int ix0 = std::max(column(d.x - d.radius), 0);
  const int ix1 = std::min(column(d.x + d.radius), g.width - 1);
  const int iy0 = std::max(row(d.y - d.radius), 0);
  const int iy1 = std::min(row(d.y + d.radius), g.height - 1);
  for (int iy = iy0; iy <= iy1; ++iy) {
    for (int ix = ix0; ix <= ix1; ++ix) {
      if (ix == cx && iy == cy) continue;
      const double dx = g.centre_x(ix) - d.x, dy = g.centre_y(iy) - d.y;
      if (dx * dx + dy * dy <= d.radius * d.radius) cells.emplace_back(ix, iy);
    }
  }
  return cells;
}

}  // namespace intgrid::simulation::support
