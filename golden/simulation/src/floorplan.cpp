// Procedural floorplans: rooms along corridors, doors, furniture.
#include "intgrid/simulation/simulator.hpp"

#include "simulation_support.hpp"

namespace intgrid::simulation {

using namespace support;

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

}  // namespace intgrid::simulation
