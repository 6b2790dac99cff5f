// Trajectories through a world's free space.
#include "intgrid/simulation/simulator.hpp"

#include <limits>
#include <queue>
#include <stdexcept>

#include "simulation_support.hpp"

namespace intgrid::simulation {

using namespace support;

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

}  // namespace intgrid::simulation
