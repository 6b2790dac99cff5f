// The map at its own resolution, for the refinement of pose hypotheses (docs/algorithms.md 7):
// the pose occupancy grid's claims evaluated at any fixed-point pose, with each reading cast on
// the map's own cells instead of the pose lattice's.
//
// A fine pose is a position in map cells with kPositionBits fractional bits and a heading as one
// of `headings` fine bins. A ray from it along fine direction d visits one map cell per column
// (or row) of its major axis, the cell holding the ray at that column's centre: the pose
// lattice's digital lines, through any point and at any of `headings` directions. Everything a
// pose's score needs is integer: the ray's steps, the distance to its first occupied cell, the
// table read and the sum.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/types.hpp"

namespace intgrid::localization {

struct FinePose {
  std::int64_t x = 0;  // map cells from the map's lower-left corner, kPositionBits fractional bits
  std::int64_t y = 0;
  int k = 0;  // heading bin: theta = 2 pi k / headings
  friend bool operator==(const FinePose&, const FinePose&) = default;
};

// One reading as the refinement applies it: claim[n] is the S_eps index of a pose whose first
// hit lies n map cells away (rounded to the nearest), rules 1 and 2 with the refinement level's
// sigma_eff; it ends with one 0, which every longer distance and "no hit" read.
struct FineClaims {
  int shift = 0;  // fine heading bins: a pose of heading k reads along (k + shift) mod headings
  std::vector<std::int32_t> claim;
  std::int64_t range = 0;  // z in map cells, kDistanceBits fractional bits
};

class FineMap {
 public:
  static constexpr int kPositionBits = 16;
  static constexpr int kDistanceBits = 8;  // first_hit's fractional bits
  static constexpr std::int64_t kNoHit = -1;
  // Clearance is stored in 7 bits: rays jump at most this many cells at a time.
  static constexpr int kMaxClearance = 127;

  FineMap() = default;
  // Classes of the map's cells as the pose lattice's (occupied: P >= occupied_threshold; free:
  // P <= free_threshold; unknown otherwise, NaN included) and `headings` directions. Throws
  // std::invalid_argument for a bad geometry, headings outside 4..65536 or a map of 2^31 cells
  // along an axis or more.
  FineMap(const core::ProbabilityGrid& map, double occupied_threshold, double free_threshold,
          int headings);

  // Bytes a FineMap of this geometry and heading count takes: one a map cell, 24 a heading.
  static std::size_t bytes_for(const core::GridGeometry& geometry, int headings);

  bool empty() const { return cells_.empty(); }
  int headings() const { return headings_; }
  const core::GridGeometry& geometry() const { return geometry_; }
  double heading_bin() const;  // 2 pi / headings (rad)

  // The nearest fine pose of a sensor pose, and back.
  FinePose fine_pose(const core::Pose2& sensor) const;
  core::Pose2 pose_of(const FinePose& pose) const;
  // Fine positions per metre along an axis (2^kPositionBits / resolution).
  double units_per_metre() const;
  // Whether the map cell holding the pose is free: where the robot may be.
  bool is_free(const FinePose& pose) const;
  // Chebyshev distance (cells) from map cell (ix, iy) to the nearest occupied cell, at most
  // kMaxClearance (also when the map has none); 0 on an occupied cell.
  int clearance(int ix, int iy) const;

  // Distance from (x, y) (fine position units) along fine direction d to the first occupied cell
  // on the ray, in map cells with kDistanceBits fractional bits: from the point to the centre of
  // that cell's column (row, for a y-major direction) measured along the ray. The ray starts at
  // the first column whose centre lies ahead of the point. kNoHit when the ray leaves the map or
  // passes `limit` (same unit) first. Rays skip ahead by each cell's clearance: no occupied cell
  // can lie nearer, so the answer is the cell-by-cell walk's.
  std::int64_t first_hit(std::int64_t x, std::int64_t y, int d, std::int64_t limit) const;
  // Whether the point `distance` (map cells, kDistanceBits fractional bits) along fine direction
  // d from (x, y) lies within one cell (Chebyshev) of an occupied cell.
  bool near_occupied(std::int64_t x, std::int64_t y, int d, std::int64_t distance) const;
  // Whether every point of the ray from `from` to `to` (same unit), a cell apart, is
  // near_occupied: the ray runs along a wall, as it does when it meets one at a grazing angle.
  bool runs_along_a_wall(std::int64_t x, std::int64_t y, int d, std::int64_t from,
                         std::int64_t to) const;

  // The claims of a reading of range z (m) and bearing beta (rad) with the given sigma_eff (m):
  // the narrow ISM on the map's cells, each reading on its own S_eps scale of seps_levels steps,
  // negative claims bounded by min(strongest claim, veto_levels).
  FineClaims claims(double z, double bearing, double sigma_eff, int seps_levels,
                    int veto_levels) const;
  // The sum of every reading's claim at the pose; INT32_MIN when the pose's cell is not free.
  // grazing_hits: a reading whose first hit lies before its range, while its ray runs along a
  // wall from there to its endpoint (runs_along_a_wall), claims as if its first hit were at its
  // range.
  std::int32_t score(std::span<const FineClaims> readings, const FinePose& pose,
                     bool grazing_hits) const;

 private:
  struct Direction {
    bool x_major = true;
    int sign = 1;             // along the major axis
    std::int64_t slope = 0;   // minor per major, 30 fractional bits, |slope| <= 2^30
    std::int64_t secant = 0;  // 1 / max(|cos|, |sin|), 16 fractional bits
  };
  static constexpr int kSlopeBits = 30;
  static constexpr std::uint8_t kFreeBit = 0x80;

  core::GridGeometry geometry_;
  int headings_ = 0;
  std::vector<std::uint8_t> cells_;  // per map cell: kFreeBit | clearance
  std::vector<Direction> directions_;
};

}  // namespace intgrid::localization
