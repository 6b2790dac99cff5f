#include "intgrid/simulation/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

#include "intgrid/core/failure.hpp"

namespace intgrid::simulation {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kSqrt2 = std::numbers::sqrt2;

// ---- Validation helpers: one message naming the field (core::fail_field).

using core::fail_field;

std::string number(double v) {
  if (std::isnan(v)) return "nan";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

void require_positive(double v, const char* field) {
  if (!(v > 0.0) || !std::isfinite(v))
    fail_field(field, "must be a positive finite number, got " + number(v));
}

void require_non_negative(double v, const char* field) {
  if (!(v >= 0.0) || !std::isfinite(v))
    fail_field(field, "must be a finite number >= 0, got " + number(v));
}

void require_probability(double v, const char* field) {
  if (!(v >= 0.0 && v <= 1.0))
    fail_field(field, "must be a probability in [0, 1], got " + number(v));
}

void require_finite(double v, const char* field) {
  if (!std::isfinite(v)) fail_field(field, "must be finite, got " + number(v));
}

void require_finite_pose(const core::Pose2& p, const std::string& field) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.theta))
    fail_field(field, "must have finite x, y and theta");
}

std::uint64_t rotl(std::uint64_t x, int k) {
  return (x << k) | (x >> (64 - k));
}

// ---- Grid helpers.

void check_world(const core::ProbabilityGrid& world) {
  core::check_geometry(world.geometry);
  if (world.cells.size() != world.geometry.size())
    core::fail<std::invalid_argument>("world: cell count does not match its geometry");
}

// The cell range [lo, hi] whose squares overlap the open interval (a, b) along one axis
// (tolerant to rounding at exact boundaries), at least one cell.
std::pair<int, int> overlapped_cells(double a, double b, double origin, double resolution) {
  constexpr double kSlack = 1e-9;
  const int lo = static_cast<int>(std::floor((a - origin) / resolution + kSlack));
  int hi = static_cast<int>(std::ceil((b - origin) / resolution - kSlack)) - 1;
  return {lo, std::max(lo, hi)};
}

// Sets p in every cell overlapping the rectangle [x0, x1] x [y0, y1], clipped to the grid.
void fill_rect(core::ProbabilityGrid& g, double x0, double y0, double x1, double y1, double p) {
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

bool is_free(double p, double free_threshold) {
  return p < free_threshold;  // false for NaN
}

// The cells a disc occupies: those whose centre it covers, and the one holding its centre.
// Only cells inside the grid are returned (the index range is clipped in double first, so a
// disc far away costs nothing and casts no huge value to int).
std::vector<std::pair<int, int>> disc_cells(const core::GridGeometry& g, const Disc& d) {
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

}  // namespace

// ---------------------------------------------------------------------------------------------
// Random numbers

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t state = seed;
  std::uint64_t mixed = splitmix64(state) ^ (stream * 0xd1b54a32d192ed03ULL);
  return splitmix64(mixed);
}

SimRandom::SimRandom(std::uint64_t seed) {
  std::uint64_t state = seed;
  for (std::uint64_t& word : s_) word = splitmix64(state);
}

std::uint64_t SimRandom::next_u64() {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double SimRandom::uniform() {
  return static_cast<double>(next_u64() >> 11) * 0x1.0p-53;
}

double SimRandom::uniform_open() {
  return (static_cast<double>(next_u64() >> 11) + 0.5) * 0x1.0p-53;
}

std::uint64_t SimRandom::below(std::uint64_t n) {
  if (n == 0) core::fail<std::invalid_argument>("SimRandom::below: n must be positive");
  const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
  for (;;) {
    const std::uint64_t r = next_u64();
    if (r >= threshold) return r % n;
  }
}

double SimRandom::normal() {
  const double u1 = uniform_open();
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

// ---------------------------------------------------------------------------------------------
// Procedural floorplan

namespace {

// Margin between a door and the end of the wall it is in (m).
constexpr double kDoorMargin = 0.15;
// Furniture: distance kept from room walls, from other furniture, and from a door's centre (m).
constexpr double kFurnitureWallGap = 0.3;
constexpr double kFurnitureGap = 0.3;
constexpr double kFurnitureDoorGap = 1.2;

struct Rect {
  double x0, y0, x1, y1;
};

struct Room {
  Rect interior;
  Point2 door;  // centre of its door
};

bool overlaps(const Rect& a, const Rect& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

// Partitions of the interval [lo, hi] into rooms whose corridor-facing part is [clo, chi]
// (lo <= clo < chi <= hi): partition centres, jittered, and for each room the interval where
// its door may go. Returns the room intervals [start, end] (walls excluded) and door centres.
struct BandRooms {
  std::vector<std::pair<double, double>> rooms;  // along the band
  std::vector<double> doors;                     // door centre along the band
};

BandRooms split_band(double lo, double hi, double clo, double chi, const FloorplanConfig& c,
                     SimRandom& random) {
  const double span = chi - clo;
  const auto n = static_cast<std::size_t>(std::max(1.0, std::floor(span / c.room_length + 0.5)));
  const double spacing = span / static_cast<double>(n);
  const double need = c.wall + c.door + 2.0 * kDoorMargin;
  const double jitter = std::max(0.0, std::min(0.25 * spacing, 0.5 * (spacing - need)));
  std::vector<double> partitions;
  for (std::size_t k = 1; k < n; ++k)
    partitions.push_back(clo + static_cast<double>(k) * spacing + random.uniform(-jitter, jitter));
  BandRooms band;
  for (std::size_t k = 0; k < n; ++k) {
    const double start = k == 0 ? lo : partitions[k - 1] + 0.5 * c.wall;
    const double end = k + 1 == n ? hi : partitions[k] - 0.5 * c.wall;
    band.rooms.emplace_back(start, end);
    const double door_lo = std::max(start, clo) + kDoorMargin + 0.5 * c.door;
    const double door_hi = std::min(end, chi) - kDoorMargin - 0.5 * c.door;
    band.doors.push_back(door_hi > door_lo ? random.uniform(door_lo, door_hi)
                                           : 0.5 * (door_lo + door_hi));
  }
  return band;
}

}  // namespace

void check_floorplan_config(const FloorplanConfig& c) {
  require_positive(c.width, "floorplan.width");
  require_positive(c.height, "floorplan.height");
  require_positive(c.cell, "floorplan.cell");
  require_positive(c.wall, "floorplan.wall");
  require_positive(c.room_depth, "floorplan.room_depth");
  require_positive(c.corridor, "floorplan.corridor");
  require_positive(c.door, "floorplan.door");
  require_positive(c.room_length, "floorplan.room_length");
  if (c.furniture > 1000) fail_field("floorplan.furniture", "must be at most 1000");
  const double cells = std::ceil(c.width / c.cell) * std::ceil(c.height / c.cell);
  if (!(cells <= 1e8))
    fail_field("floorplan.cell", "gives more than 10^8 cells for " + number(c.width) + " x " +
                                     number(c.height) + " m");
  if (c.door < 3.0 * c.cell) fail_field("floorplan.door", "must be at least 3 cells wide");
  if (c.corridor < 4.0 * c.cell) fail_field("floorplan.corridor", "must be at least 4 cells wide");
  if (c.wall >= c.room_depth) fail_field("floorplan.wall", "must be thinner than room_depth");
  const double inner = 2.0 * (c.room_depth + 3.0 * c.wall + c.corridor) + 1.0;
  if (c.width < inner || c.height < inner)
    fail_field("floorplan.width",
               "must be at least 2 (room_depth + 3 wall + corridor) + 1 = " + number(inner) +
                   " m, and so must the height, for rooms, the corridor and an inner block of 1 m");
  const double need = c.wall + c.door + 2.0 * kDoorMargin;
  if (0.75 * c.room_length < need)
    fail_field("floorplan.room_length",
               "must be at least (wall + door + 0.3) / 0.75 = " + number(need / 0.75) + " m");
  if (c.room_depth - c.wall < c.door + 2.0 * kDoorMargin)
    fail_field("floorplan.room_depth", "is too shallow for a door");
}

Floorplan make_floorplan(const FloorplanConfig& c, std::uint64_t seed) {
  check_floorplan_config(c);
  SimRandom random(seed);
  core::GridGeometry g;
  g.resolution = c.cell;
  g.width = std::max(1, static_cast<int>(std::lround(c.width / c.cell)));
  g.height = std::max(1, static_cast<int>(std::lround(c.height / c.cell)));
  Floorplan plan;
  plan.grid = core::ProbabilityGrid(g, 0.0);
  core::ProbabilityGrid& grid = plan.grid;
  const double W = g.width * c.cell, H = g.height * c.cell, t = c.wall;
  const auto wall = [&](double x0, double y0, double x1, double y1) {
    fill_rect(grid, x0, y0, x1, y1, 1.0);
  };
  const auto ring = [&](double x0, double y0, double x1, double y1) {  // thickness t inward
    wall(x0, y0, x1, y0 + t);
    wall(x0, y1 - t, x1, y1);
    wall(x0, y0, x0 + t, y1);
    wall(x1 - t, y0, x1, y1);
  };
  // Outer wall; the corridor's outer wall (a in from the edge); its inner wall (ending at b).
  const double a = t + c.room_depth;
  const double b = a + 2.0 * t + c.corridor;
  ring(0.0, 0.0, W, H);
  ring(a, a, W - a, H - a);
  ring(b - t, b - t, W - b + t, H - b + t);
  // The corner walls from the corridor's outer wall to the outer wall: the bottom and top bands
  // lie between the left and right ones.
  wall(a, t, a + t, a);
  wall(W - a - t, t, W - a, a);
  wall(a, H - a, a + t, H - t);
  wall(W - a - t, H - a, W - a, H - t);

  std::vector<Room> rooms;
  std::vector<Rect> doors;  // wall areas to clear
  const double corridor_lo = a + t;
  // Left and right bands: rooms along y; bottom and top bands: rooms along x.
  const double cx_hi = W - a - t, cy_hi = H - a - t;
  for (int side = 0; side < 4; ++side) {
    const bool vertical = side < 2;  // left, right
    const BandRooms band = vertical ? split_band(t, H - t, corridor_lo, cy_hi, c, random)
                                    : split_band(a + t, W - a - t, corridor_lo, cx_hi, c, random);
    for (std::size_t k = 0; k < band.rooms.size(); ++k) {
      const auto [s, e] = band.rooms[k];
      const double d = band.doors[k];
      Room room{};
      if (side == 0) {  // left
        room.interior = {t, s, a, e};
        room.door = {a + 0.5 * t, d};
        doors.push_back({a, d - 0.5 * c.door, a + t, d + 0.5 * c.door});
      } else if (side == 1) {  // right
        room.interior = {W - a, s, W - t, e};
        room.door = {W - a - 0.5 * t, d};
        doors.push_back({W - a - t, d - 0.5 * c.door, W - a, d + 0.5 * c.door});
      } else if (side == 2) {  // bottom
        room.interior = {s, t, e, a};
        room.door = {d, a + 0.5 * t};
        doors.push_back({d - 0.5 * c.door, a, d + 0.5 * c.door, a + t});
      } else {  // top
        room.interior = {s, H - a, e, H - t};
        room.door = {d, H - a - 0.5 * t};
        doors.push_back({d - 0.5 * c.door, H - a - t, d + 0.5 * c.door, H - a});
      }
      rooms.push_back(room);
      // The partition after this room.
      if (k + 1 < band.rooms.size()) {
        const double p0 = e, p1 = band.rooms[k + 1].first;
        if (side == 0) wall(t, p0, a, p1);
        if (side == 1) wall(W - a, p0, W - t, p1);
        if (side == 2) wall(p0, t, p1, a);
        if (side == 3) wall(p0, H - a, p1, H - t);
      }
    }
  }
  // The inner block: two rooms side by side if it is wide enough, each with a door in its
  // bottom or top wall.
  {
    const double need = c.door + 2.0 * kDoorMargin;
    const double inner_w = W - 2.0 * b;
    std::vector<std::pair<double, double>> spans;
    if (inner_w >= 2.0 * need + t) {
      const double jitter = std::min(0.1 * inner_w, 0.5 * inner_w - 0.5 * t - need);
      const double p = 0.5 * W + random.uniform(-jitter, jitter);
      wall(p - 0.5 * t, b, p + 0.5 * t, H - b);
      spans = {{b, p - 0.5 * t}, {p + 0.5 * t, W - b}};
    } else {
      spans = {{b, W - b}};
    }
    for (const auto& [s, e] : spans) {
      const double d_lo = s + kDoorMargin + 0.5 * c.door, d_hi = e - kDoorMargin - 0.5 * c.door;
      const double d = d_hi > d_lo ? random.uniform(d_lo, d_hi) : 0.5 * (s + e);
      const bool bottom = random.uniform() < 0.5;
      Room room{};
      room.interior = {s, b, e, H - b};
      if (bottom) {
        room.door = {d, b - 0.5 * t};
        doors.push_back({d - 0.5 * c.door, b - t, d + 0.5 * c.door, b});
      } else {
        room.door = {d, H - b + 0.5 * t};
        doors.push_back({d - 0.5 * c.door, H - b, d + 0.5 * c.door, H - b + t});
      }
      rooms.push_back(room);
    }
  }
  for (const Rect& d : doors) fill_rect(grid, d.x0, d.y0, d.x1, d.y1, 0.0);

  // Furniture: boxes inside rooms, away from walls, doors and each other; up to c.furniture
  // (a box that finds no place in 200 tries is left out).
  std::vector<Rect> placed;
  for (std::size_t f = 0; f < c.furniture; ++f) {
    for (int attempt = 0; attempt < 200; ++attempt) {
      const Room& room = rooms[random.below(rooms.size())];
      double w = random.uniform(0.4, 1.2), h = random.uniform(0.4, 1.0);
      if (random.uniform() < 0.5) std::swap(w, h);
      const double x_lo = room.interior.x0 + kFurnitureWallGap;
      const double x_hi = room.interior.x1 - kFurnitureWallGap - w;
      const double y_lo = room.interior.y0 + kFurnitureWallGap;
      const double y_hi = room.interior.y1 - kFurnitureWallGap - h;
      const double u = random.uniform(), v = random.uniform();
      if (x_hi <= x_lo || y_hi <= y_lo) continue;
      const double x0 = x_lo + u * (x_hi - x_lo), y0 = y_lo + v * (y_hi - y_lo);
      const Rect box{x0, y0, x0 + w, y0 + h};
      const Rect near_door{room.door.x - kFurnitureDoorGap, room.door.y - kFurnitureDoorGap,
                           room.door.x + kFurnitureDoorGap, room.door.y + kFurnitureDoorGap};
      if (overlaps(box, near_door)) continue;
      const Rect grown{box.x0 - kFurnitureGap, box.y0 - kFurnitureGap, box.x1 + kFurnitureGap,
                       box.y1 + kFurnitureGap};
      if (std::any_of(placed.begin(), placed.end(),
                      [&](const Rect& other) { return overlaps(grown, other); }))
        continue;
      placed.push_back(box);
      fill_rect(grid, box.x0, box.y0, box.x1, box.y1, 1.0);
      break;
    }
  }

  const double m = a + t + 0.5 * c.corridor;
  plan.corridor_loop = {{0.5 * W, m}, {W - m, m}, {W - m, H - m}, {m, H - m}, {m, m}};
  return plan;
}

core::ProbabilityGrid procedural_floorplan(const FloorplanConfig& c, std::uint64_t seed) {
  return make_floorplan(c, seed).grid;
}

// ---------------------------------------------------------------------------------------------
// Trajectory

void check_trajectory_config(const TrajectoryConfig& c) {
  if (c.scans == 0) fail_field("trajectory.scans", "must be at least 1");
  if (c.scans > 10'000'000) fail_field("trajectory.scans", "must be at most 10^7");
  require_positive(c.scan_period, "trajectory.scan_period");
  require_positive(c.speed, "trajectory.speed");
  require_positive(c.turn_rate, "trajectory.turn_rate");
  require_non_negative(c.robot_radius, "trajectory.robot_radius");
  require_non_negative(c.min_leg, "trajectory.min_leg");
  if (!(c.free_threshold > 0.0 && c.free_threshold <= 1.0))
    fail_field("trajectory.free_threshold", "must be in (0, 1], got " + number(c.free_threshold));
}

namespace {

// Appends poses toward successive targets under the step limits of TrajectoryConfig.
class RouteSampler {
 public:
  RouteSampler(const TrajectoryConfig& c, std::vector<core::Pose2>& out)
      : max_step_(c.speed * c.scan_period),
        max_turn_(c.turn_rate * c.scan_period),
        limit_(c.scans),
        out_(out) {}

  bool full() const { return out_.size() >= limit_; }

  void start(Point2 p, double heading) {
    pose_ = {p.x, p.y, core::wrap_angle(heading)};
    if (!full()) out_.push_back(pose_);
  }

  // Goes to target; false if the trajectory filled up first.
  bool go_to(Point2 target) {
    while (!full()) {
      const double dx = target.x - pose_.x, dy = target.y - pose_.y;
      const double dist = std::hypot(dx, dy);
      if (dist == 0.0) return true;
      const double direction = std::atan2(dy, dx);
      const double error = core::wrap_angle(direction - pose_.theta);
      if (std::abs(error) > max_turn_) {
        pose_.theta = core::wrap_angle(pose_.theta + std::copysign(max_turn_, error));
      } else {
        pose_.theta = direction;
        if (dist <= max_step_) {
          pose_.x = target.x;
          pose_.y = target.y;
        } else {
          pose_.x += max_step_ * dx / dist;
          pose_.y += max_step_ * dy / dist;
        }
      }
      out_.push_back(pose_);
    }
    return false;
  }

 private:
  double max_step_, max_turn_;
  std::size_t limit_;
  std::vector<core::Pose2>& out_;
  core::Pose2 pose_;
};

// The squared distance transform of one line (Felzenszwalb and Huttenlocher 2012): d[q] =
// min_p (q - p)^2 + f[p].
void distance_transform_1d(const std::vector<double>& f, std::vector<double>& d,
                           std::vector<int>& v, std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  d.resize(f.size());
  v.assign(f.size(), 0);
  z.assign(f.size() + 1, 0.0);
  int k = 0;
  v[0] = 0;
  z[0] = -std::numeric_limits<double>::infinity();
  z[1] = std::numeric_limits<double>::infinity();
  const auto intersection = [&](int q, int p) {
    return ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * (q - p));
  };
  for (int q = 1; q < n; ++q) {
    double s = intersection(q, v[k]);
    while (s <= z[k]) {  // ends at k = 0, whose z is -infinity
      --k;
      s = intersection(q, v[k]);
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    const double dq = q - v[k];
    d[q] = dq * dq + f[v[k]];
  }
}

}  // namespace

std::vector<core::Pose2> follow_route(const std::vector<Point2>& route, bool closed,
                                      const TrajectoryConfig& c) {
  check_trajectory_config(c);
  for (const Point2& p : route)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) fail_field("route", "points must be finite");
  std::size_t second = 1;
  while (second < route.size() && route[second].x == route[0].x && route[second].y == route[0].y)
    ++second;
  if (route.empty() || second == route.size())
    fail_field("route", "must hold at least two distinct points");
  std::vector<core::Pose2> poses;
  poses.reserve(c.scans);
  RouteSampler sampler(c, poses);
  sampler.start(route[0], std::atan2(route[second].y - route[0].y, route[second].x - route[0].x));
  do {
    for (std::size_t i = 1; i < route.size(); ++i)
      if (!sampler.go_to(route[i])) return poses;
    if (closed && !sampler.go_to(route[0])) return poses;
  } while (closed);
  return poses;
}

core::Grid<double> clearance_map(const core::ProbabilityGrid& world, double free_threshold) {
  check_world(world);
  const core::GridGeometry& g = world.geometry;
  // Squared distances in cells over the grid padded by one non-free cell on each side.
  const int pw = g.width + 2, ph = g.height + 2;
  constexpr double kFar = 1e20;
  std::vector<double> f(static_cast<std::size_t>(pw) * static_cast<std::size_t>(ph), 0.0);
  for (int iy = 0; iy < g.height; ++iy)
    for (int ix = 0; ix < g.width; ++ix)
      if (is_free(world.at(ix, iy), free_threshold))
        f[static_cast<std::size_t>(iy + 1) * pw + static_cast<std::size_t>(ix + 1)] = kFar;
  std::vector<double> line, out, z;
  std::vector<int> v;
  for (int x = 0; x < pw; ++x) {  // columns
    line.resize(static_cast<std::size_t>(ph));
    for (int y = 0; y < ph; ++y) line[y] = f[static_cast<std::size_t>(y) * pw + x];
    distance_transform_1d(line, out, v, z);
    for (int y = 0; y < ph; ++y) f[static_cast<std::size_t>(y) * pw + x] = out[y];
  }
  core::Grid<double> clearance(g, 0.0);
  line.resize(static_cast<std::size_t>(pw));
  for (int y = 1; y <= g.height; ++y) {  // rows
    for (int x = 0; x < pw; ++x) line[x] = f[static_cast<std::size_t>(y) * pw + x];
    distance_transform_1d(line, out, v, z);
    for (int x = 1; x <= g.width; ++x)
      clearance.at(x - 1, y - 1) = std::sqrt(out[x]) * g.resolution;
  }
  return clearance;
}

namespace {

// The region of cells a random trajectory may use, and shortest paths through it.
class FreeSpace {
 public:
  FreeSpace(const core::ProbabilityGrid& world, const TrajectoryConfig& c) : g_(world.geometry) {
    const core::Grid<double> clearance = clearance_map(world, c.free_threshold);
    const double need = c.robot_radius + kSqrt2 * g_.resolution;
    ok_.assign(g_.size(), 0);
    for (std::size_t i = 0; i < g_.size(); ++i) ok_[i] = clearance.cells[i] >= need ? 1 : 0;
  }

  const core::GridGeometry& geometry() const { return g_; }
  bool ok(int ix, int iy) const { return g_.contains(ix, iy) && ok_[g_.index(ix, iy)]; }

  // The 8 moves with their cost; a diagonal one only if both cells beside it are usable.
  template <class Visit>
  void for_each_move(int ix, int iy, Visit&& visit) const {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !ok(ix + dx, iy + dy)) continue;
        if (dx != 0 && dy != 0 && !(ok(ix + dx, iy) && ok(ix, iy + dy))) continue;
        visit(ix + dx, iy + dy, dx != 0 && dy != 0 ? kSqrt2 : 1.0);
      }
    }
  }

  // The cells of the largest connected region (ties: the one found first, row by row).
  std::vector<std::size_t> largest_region() const {
    std::vector<int> label(g_.size(), -1);
    std::vector<std::size_t> best, current, stack;
    int next = 0;
    for (int iy = 0; iy < g_.height; ++iy) {
      for (int ix = 0; ix < g_.width; ++ix) {
        const std::size_t start = g_.index(ix, iy);
        if (!ok_[start] || label[start] >= 0) continue;
        current.clear();
        stack.assign(1, start);
        label[start] = next;
        while (!stack.empty()) {
          const std::size_t i = stack.back();
          stack.pop_back();
          current.push_back(i);
          const int cx = static_cast<int>(i % g_.width), cy = static_cast<int>(i / g_.width);
          for_each_move(cx, cy, [&](int nx, int ny, double) {
            const std::size_t j = g_.index(nx, ny);
            if (label[j] < 0) {
              label[j] = next;
              stack.push_back(j);
            }
          });
        }
        ++next;
        if (current.size() > best.size()) best = current;
      }
    }
    std::sort(best.begin(), best.end());
    return best;
  }

  // Dijkstra from cell `from` to cell `to` (same region): the cells of a shortest path.
  std::vector<std::size_t> shortest_path(std::size_t from, std::size_t to) const {
    std::vector<double> dist(g_.size(), std::numeric_limits<double>::infinity());
    std::vector<std::size_t> previous(g_.size(), g_.size());
    using Entry = std::pair<double, std::size_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    dist[from] = 0.0;
    queue.push({0.0, from});
    while (!queue.empty()) {
      const auto [d, i] = queue.top();
      queue.pop();
      if (d > dist[i]) continue;
      if (i == to) break;
      const int cx = static_cast<int>(i % g_.width), cy = static_cast<int>(i / g_.width);
      for_each_move(cx, cy, [&](int nx, int ny, double cost) {
        const std::size_t j = g_.index(nx, ny);
        if (d + cost < dist[j]) {
          dist[j] = d + cost;
          previous[j] = i;
          queue.push({dist[j], j});
        }
      });
    }
    if (!std::isfinite(dist[to]))
      core::fail<std::logic_error>("shortest_path: cells not connected");
    std::vector<std::size_t> path;
    for (std::size_t i = to; i != from; i = previous[i]) path.push_back(i);
    path.push_back(from);
    std::reverse(path.begin(), path.end());
    return path;
  }

  // True if every cell the segment between the centres of cells a and b touches (both cells
  // beside it where it passes exactly through a corner) is usable.
  bool line_of_sight(std::size_t a, std::size_t b) const {
    int x = static_cast<int>(a % g_.width), y = static_cast<int>(a / g_.width);
    const int x1 = static_cast<int>(b % g_.width), y1 = static_cast<int>(b / g_.width);
    const long long nx = std::abs(x1 - x), ny = std::abs(y1 - y);
    const int sx = x1 > x ? 1 : -1, sy = y1 > y ? 1 : -1;
    long long ix = 0, iy = 0;
    if (!ok(x, y)) return false;
    while (ix < nx || iy < ny) {
      // Compare the parameters (ix + 1/2) / nx and (iy + 1/2) / ny of the next crossings.
      const long long decision = (1 + 2 * ix) * ny - (1 + 2 * iy) * nx;
      if (decision == 0) {
        if (!ok(x + sx, y) || !ok(x, y + sy)) return false;
        x += sx;
        y += sy;
        ++ix;
        ++iy;
      } else if (decision < 0) {
        x += sx;
        ++ix;
      } else {
        y += sy;
        ++iy;
      }
      if (!ok(x, y)) return false;
    }
    return true;
  }

  // The path shortened greedily: from each kept cell, the farthest next one in sight.
  std::vector<std::size_t> shorten(const std::vector<std::size_t>& path) const {
    std::vector<std::size_t> kept{path.front()};
    std::size_t i = 0;
    while (i + 1 < path.size()) {
      std::size_t j = i + 1;
      while (j + 1 < path.size() && line_of_sight(path[i], path[j + 1])) ++j;
      kept.push_back(path[j]);
      i = j;
    }
    return kept;
  }

  Point2 centre(std::size_t i) const {
    return {g_.centre_x(static_cast<int>(i % g_.width)),
            g_.centre_y(static_cast<int>(i / g_.width))};
  }

 private:
  core::GridGeometry g_;
  std::vector<std::uint8_t> ok_;
};

}  // namespace

std::vector<core::Pose2> random_trajectory(const core::ProbabilityGrid& world,
                                           const TrajectoryConfig& c, std::uint64_t seed) {
  check_trajectory_config(c);
  check_world(world);
  const FreeSpace space(world, c);
  const std::vector<std::size_t> region = space.largest_region();
  if (region.size() < 2)
    core::fail<std::invalid_argument>("world: fewer than two free cells (P < " +
                                      number(c.free_threshold) + ") with " +
                                      number(c.robot_radius) + " m clearance for the robot");
  SimRandom random(seed);
  std::vector<core::Pose2> poses;
  poses.reserve(c.scans);
  RouteSampler sampler(c, poses);
  std::size_t current = region[random.below(region.size())];
  sampler.start(space.centre(current), random.uniform(-kPi, kPi));
  const auto distance = [&](std::size_t a, std::size_t b) {
    const Point2 p = space.centre(a), q = space.centre(b);
    return std::hypot(p.x - q.x, p.y - q.y);
  };
  while (!sampler.full()) {
    // The first draw at least min_leg away, else the farthest of 20 draws.
    std::size_t next = current;
    for (int attempt = 0; attempt < 20; ++attempt) {
      const std::size_t candidate = region[random.below(region.size())];
      if (candidate == current) continue;
      if (next == current || distance(current, candidate) > distance(current, next))
        next = candidate;
      if (distance(current, candidate) >= c.min_leg) {
        next = candidate;
        break;
      }
    }
    while (next == current) next = region[random.below(region.size())];
    const std::vector<std::size_t> path = space.shorten(space.shortest_path(current, next));
    for (std::size_t i = 1; i < path.size(); ++i)
      if (!sampler.go_to(space.centre(path[i]))) break;
    current = next;
  }
  return poses;
}

// ---------------------------------------------------------------------------------------------
// Odometry

void check_odometry_noise(const OdometryNoiseConfig& c) {
  require_non_negative(c.alpha1, "odometry.alpha1");
  require_non_negative(c.alpha2, "odometry.alpha2");
  require_non_negative(c.alpha3, "odometry.alpha3");
  require_non_negative(c.alpha4, "odometry.alpha4");
}

std::vector<core::Pose2> noisy_odometry(const std::vector<core::Pose2>& truth,
                                        const OdometryNoiseConfig& c, SimRandom& random) {
  check_odometry_noise(c);
  if (c.alpha1 == 0.0 && c.alpha2 == 0.0 && c.alpha3 == 0.0 && c.alpha4 == 0.0) return truth;
  std::vector<core::Pose2> odometry;
  odometry.reserve(truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (i == 0) {
      odometry.push_back(truth[0]);
      continue;
    }
    const core::Pose2& a = truth[i - 1];
    const core::Pose2& b = truth[i];
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double trans = std::hypot(dx, dy);
    const double rot1 = trans < 1e-9 ? 0.0 : core::wrap_angle(std::atan2(dy, dx) - a.theta);
    const double rot2 = core::wrap_angle(b.theta - a.theta - rot1);
    const double n1 = random.normal(), n2 = random.normal(), n3 = random.normal();
    const double rot1_hat =
        rot1 + std::sqrt(c.alpha1 * rot1 * rot1 + c.alpha2 * trans * trans) * n1;
    const double trans_hat =
        trans + std::sqrt(c.alpha3 * trans * trans + c.alpha4 * (rot1 * rot1 + rot2 * rot2)) * n2;
    const double rot2_hat =
        rot2 + std::sqrt(c.alpha1 * rot2 * rot2 + c.alpha2 * trans * trans) * n3;
    const core::Pose2& o = odometry.back();
    odometry.push_back({o.x + trans_hat * std::cos(o.theta + rot1_hat),
                        o.y + trans_hat * std::sin(o.theta + rot1_hat),
                        core::wrap_angle(o.theta + rot1_hat + rot2_hat)});
  }
  return odometry;
}

// ---------------------------------------------------------------------------------------------
// Range sensors

SensorConfig lidar_sensor(std::size_t beams, double fov, double max_range) {
  SensorConfig s;
  s.kind = SensorKind::lidar;
  s.beams = beams;
  s.max_range = max_range;
  if (beams <= 1) {
    s.angle0 = 0.0;
    s.dangle = 0.0;
  } else if (fov >= kTwoPi) {
    s.angle0 = -kPi;
    s.dangle = kTwoPi / static_cast<double>(beams);
  } else {
    s.angle0 = -0.5 * fov;
    s.dangle = fov / static_cast<double>(beams - 1);
  }
  return s;
}

SensorConfig cone_ring_sensor(std::size_t cones, double cone_fov, double max_range) {
  SensorConfig s;
  s.kind = SensorKind::cone;
  s.beams = cones;
  s.angle0 = 0.0;
  s.dangle = cones == 0 ? 0.0 : kTwoPi / static_cast<double>(cones);
  s.cone_fov = cone_fov;
  s.max_range = max_range;
  return s;
}

void check_sensor_config(const SensorConfig& c) {
  if (c.beams == 0) fail_field("sensor.beams", "must be at least 1");
  if (c.beams > 100000) fail_field("sensor.beams", "must be at most 100000");
  require_finite(c.angle0, "sensor.angle0");
  require_finite(c.dangle, "sensor.dangle");
  require_positive(c.max_range, "sensor.max_range");
  require_finite_pose(c.mount, "sensor.mount");
  if (!(c.occupied_threshold > 0.0 && c.occupied_threshold <= 1.0))
    fail_field("sensor.occupied_threshold",
               "must be in (0, 1], got " + number(c.occupied_threshold));
  if (c.kind == SensorKind::cone) {
    if (!(c.cone_fov > 0.0 && c.cone_fov < kPi))
      fail_field("sensor.cone_fov", "must be in (0, pi) rad, got " + number(c.cone_fov));
    if (c.rays_per_cone > 100000) fail_field("sensor.rays_per_cone", "must be at most 100000");
  }
}

double ray_cast(const core::ProbabilityGrid& world, double x, double y, double angle,
                double max_range, double occupied_threshold) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(angle) || !(max_range >= 0.0) ||
      !std::isfinite(max_range))
    core::fail<std::invalid_argument>("ray_cast: the start, angle and max_range must be finite");
  const core::GridGeometry& g = world.geometry;
  const double res = g.resolution;
  const double dx = std::cos(angle), dy = std::sin(angle);
  // The part [t0, t1] of the ray inside the grid's box and within max_range.
  double t0 = 0.0, t1 = max_range;
  const auto clip = [&](double p, double d, double lo, double hi) {
    if (d == 0.0) return p >= lo && p <= hi;
    double a = (lo - p) / d, b = (hi - p) / d;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    return true;
  };
  if (!clip(x, dx, g.origin_x, g.origin_x + g.width * res) ||
      !clip(y, dy, g.origin_y, g.origin_y + g.height * res) || t0 > t1)
    return max_range;
  const auto occupied = [&](int ix, int iy) {
    return g.contains(ix, iy) && world.at(ix, iy) >= occupied_threshold;
  };
  int ix = std::clamp(g.cell_x(x + t0 * dx), 0, g.width - 1);
  int iy = std::clamp(g.cell_y(y + t0 * dy), 0, g.height - 1);
  const int step_x = dx > 0.0 ? 1 : -1, step_y = dy > 0.0 ? 1 : -1;
  constexpr double kNever = std::numeric_limits<double>::infinity();
  // The distance at which the ray crosses the boundary of column ix (row iy) it goes toward.
  const auto next_x = [&](int column) {
    if (dx == 0.0) return kNever;
    return (g.origin_x + (dx > 0.0 ? column + 1 : column) * res - x) / dx;
  };
  const auto next_y = [&](int row) {
    if (dy == 0.0) return kNever;
    return (g.origin_y + (dy > 0.0 ? row + 1 : row) * res - y) / dy;
  };
  double t_enter = t0;
  double t_x = next_x(ix), t_y = next_y(iy);
  for (;;) {
    if (occupied(ix, iy)) return t_enter < max_range ? t_enter : max_range;
    if (t_x == t_y) {  // through a corner: the ray touches both cells beside it
      t_enter = t_x;
      if (t_enter > t1) return max_range;
      if (occupied(ix + step_x, iy) || occupied(ix, iy + step_y))
        return t_enter < max_range ? t_enter : max_range;
      ix += step_x;
      iy += step_y;
      t_x = next_x(ix);
      t_y = next_y(iy);
    } else if (t_x < t_y) {
      t_enter = t_x;
      ix += step_x;
      t_x = next_x(ix);
    } else {
      t_enter = t_y;
      iy += step_y;
      t_y = next_y(iy);
    }
    if (t_enter > t1 || !g.contains(ix, iy)) return max_range;
  }
}

std::vector<double> true_ranges(const core::ProbabilityGrid& world, const SensorConfig& sensor,
                                const core::Pose2& robot) {
  check_sensor_config(sensor);
  check_world(world);
  require_finite_pose(robot, "robot pose");
  const core::Pose2 s = core::compose(robot, sensor.mount);
  std::vector<double> ranges(sensor.beams);
  std::size_t rays = 1;
  if (sensor.kind == SensorKind::cone) {
    rays = sensor.rays_per_cone;
    if (rays == 0) {
      const double needed =
          std::ceil(sensor.cone_fov * sensor.max_range / world.geometry.resolution) + 1.0;
      rays = static_cast<std::size_t>(std::clamp(needed, 2.0, 100000.0));
    }
  }
  for (std::size_t i = 0; i < sensor.beams; ++i) {
    // The bearing as a Scan computes it, so that a reader of the log finds the same ray.
    const double axis = s.theta + (sensor.angle0 + static_cast<double>(i) * sensor.dangle);
    if (sensor.kind == SensorKind::lidar) {
      ranges[i] = ray_cast(world, s.x, s.y, axis, sensor.max_range, sensor.occupied_threshold);
      continue;
    }
    double nearest = sensor.max_range;
    for (std::size_t k = 0; k < rays; ++k) {
      const double offset =
          rays == 1
              ? 0.0
              : sensor.cone_fov * (static_cast<double>(k) / static_cast<double>(rays - 1) - 0.5);
      nearest = std::min(nearest, ray_cast(world, s.x, s.y, axis + offset, sensor.max_range,
                                           sensor.occupied_threshold));
    }
    ranges[i] = nearest;
  }
  return ranges;
}

// ---------------------------------------------------------------------------------------------
// Range noise

void check_range_noise(const RangeNoiseConfig& c) {
  require_non_negative(c.sigma, "noise.sigma");
  require_probability(c.dropout, "noise.dropout");
  require_probability(c.contamination, "noise.contamination");
}

double corrupt_range(double true_range, double max_range, const RangeNoiseConfig& c,
                     SimRandom& random) {
  const double n = random.normal();
  const double u_dropout = random.uniform();
  const double u_contamination = random.uniform();
  const double u_value = random.uniform_open();
  if (u_dropout < c.dropout) return 0.0;
  if (u_contamination < c.contamination) {
    const double z = u_value * max_range;
    return z < max_range ? z : std::nextafter(max_range, 0.0);
  }
  if (!(true_range < max_range)) return 0.0;
  const double z = true_range + c.sigma * n;
  return z > 0.0 && z < max_range ? z : 0.0;
}

core::Scan simulate_scan(const core::ProbabilityGrid& world, const SensorConfig& sensor,
                         const RangeNoiseConfig& noise, const core::Pose2& robot,
                         SimRandom& random) {
  check_range_noise(noise);
  core::Scan scan;
  scan.robot = robot;
  scan.sensor_mount = sensor.mount;
  scan.angle0 = sensor.angle0;
  scan.dangle = sensor.dangle;
  scan.max_range = sensor.max_range;
  scan.ranges = true_ranges(world, sensor, robot);
  for (double& r : scan.ranges) r = corrupt_range(r, sensor.max_range, noise, random);
  return scan;
}

core::Scan simulate_scan(const core::ProbabilityGrid& world, const SensorConfig& sensor,
                         const RangeNoiseConfig& noise, const core::Pose2& robot,
                         std::uint64_t seed) {
  SimRandom random(seed);
  return simulate_scan(world, sensor, noise, robot, random);
}

// ---------------------------------------------------------------------------------------------
// Unmodelled obstacles

void check_obstacle_config(const ObstacleConfig& c) {
  if (c.count > 1'000'000) fail_field("obstacles.count", "must be at most 10^6");
  require_positive(c.min_diameter, "obstacles.min_diameter");
  require_positive(c.max_diameter, "obstacles.max_diameter");
  if (c.min_diameter > c.max_diameter)
    fail_field("obstacles.min_diameter", "must not exceed max_diameter");
  require_non_negative(c.clearance, "obstacles.clearance");
  if (c.large_distance) {
    require_non_negative(*c.large_distance, "obstacles.large_distance");
    require_positive(c.large_diameter, "obstacles.large_diameter");
  }
}

std::vector<Disc> place_obstacles(const core::ProbabilityGrid& world,
                                  const std::vector<core::Pose2>& truth, const ObstacleConfig& c,
                                  double free_threshold, SimRandom& random) {
  check_obstacle_config(c);
  check_world(world);
  const core::GridGeometry& g = world.geometry;
  std::vector<Disc> discs;
  if (c.count > 0) {
    std::vector<std::size_t> free_cells;
    for (std::size_t i = 0; i < g.size(); ++i)
      if (is_free(world.cells[i], free_threshold)) free_cells.push_back(i);
    if (free_cells.empty())
      fail_field("obstacles.count", "cannot be placed: the world has no free cell");
    const double half_diagonal = 0.5 * kSqrt2 * g.resolution;
    for (std::size_t k = 0; k < c.count; ++k) {
      bool placed = false;
      for (int attempt = 0; attempt < 1000 && !placed; ++attempt) {
        const std::size_t cell = free_cells[random.below(free_cells.size())];
        const int cx = static_cast<int>(cell % g.width), cy = static_cast<int>(cell / g.width);
        const double u = random.uniform(), v = random.uniform(), w = random.uniform();
        const Disc d{g.centre_x(cx) + (u - 0.5) * g.resolution,
                     g.centre_y(cy) + (v - 0.5) * g.resolution,
                     0.5 * (c.min_diameter + w * (c.max_diameter - c.min_diameter))};
        const double keep = c.clearance + d.radius + half_diagonal;
        const bool clear = std::all_of(truth.begin(), truth.end(), [&](const core::Pose2& p) {
          return std::hypot(p.x - d.x, p.y - d.y) >= keep;
        });
        if (!clear) continue;
        const bool inside = d.x - d.radius >= g.origin_x && d.y - d.radius >= g.origin_y &&
                            d.x + d.radius <= g.origin_x + g.width * g.resolution &&
                            d.y + d.radius <= g.origin_y + g.height * g.resolution;
        if (!inside) continue;
        const std::vector<std::pair<int, int>> cells = disc_cells(g, d);
        const bool in_free_space = std::all_of(cells.begin(), cells.end(), [&](auto ij) {
          return is_free(world.at(ij.first, ij.second), free_threshold);
        });
        if (!in_free_space) continue;
        discs.push_back(d);
        placed = true;
      }
      if (!placed)
        fail_field("obstacles.count", "cannot be placed: only " + std::to_string(discs.size()) +
                                          " of " + std::to_string(c.count) +
                                          " obstacles fit in free space away from the trajectory");
    }
  }
  if (c.large_distance) {
    if (truth.empty()) fail_field("obstacles.large_distance", "needs a true pose to measure from");
    const core::Pose2& p = truth.front();
    const double r = 0.5 * c.large_diameter;
    const double reach = *c.large_distance + r;
    discs.push_back({p.x + reach * std::cos(p.theta), p.y + reach * std::sin(p.theta), r});
  }
  return discs;
}

void add_obstacles(core::ProbabilityGrid& world, const std::vector<Disc>& discs) {
  for (const Disc& d : discs)
    for (const auto& [ix, iy] : disc_cells(world.geometry, d)) world.at(ix, iy) = 1.0;
}

// ---------------------------------------------------------------------------------------------
// Simulation

void check_simulation_config(const SimulationConfig& c) {
  check_trajectory_config(c.trajectory);
  check_odometry_noise(c.odometry);
  check_sensor_config(c.sensor);
  check_range_noise(c.noise);
  check_obstacle_config(c.obstacles);
  require_finite(c.start_time, "start_time");
  if (c.true_poses.size() > 10'000'000) fail_field("true_poses", "must hold at most 10^7 poses");
  for (std::size_t i = 0; i < c.true_poses.size(); ++i)
    require_finite_pose(c.true_poses[i], "true_poses[" + std::to_string(i) + "]");
  for (const Point2& p : c.route)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) fail_field("route", "points must be finite");
  if (c.trajectory.free_threshold > c.sensor.occupied_threshold)
    fail_field("trajectory.free_threshold",
               "must not exceed sensor.occupied_threshold (free cells would stop rays)");
}

Simulation simulate(const core::ProbabilityGrid& world, const SimulationConfig& c,
                    std::uint64_t seed) {
  check_simulation_config(c);
  check_world(world);
  std::vector<core::Pose2> truth;
  if (!c.true_poses.empty()) {
    truth = c.true_poses;
  } else if (!c.route.empty()) {
    truth = follow_route(c.route, true, c.trajectory);
  } else {
    truth = random_trajectory(world, c.trajectory, derive_seed(seed, 1));
  }
  Simulation sim;
  sim.world = world;
  SimRandom obstacle_random(derive_seed(seed, 2));
  sim.obstacles =
      place_obstacles(world, truth, c.obstacles, c.trajectory.free_threshold, obstacle_random);
  sim.sensed_world = world;
  add_obstacles(sim.sensed_world, sim.obstacles);
  SimRandom odometry_random(derive_seed(seed, 3));
  const std::vector<core::Pose2> odometry = noisy_odometry(truth, c.odometry, odometry_random);
  SimRandom noise_random(derive_seed(seed, 4));
  sim.log.scans.reserve(truth.size());
  sim.log.odometry.reserve(truth.size());
  sim.truth.scans.reserve(truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const double t = c.start_time + static_cast<double>(i) * c.trajectory.scan_period;
    core::Scan scan = simulate_scan(sim.sensed_world, c.sensor, c.noise, truth[i], noise_random);
    scan.t = t;
    sim.truth.scans.push_back(scan);
    scan.robot = odometry[i];
    sim.log.scans.push_back(std::move(scan));
    sim.log.odometry.push_back({t, odometry[i]});
  }
  return sim;
}

}  // namespace intgrid::simulation
