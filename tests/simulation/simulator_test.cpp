// The simulator against independent oracles: analytic ray lengths in analytic worlds, the
// published splitmix64 sequence, binomial and normal bounds on the noise, brute-force clearance
// of the trajectory, and determinism bit for bit.
#include "intgrid/simulation/simulator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

using namespace intgrid::core;

using namespace intgrid::simulation;

namespace intgrid {
namespace {

constexpr double kPi = std::numbers::pi;

// 5-sigma bound on the mean of n draws of a variable with standard deviation sd.
double mean_bound(double sd, std::size_t n) {
  return 5.0 * sd / std::sqrt(static_cast<double>(n));
}

// A world of width x height cells, all free, origin (ox, oy).
ProbabilityGrid empty_world(int width, int height, double res, double ox = 0.0, double oy = 0.0) {
  GridGeometry g;
  g.width = width;
  g.height = height;
  g.resolution = res;
  g.origin_x = ox;
  g.origin_y = oy;
  return ProbabilityGrid(g, 0.0);
}

// A rectangular room: the outermost ring of cells is wall. Its free interior is the box
// [ox + res, ox + (width - 1) res] x [oy + res, oy + (height - 1) res].
ProbabilityGrid room_world(int width, int height, double res, double ox, double oy) {
  ProbabilityGrid w = empty_world(width, height, res, ox, oy);
  for (int ix = 0; ix < width; ++ix) w.at(ix, 0) = w.at(ix, height - 1) = 1.0;
  for (int iy = 0; iy < height; ++iy) w.at(0, iy) = w.at(width - 1, iy) = 1.0;
  return w;
}

// Distance from (x, y) inside the box along angle to the box's boundary.
double distance_to_box(double x, double y, double angle, double x0, double y0, double x1,
                       double y1) {
  const double dx = std::cos(angle), dy = std::sin(angle);
  double t = std::numeric_limits<double>::infinity();
  if (dx > 0) t = std::min(t, (x1 - x) / dx);
  if (dx < 0) t = std::min(t, (x0 - x) / dx);
  if (dy > 0) t = std::min(t, (y1 - y) / dy);
  if (dy < 0) t = std::min(t, (y0 - y) / dy);
  return t;
}

// Distance along angle from (x, y) to the circle (cx, cy, r), or infinity if the ray misses it.
double distance_to_circle(double x, double y, double angle, double cx, double cy, double r) {
  const double dx = std::cos(angle), dy = std::sin(angle);
  const double fx = x - cx, fy = y - cy;
  const double b = fx * dx + fy * dy;
  const double c = fx * fx + fy * fy - r * r;
  const double disc = b * b - c;
  if (disc < 0) return std::numeric_limits<double>::infinity();
  const double t = -b - std::sqrt(disc);
  return t >= 0 ? t : std::numeric_limits<double>::infinity();
}

// Brute force: distance from (x, y) to the nearest non-free cell's square or the grid's edge.
double brute_clearance(const ProbabilityGrid& world, double x, double y, double free_threshold,
                       double search) {
  const GridGeometry& g = world.geometry;
  double best = std::min({x - g.origin_x, g.origin_x + g.width * g.resolution - x, y - g.origin_y,
                          g.origin_y + g.height * g.resolution - y});
  const int r = static_cast<int>(std::ceil(search / g.resolution)) + 1;
  const int cx = g.cell_x(x), cy = g.cell_y(y);
  for (int iy = cy - r; iy <= cy + r; ++iy) {
    for (int ix = cx - r; ix <= cx + r; ++ix) {
      if (!g.contains(ix, iy) || world.at(ix, iy) < free_threshold) continue;
      const double x0 = g.origin_x + ix * g.resolution, y0 = g.origin_y + iy * g.resolution;
      const double ddx = std::max({x0 - x, 0.0, x - (x0 + g.resolution)});
      const double ddy = std::max({y0 - y, 0.0, y - (y0 + g.resolution)});
      best = std::min(best, std::hypot(ddx, ddy));
    }
  }
  return best;
}

void expect_step_limits(const std::vector<Pose2>& poses, const TrajectoryConfig& c) {
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const double step = std::hypot(poses[i].x - poses[i - 1].x, poses[i].y - poses[i - 1].y);
    const double turn = std::abs(wrap_angle(poses[i].theta - poses[i - 1].theta));
    ASSERT_LE(step, c.speed * c.scan_period + 1e-9) << i;
    ASSERT_LE(turn, c.turn_rate * c.scan_period + 1e-9) << i;
  }
}

// ---------------------------------------------------------------------------------------------
// Random numbers

TEST(SimulatorRandom, Splitmix64GivesThePublishedSequence) {
  std::uint64_t state = 1234567;
  const std::uint64_t expected[] = {6457827717110365317ULL, 3203168211198807973ULL,
                                    9817491932198370423ULL, 4593380528125082431ULL,
                                    16408922859458223821ULL};
  for (const std::uint64_t e : expected) EXPECT_EQ(splitmix64(state), e);
}

TEST(SimulatorRandom, Xoshiro256StarStarMatchesAnIndependentImplementation) {
  // Computed by a Python transcription of Blackman and Vigna's xoshiro256** with the state
  // filled by splitmix64(42).
  SimRandom random(42);
  const std::uint64_t expected[] = {1546998764402558742ULL, 6990951692964543102ULL,
                                    12544586762248559009ULL, 17057574109182124193ULL};
  for (const std::uint64_t e : expected) EXPECT_EQ(random.next_u64(), e);
}

TEST(SimulatorRandom, UniformBelowAndNormalHaveTheirDistributions) {
  SimRandom random(7);
  constexpr std::size_t n = 200000;
  double sum_u = 0, sum_n = 0, sum_n2 = 0;
  std::vector<std::size_t> buckets(7, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double u = random.uniform();
    ASSERT_TRUE(u >= 0.0 && u < 1.0);
    const double o = random.uniform_open();
    ASSERT_TRUE(o > 0.0 && o < 1.0);
    sum_u += u;
    ++buckets[random.below(7)];
    const double z = random.normal();
    sum_n += z;
    sum_n2 += z * z;
  }
  EXPECT_NEAR(sum_u / n, 0.5, mean_bound(std::sqrt(1.0 / 12.0), n));
  const double p = 1.0 / 7.0;
  for (const std::size_t b : buckets)
    EXPECT_NEAR(static_cast<double>(b), n * p, 5.0 * std::sqrt(n * p * (1 - p)));
  EXPECT_NEAR(sum_n / n, 0.0, mean_bound(1.0, n));
  // The variance of z^2 is 2 for a standard normal.
  EXPECT_NEAR(sum_n2 / n, 1.0, mean_bound(std::sqrt(2.0), n));
  EXPECT_THROW(random.below(0), std::invalid_argument);
}

TEST(SimulatorRandom, DerivedStreamsDiffer) {
  EXPECT_NE(derive_seed(1, 1), derive_seed(1, 2));
  EXPECT_NE(derive_seed(1, 1), derive_seed(2, 1));
  EXPECT_EQ(derive_seed(5, 3), derive_seed(5, 3));
}

// ---------------------------------------------------------------------------------------------
// Ray casting

TEST(SimulatorRayCast, RectangularRoomGivesTheAnalyticDistance) {
  const double res = 0.1, ox = -1.3, oy = 0.7;
  const ProbabilityGrid w = room_world(60, 40, res, ox, oy);
  const double x0 = ox + res, x1 = ox + 59 * res, y0 = oy + res, y1 = oy + 39 * res;
  SimRandom random(3);
  for (int i = 0; i < 5000; ++i) {
    const double x = random.uniform(x0 + 1e-6, x1 - 1e-6), y = random.uniform(y0 + 1e-6, y1 - 1e-6);
    const double a = random.uniform(-kPi, kPi);
    const double expected = distance_to_box(x, y, a, x0, y0, x1, y1);
    ASSERT_NEAR(ray_cast(w, x, y, a, 100.0), expected, 1e-9) << x << " " << y << " " << a;
    // A shorter max range than the wall: no hit, reported as max_range.
    ASSERT_EQ(ray_cast(w, x, y, a, 0.5 * expected), 0.5 * expected);
  }
  // Axis-aligned rays and rays exactly through cell corners.
  const double cx = ox + 30 * res, cy = oy + 20 * res;  // a cell corner
  EXPECT_NEAR(ray_cast(w, cx, cy, 0.0, 100.0), x1 - cx, 1e-9);
  EXPECT_NEAR(ray_cast(w, cx, cy, kPi / 2, 100.0), y1 - cy, 1e-9);
  EXPECT_NEAR(ray_cast(w, cx, cy, kPi, 100.0), cx - x0, 1e-9);
  EXPECT_NEAR(ray_cast(w, cx, cy, -kPi / 2, 100.0), cy - y0, 1e-9);
  EXPECT_NEAR(ray_cast(w, cx, cy, kPi / 4, 100.0), distance_to_box(cx, cy, kPi / 4, x0, y0, x1, y1),
              1e-9);
}

TEST(SimulatorRayCast, DiscIsHitWithinOneCellsGeometry) {
  // A disc rasterized by cell centres lies between the circles of radius r -+ half a diagonal.
  const double res = 0.05, r = 1.3, cx = 2.52, cy = 2.47;
  ProbabilityGrid w = empty_world(100, 100, res);
  for (int iy = 0; iy < 100; ++iy)
    for (int ix = 0; ix < 100; ++ix)
      if (std::hypot(w.geometry.centre_x(ix) - cx, w.geometry.centre_y(iy) - cy) <= r)
        w.at(ix, iy) = 1.0;
  const double h = 0.5 * std::sqrt(2.0) * res;
  SimRandom random(4);
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const double x = random.uniform(0.0, 5.0), y = random.uniform(0.0, 5.0);
    if (std::hypot(x - cx, y - cy) < r + 2 * h) continue;
    const double a = random.uniform(-kPi, kPi);
    const double cast = ray_cast(w, x, y, a, 50.0);
    const double outer = distance_to_circle(x, y, a, cx, cy, r + h);
    const double inner = distance_to_circle(x, y, a, cx, cy, r - h);
    if (std::isinf(outer)) {
      ASSERT_EQ(cast, 50.0);
      continue;
    }
    ASSERT_GE(cast, outer - 1e-9);
    if (!std::isinf(inner)) {
      ASSERT_LE(cast, inner + 1e-9);
      ++hits;
    }
  }
  EXPECT_GT(hits, 500);
}

TEST(SimulatorRayCast, EdgeCases) {
  const ProbabilityGrid w = room_world(20, 20, 0.1, 0.0, 0.0);
  EXPECT_EQ(ray_cast(w, 0.05, 0.05, 0.3, 5.0), 0.0);  // inside a wall cell
  // From outside the grid: toward it hits the wall's outer face; away from it nothing.
  EXPECT_NEAR(ray_cast(w, -1.0, 1.0, 0.0, 5.0), 1.0, 1e-12);
  EXPECT_EQ(ray_cast(w, -1.0, 1.0, kPi, 5.0), 5.0);
  EXPECT_EQ(ray_cast(w, -1.0, 1.0, kPi / 2, 5.0), 5.0);
  // The threshold decides what is an obstacle.
  ProbabilityGrid soft = empty_world(20, 1, 0.1);
  soft.at(10, 0) = 0.6;
  EXPECT_EQ(ray_cast(soft, 0.05, 0.05, 0.0, 5.0, 0.65), 5.0);
  EXPECT_NEAR(ray_cast(soft, 0.05, 0.05, 0.0, 5.0, 0.6), 0.95, 1e-12);
  EXPECT_THROW(ray_cast(w, std::nan(""), 1.0, 0.0, 5.0), std::invalid_argument);
}

TEST(SimulatorRayCast, DiagonalWallsHaveNoGaps) {
  // Two staircase walls, cells (i, i) and (i, 39 - i): 8-connected only, touching at corners.
  ProbabilityGrid w = empty_world(40, 40, 0.1);
  for (int i = 0; i < 40; ++i) w.at(i, i) = w.at(i, 39 - i) = 1.0;
  SimRandom random(5);
  for (int k = 0; k < 20000; ++k) {
    // From below both walls (the triangle around x = 2, y < 2) in any upward direction that
    // must cross one of them inside the grid.
    const double x = random.uniform(1.0, 3.0), y = random.uniform(0.0, 0.6);
    if (y >= std::min(x, 4.0 - x) - 0.15) continue;
    const double a = random.uniform(0.3, kPi - 0.3);
    ASSERT_LT(ray_cast(w, x, y, a, 100.0), 100.0) << x << " " << y << " " << a;
  }
  // Exactly through the corners of the staircase.
  EXPECT_LT(ray_cast(w, 2.0, 0.0, kPi / 4, 100.0), 100.0);
  EXPECT_LT(ray_cast(w, 1.0, 0.0, kPi / 4, 100.0), 100.0);
}

TEST(SimulatorSensor, ConeReturnsTheNearestWallWithinItsFov) {
  const double res = 0.05;
  const ProbabilityGrid w = room_world(120, 80, res, 0.0, 0.0);
  const double x0 = res, x1 = 119 * res, y0 = res, y1 = 79 * res;
  SensorConfig sensor = cone_ring_sensor(12, 0.5, 20.0);
  sensor.rays_per_cone = 41;
  const double spacing = sensor.cone_fov / 40.0;
  SimRandom random(6);
  for (int i = 0; i < 200; ++i) {
    const Pose2 pose{random.uniform(0.5, 5.4), random.uniform(0.5, 3.4), random.uniform(-kPi, kPi)};
    const std::vector<double> ranges = true_ranges(w, sensor, pose);
    ASSERT_EQ(ranges.size(), 12u);
    for (std::size_t k = 0; k < 12; ++k) {
      const double axis = pose.theta + sensor.angle0 + static_cast<double>(k) * sensor.dangle;
      // Analytic: per wall, its perpendicular distance if the normal is inside the cone, else the
      // distance along the cone edge nearest the normal.
      double exact = std::numeric_limits<double>::infinity();
      double sampled_bound = exact;
      const double walls[4][2] = {
          {x1 - pose.x, 0.0}, {pose.y - y0, -kPi / 2}, {pose.x - x0, kPi}, {y1 - pose.y, kPi / 2}};
      for (const auto& [d, normal] : walls) {
        const double off = wrap_angle(normal - axis);
        if (std::abs(off) <= 0.5 * sensor.cone_fov) {
          exact = std::min(exact, d);
          sampled_bound = std::min(sampled_bound, d / std::cos(0.5 * spacing));
        } else {
          const double edge = std::abs(off) - 0.5 * sensor.cone_fov;
          if (edge < kPi / 2) {
            exact = std::min(exact, d / std::cos(edge));
            sampled_bound = std::min(sampled_bound, d / std::cos(edge));
          }
        }
      }
      ASSERT_GE(ranges[k], exact - 1e-9);
      ASSERT_LE(ranges[k], sampled_bound + 1e-9);
    }
  }
}

TEST(SimulatorSensor, LidarDefaultsAndMounting) {
  const SensorConfig lidar = lidar_sensor();
  EXPECT_EQ(lidar.beams, 361u);
  EXPECT_NEAR(lidar.angle0, -kPi / 2, 1e-15);
  EXPECT_NEAR(lidar.angle0 + 360 * lidar.dangle, kPi / 2, 1e-12);
  const SensorConfig ring = lidar_sensor(8, 2 * kPi, 5.0);
  EXPECT_NEAR(ring.dangle, kPi / 4, 1e-15);
  // A sensor mounted 0.5 m ahead, facing backwards, in a room: its beam 0 (bearing 0) reads the
  // distance from the mount point to the wall behind the robot.
  const ProbabilityGrid w = room_world(50, 50, 0.1, 0.0, 0.0);
  SensorConfig s = lidar_sensor(1, 0.0, 10.0);
  s.mount = {0.5, 0.0, kPi};
  const std::vector<double> r = true_ranges(w, s, {2.0, 2.5, 0.0});
  EXPECT_NEAR(r[0], 2.5 - 0.1, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// Noise

TEST(SimulatorNoise, GaussianResidualsHaveMeanZeroAndSigma) {
  const ProbabilityGrid w = room_world(100, 100, 0.1, 0.0, 0.0);
  const SensorConfig s = lidar_sensor(361, 2 * kPi, 20.0);
  RangeNoiseConfig noise;
  noise.sigma = 0.05;
  SimRandom random(8);
  double sum = 0, sum2 = 0;
  std::size_t n = 0;
  for (int i = 0; i < 40; ++i) {
    const Pose2 pose{random.uniform(2, 8), random.uniform(2, 8), random.uniform(-kPi, kPi)};
    const std::vector<double> exact = true_ranges(w, s, pose);
    const Scan scan = simulate_scan(w, s, noise, pose, random);
    for (std::size_t k = 0; k < exact.size(); ++k) {
      ASSERT_GT(scan.ranges[k], 0.0);  // every beam hits, no clipping at 1 m from walls
      const double e = scan.ranges[k] - exact[k];
      sum += e;
      sum2 += e * e;
      ++n;
    }
  }
  ASSERT_GT(n, 10000u);
  const double count = static_cast<double>(n);
  const double mean = sum / count, var = sum2 / count - mean * mean;
  EXPECT_NEAR(mean, 0.0, mean_bound(noise.sigma, n));
  // The sample variance of a normal has standard deviation sigma^2 sqrt(2 / n).
  EXPECT_NEAR(var, noise.sigma * noise.sigma,
              5.0 * noise.sigma * noise.sigma * std::sqrt(2.0 / count));
}

TEST(SimulatorNoise, DropoutAndContaminationRatesAreBinomial) {
  const ProbabilityGrid w = room_world(60, 60, 0.1, 0.0, 0.0);
  const SensorConfig s = lidar_sensor(360, 2 * kPi, 10.0);
  RangeNoiseConfig noise;
  noise.sigma = 0.0;
  noise.dropout = 0.1;
  noise.contamination = 0.2;
  SimRandom random(9);
  std::size_t n = 0, dropped = 0, contaminated = 0;
  double contaminated_sum = 0;
  for (int i = 0; i < 60; ++i) {
    const Pose2 pose{random.uniform(1, 5), random.uniform(1, 5), random.uniform(-kPi, kPi)};
    const std::vector<double> exact = true_ranges(w, s, pose);
    const Scan scan = simulate_scan(w, s, noise, pose, random);
    for (std::size_t k = 0; k < exact.size(); ++k) {
      ++n;
      const double z = scan.ranges[k];
      if (z == 0.0) {
        ++dropped;
      } else if (z != exact[k]) {
        ASSERT_TRUE(z > 0.0 && z < s.max_range);
        ++contaminated;
        contaminated_sum += z;
      }
    }
  }
  const double pd = noise.dropout, pc = (1 - noise.dropout) * noise.contamination;
  const double count = static_cast<double>(n);
  EXPECT_NEAR(static_cast<double>(dropped), count * pd, 5 * std::sqrt(count * pd * (1 - pd)));
  EXPECT_NEAR(static_cast<double>(contaminated), count * pc, 5 * std::sqrt(count * pc * (1 - pc)));
  // Contaminated readings are uniform on (0, max_range).
  EXPECT_NEAR(contaminated_sum / static_cast<double>(contaminated), 5.0,
              mean_bound(10.0 / std::sqrt(12.0), contaminated));
}

TEST(SimulatorNoise, NoHitAndNoiseOutsideTheRangeBecomeZero) {
  SimRandom random(10);
  RangeNoiseConfig clean;
  clean.sigma = 0.0;
  EXPECT_EQ(corrupt_range(8.0, 8.0, clean, random), 0.0);  // no hit
  EXPECT_EQ(corrupt_range(3.0, 8.0, clean, random), 3.0);
  RangeNoiseConfig wide;
  wide.sigma = 10.0;
  for (int i = 0; i < 1000; ++i) {
    const double z = corrupt_range(7.9, 8.0, wide, random);
    ASSERT_TRUE(z == 0.0 || (z > 0.0 && z < 8.0)) << z;
  }
}

// ---------------------------------------------------------------------------------------------
// Odometry

TEST(SimulatorOdometry, IncrementResidualsFollowTheAlphaModel) {
  // A true path of random increments; the odometry's own increments, decomposed back into
  // rotation1, translation, rotation2, must differ from the true ones by normals of the
  // model's variances.
  SimRandom random(11);
  std::vector<Pose2> truth{{1.0, 2.0, 0.3}};
  for (int i = 0; i < 6000; ++i) {
    const double rot1 = random.uniform(-0.2, 0.2), trans = random.uniform(0.1, 0.2),
                 rot2 = random.uniform(-0.2, 0.2);
    const Pose2& p = truth.back();
    truth.push_back({p.x + trans * std::cos(p.theta + rot1), p.y + trans * std::sin(p.theta + rot1),
                     wrap_angle(p.theta + rot1 + rot2)});
  }
  // Alphas small enough that the noisy translation stays positive (over 7 sigma).
  const OdometryNoiseConfig c{0.05, 0.01, 0.01, 0.001};
  SimRandom noise(12);
  const std::vector<Pose2> odometry = noisy_odometry(truth, c, noise);
  ASSERT_EQ(odometry.size(), truth.size());
  EXPECT_EQ(odometry[0].x, truth[0].x);
  const auto decompose = [](const Pose2& a, const Pose2& b) {
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double rot1 = wrap_angle(std::atan2(dy, dx) - a.theta);
    return std::array<double, 3>{rot1, std::hypot(dx, dy), wrap_angle(b.theta - a.theta - rot1)};
  };
  std::array<double, 3> sum{}, sum2{};
  const std::size_t n = truth.size() - 1;
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const auto t = decompose(truth[i - 1], truth[i]);
    const auto o = decompose(odometry[i - 1], odometry[i]);
    const double sd[3] = {
        std::sqrt(c.alpha1 * t[0] * t[0] + c.alpha2 * t[1] * t[1]),
        std::sqrt(c.alpha3 * t[1] * t[1] + c.alpha4 * (t[0] * t[0] + t[2] * t[2])),
        std::sqrt(c.alpha1 * t[2] * t[2] + c.alpha2 * t[1] * t[1])};
    for (int k = 0; k < 3; ++k) {
      const double z = (k == 1 ? o[k] - t[k] : wrap_angle(o[k] - t[k])) / sd[k];
      sum[k] += z;
      sum2[k] += z * z;
    }
  }
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(sum[k] / static_cast<double>(n), 0.0, mean_bound(1.0, n));
    EXPECT_NEAR(sum2[k] / static_cast<double>(n), 1.0, mean_bound(std::sqrt(2.0), n));
  }
  // The odometry drifts: its last pose is not the true one.
  EXPECT_GT(std::hypot(odometry.back().x - truth.back().x, odometry.back().y - truth.back().y),
            0.01);
}

// ---------------------------------------------------------------------------------------------
// Floorplan

TEST(SimulatorFloorplan, IsClosedConnectedAndDeterministic) {
  const FloorplanConfig c;
  for (const std::uint64_t seed : {1ULL, 2ULL, 77ULL}) {
    SCOPED_TRACE(seed);
    const Floorplan plan = make_floorplan(c, seed);
    const ProbabilityGrid& w = plan.grid;
    const GridGeometry& g = w.geometry;
    ASSERT_EQ(g.width, 200);
    ASSERT_EQ(g.height, 150);
    EXPECT_EQ(procedural_floorplan(c, seed).cells, w.cells);
    // Only 0 and 1; the outer ring is wall.
    for (const double p : w.cells) ASSERT_TRUE(p == 0.0 || p == 1.0);
    for (int ix = 0; ix < g.width; ++ix) ASSERT_TRUE(w.at(ix, 0) == 1.0 && w.at(ix, g.height - 1));
    for (int iy = 0; iy < g.height; ++iy) ASSERT_TRUE(w.at(0, iy) == 1.0 && w.at(g.width - 1, iy));
    // Every free cell is 4-connected to every other (each room has a door).
    std::vector<char> seen(g.size(), 0);
    std::size_t free_cells = 0, reached = 0;
    int sx = -1, sy = -1;
    for (int iy = 0; iy < g.height; ++iy)
      for (int ix = 0; ix < g.width; ++ix)
        if (w.at(ix, iy) == 0.0) {
          ++free_cells;
          sx = ix;
          sy = iy;
        }
    std::deque<std::pair<int, int>> queue{{sx, sy}};
    seen[g.index(sx, sy)] = 1;
    while (!queue.empty()) {
      const auto [x, y] = queue.front();
      queue.pop_front();
      ++reached;
      const int nx[4] = {x + 1, x - 1, x, x}, ny[4] = {y, y, y + 1, y - 1};
      for (int k = 0; k < 4; ++k) {
        if (!g.contains(nx[k], ny[k]) || w.at(nx[k], ny[k]) != 0.0 || seen[g.index(nx[k], ny[k])])
          continue;
        seen[g.index(nx[k], ny[k])] = 1;
        queue.push_back({nx[k], ny[k]});
      }
    }
    EXPECT_EQ(reached, free_cells);
    EXPECT_GT(free_cells, g.size() / 2);
    // Rays from free cells never leave through the walls: every one hits within the floor's
    // diagonal.
    const double diagonal = std::hypot(20.0, 15.0);
    for (std::size_t i = 0; i < g.size(); i += 37) {
      const int ix = static_cast<int>(i % g.width), iy = static_cast<int>(i / g.width);
      if (w.at(ix, iy) != 0.0) continue;
      for (int k = 0; k < 32; ++k) {
        const double a = 2 * kPi * k / 32 + 0.01;
        ASSERT_LT(ray_cast(w, g.centre_x(ix), g.centre_y(iy), a, 2 * diagonal), diagonal);
      }
    }
    // The corridor loop keeps corridor / 2 - cell from the walls.
    ASSERT_EQ(plan.corridor_loop.size(), 5u);
    const std::vector<Pose2> loop = follow_route(plan.corridor_loop, true, TrajectoryConfig{});
    for (const Pose2& p : loop)
      ASSERT_GE(brute_clearance(w, p.x, p.y, 0.5, 1.0), 0.5 * c.corridor - c.cell);
  }
  EXPECT_NE(procedural_floorplan(c, 1).cells, procedural_floorplan(c, 2).cells);
}

// ---------------------------------------------------------------------------------------------
// Trajectories

TEST(SimulatorTrajectory, CorridorLoopRespectsTheStepLimitsAndGoesAround) {
  TrajectoryConfig c;
  c.scans = 1000;
  const Floorplan plan = make_floorplan(FloorplanConfig{}, 3);
  const std::vector<Pose2> poses = follow_route(plan.corridor_loop, true, c);
  ASSERT_EQ(poses.size(), 1000u);
  expect_step_limits(poses, c);
  EXPECT_EQ(poses[0].x, plan.corridor_loop[0].x);
  EXPECT_EQ(poses[0].y, plan.corridor_loop[0].y);
  EXPECT_NEAR(poses[0].theta, 0.0, 1e-15);
  // 1000 steps of 0.1 m, less those spent turning in the corners (about 8 a corner): more
  // than two laps of 35.6 m.
  double length = 0, turned = 0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    length += std::hypot(poses[i].x - poses[i - 1].x, poses[i].y - poses[i - 1].y);
    turned += wrap_angle(poses[i].theta - poses[i - 1].theta);
  }
  EXPECT_GT(length, 85.0);
  EXPECT_GT(turned, 4 * kPi);  // counter-clockwise, more than two laps' worth of turning
  // An open route ends when it runs out.
  EXPECT_LT(follow_route({{1, 1}, {2, 1}}, false, c).size(), 20u);
  EXPECT_THROW(follow_route({{1, 1}, {1, 1}}, true, c), std::invalid_argument);
}

TEST(SimulatorTrajectory, RandomWaypointsStayInFreeSpaceWithClearance) {
  // A map with unknown (0.5) outside an L-shaped free area and two pillars.
  ProbabilityGrid w = empty_world(120, 100, 0.05, -2.0, 1.0);
  for (int iy = 0; iy < 100; ++iy)
    for (int ix = 0; ix < 120; ++ix)
      if (ix >= 70 && iy >= 50) w.at(ix, iy) = 0.5;
  for (int iy = 20; iy < 30; ++iy)
    for (int ix = 20; ix < 26; ++ix) w.at(ix, iy) = w.at(ix + 30, iy + 20) = 1.0;
  TrajectoryConfig c;
  c.scans = 1500;
  c.robot_radius = 0.25;
  const std::vector<Pose2> poses = random_trajectory(w, c, 5);
  ASSERT_EQ(poses.size(), 1500u);
  expect_step_limits(poses, c);
  double length = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    ASSERT_GE(brute_clearance(w, poses[i].x, poses[i].y, c.free_threshold, 1.0), c.robot_radius)
        << i << " " << poses[i].x << " " << poses[i].y;
    if (i > 0) length += std::hypot(poses[i].x - poses[i - 1].x, poses[i].y - poses[i - 1].y);
  }
  EXPECT_GT(length, 50.0);  // it travels, not only turns
  EXPECT_EQ(random_trajectory(w, c, 5).back().x, poses.back().x);
  EXPECT_NE(random_trajectory(w, c, 6).back().x, poses.back().x);
}

TEST(SimulatorTrajectory, WorldWithoutFreeSpaceIsRefused) {
  ProbabilityGrid w = empty_world(30, 30, 0.1);
  std::fill(w.cells.begin(), w.cells.end(), 1.0);
  EXPECT_THROW(random_trajectory(w, TrajectoryConfig{}, 1), std::invalid_argument);
  // Free, but too narrow for the robot.
  ProbabilityGrid narrow = empty_world(30, 3, 0.1);
  EXPECT_THROW(random_trajectory(narrow, TrajectoryConfig{}, 1), std::invalid_argument);
  SimulationConfig sc;
  EXPECT_THROW(simulate(w, sc, 1), std::invalid_argument);
}

TEST(SimulatorTrajectory, ClearanceMapIsTheExactDistanceToNonFreeCentres) {
  ProbabilityGrid w = empty_world(23, 17, 0.1);
  SimRandom random(13);
  for (double& p : w.cells) p = random.uniform() < 0.08 ? 1.0 : 0.0;
  const Grid<double> d = clearance_map(w, kSimFreeThreshold);
  const GridGeometry& g = w.geometry;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      double best = std::numeric_limits<double>::infinity();
      for (int y = -1; y <= g.height; ++y)
        for (int x = -1; x <= g.width; ++x)
          if (!g.contains(x, y) || w.at(x, y) >= kSimFreeThreshold)
            best = std::min(best, std::hypot(x - ix, y - iy) * g.resolution);
      ASSERT_NEAR(d.at(ix, iy), best, 1e-12) << ix << " " << iy;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The whole simulation

SimulationConfig noisy_config() {
  SimulationConfig c;
  c.trajectory.scans = 120;
  c.noise.sigma = 0.02;
  c.noise.dropout = 0.05;
  c.noise.contamination = 0.05;
  c.obstacles.count = 10;
  return c;
}

void expect_same_log(const Log& a, const Log& b) {
  ASSERT_EQ(a.scans.size(), b.scans.size());
  ASSERT_EQ(a.odometry.size(), b.odometry.size());
  for (std::size_t i = 0; i < a.scans.size(); ++i) {
    const Scan &s = a.scans[i], &t = b.scans[i];
    ASSERT_EQ(s.t, t.t);
    ASSERT_EQ(s.robot.x, t.robot.x);
    ASSERT_EQ(s.robot.y, t.robot.y);
    ASSERT_EQ(s.robot.theta, t.robot.theta);
    ASSERT_EQ(s.angle0, t.angle0);
    ASSERT_EQ(s.dangle, t.dangle);
    ASSERT_EQ(s.max_range, t.max_range);
    ASSERT_EQ(s.ranges, t.ranges);
  }
  for (std::size_t i = 0; i < a.odometry.size(); ++i) {
    ASSERT_EQ(a.odometry[i].t, b.odometry[i].t);
    ASSERT_EQ(a.odometry[i].pose.x, b.odometry[i].pose.x);
    ASSERT_EQ(a.odometry[i].pose.y, b.odometry[i].pose.y);
    ASSERT_EQ(a.odometry[i].pose.theta, b.odometry[i].pose.theta);
  }
}

TEST(SimulatorRun, SameSeedSameLogsDifferentSeedDifferent) {
  const ProbabilityGrid world = procedural_floorplan(FloorplanConfig{}, 1);
  const SimulationConfig c = noisy_config();  // random waypoints
  const Simulation a = simulate(world, c, 42), b = simulate(world, c, 42);
  expect_same_log(a.log, b.log);
  expect_same_log(a.truth, b.truth);
  EXPECT_EQ(a.sensed_world.cells, b.sensed_world.cells);
  const Simulation other = simulate(world, c, 43);
  ASSERT_EQ(other.log.scans.size(), a.log.scans.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.log.scans.size(); ++i)
    differing += a.log.scans[i].ranges != other.log.scans[i].ranges ? 1 : 0;
  EXPECT_EQ(differing, a.log.scans.size());
  EXPECT_NE(a.truth.scans.back().robot.x, other.truth.scans.back().robot.x);
}

TEST(SimulatorRun, LogLayoutTimesAndOdometryRecords) {
  const Floorplan plan = make_floorplan(FloorplanConfig{}, 2);
  SimulationConfig c = noisy_config();
  c.route = plan.corridor_loop;
  c.sensor = cone_ring_sensor();
  const Simulation s = simulate(plan.grid, c, 1);
  ASSERT_EQ(s.log.scans.size(), 120u);
  ASSERT_EQ(s.truth.scans.size(), 120u);
  ASSERT_EQ(s.log.odometry.size(), 120u);
  EXPECT_TRUE(s.truth.odometry.empty());
  for (std::size_t i = 0; i < 120; ++i) {
    const Scan &l = s.log.scans[i], &t = s.truth.scans[i];
    EXPECT_EQ(l.t, 1e9 + static_cast<double>(i) * 0.2);
    EXPECT_EQ(t.t, l.t);
    EXPECT_EQ(s.log.odometry[i].t, l.t);
    EXPECT_EQ(s.log.odometry[i].pose.x, l.robot.x);
    EXPECT_EQ(s.log.odometry[i].pose.theta, l.robot.theta);
    EXPECT_EQ(l.ranges, t.ranges);
    EXPECT_EQ(l.ranges.size(), 16u);
  }
  // Noisy odometry drifts from the truth after 120 scans; the first pose is shared.
  EXPECT_EQ(s.log.scans[0].robot.x, s.truth.scans[0].robot.x);
  EXPECT_NE(s.log.scans.back().robot.x, s.truth.scans.back().robot.x);
  EXPECT_EQ(s.world.cells, plan.grid.cells);
}

TEST(SimulatorRun, WithoutNoiseOdometryIsTruthAndRangesAreRayCasts) {
  const Floorplan plan = make_floorplan(FloorplanConfig{}, 4);
  SimulationConfig c;
  c.trajectory.scans = 60;
  c.route = plan.corridor_loop;
  c.odometry = {0, 0, 0, 0};
  c.noise = {0.0, 0.0, 0.0};
  c.obstacles.count = 5;
  const Simulation s = simulate(plan.grid, c, 9);
  for (std::size_t i = 0; i < s.log.scans.size(); ++i) {
    const Scan &l = s.log.scans[i], &t = s.truth.scans[i];
    ASSERT_EQ(l.robot.x, t.robot.x);
    ASSERT_EQ(l.robot.y, t.robot.y);
    ASSERT_EQ(l.robot.theta, t.robot.theta);
    const Pose2 sensor = t.sensor_pose();
    for (std::size_t k = 0; k < t.ranges.size(); ++k) {
      const double cast =
          ray_cast(s.sensed_world, sensor.x, sensor.y, sensor.theta + t.bearing(k), t.max_range);
      ASSERT_EQ(t.ranges[k], cast < t.max_range ? cast : 0.0) << i << " " << k;
    }
  }
}

TEST(SimulatorRun, UnmodelledObstaclesShortenReadingsButAreNotInTheMap) {
  const Floorplan plan = make_floorplan(FloorplanConfig{}, 5);
  SimulationConfig c;
  c.trajectory.scans = 300;
  c.route = plan.corridor_loop;
  c.odometry = {0, 0, 0, 0};
  c.noise = {0.0, 0.0, 0.0};
  const Simulation clean = simulate(plan.grid, c, 3);
  c.obstacles.count = 30;
  const Simulation cluttered = simulate(plan.grid, c, 3);
  ASSERT_EQ(cluttered.obstacles.size(), 30u);
  EXPECT_EQ(cluttered.world.cells, plan.grid.cells);
  EXPECT_EQ(clean.sensed_world.cells, plan.grid.cells);
  // The obstacles' cells: free in the map, away from every true position.
  const GridGeometry& g = plan.grid.geometry;
  std::size_t added = 0;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      if (cluttered.sensed_world.at(ix, iy) == plan.grid.at(ix, iy)) continue;
      ++added;
      EXPECT_EQ(plan.grid.at(ix, iy), 0.0);
      EXPECT_EQ(cluttered.sensed_world.at(ix, iy), 1.0);
      const double x0 = g.origin_x + ix * g.resolution, y0 = g.origin_y + iy * g.resolution;
      for (const Scan& scan : cluttered.truth.scans) {
        const double dx = std::max({x0 - scan.robot.x, 0.0, scan.robot.x - x0 - g.resolution});
        const double dy = std::max({y0 - scan.robot.y, 0.0, scan.robot.y - y0 - g.resolution});
        ASSERT_GE(std::hypot(dx, dy), c.obstacles.clearance);
      }
    }
  }
  EXPECT_GE(added, 30u);
  // Same trajectory; readings only get shorter (0 = no hit counts as longest), some do.
  std::size_t shorter = 0;
  for (std::size_t i = 0; i < clean.truth.scans.size(); ++i) {
    const Scan &a = clean.truth.scans[i], &b = cluttered.truth.scans[i];
    ASSERT_EQ(a.robot.x, b.robot.x);
    for (std::size_t k = 0; k < a.ranges.size(); ++k) {
      const double ra = a.ranges[k] == 0.0 ? a.max_range : a.ranges[k];
      const double rb = b.ranges[k] == 0.0 ? b.max_range : b.ranges[k];
      ASSERT_LE(rb, ra);
      shorter += rb < ra ? 1 : 0;
    }
  }
  EXPECT_GT(shorter, 50u);
}

TEST(SimulatorRun, LargeObstacleStandsAtItsDistanceAhead) {
  const Floorplan plan = make_floorplan(FloorplanConfig{}, 6);
  SimulationConfig c;
  c.true_poses = {{10.0, 4.7, 0.0}};
  c.noise.sigma = 0.0;
  c.obstacles.large_distance = 2.0;
  c.obstacles.large_diameter = 1.0;
  const Simulation s = simulate(plan.grid, c, 1);
  ASSERT_EQ(s.log.scans.size(), 1u);
  ASSERT_EQ(s.obstacles.size(), 1u);
  const Scan& scan = s.truth.scans[0];
  const double ahead = scan.ranges[180];  // bearing 0
  const double h = 0.5 * std::sqrt(2.0) * 0.1;
  EXPECT_GE(ahead, 2.0 - h - 1e-9);
  EXPECT_LE(ahead, 2.0 + h + 1e-9);
  EXPECT_EQ(s.world.cells, plan.grid.cells);
}

TEST(SimulatorRun, GivenTruePosesAreUsedAsTheyAre) {
  const Floorplan plan = make_floorplan(FloorplanConfig{}, 7);
  SimulationConfig c;
  c.true_poses = {{10.0, 4.7, 0.0}, {10.1, 4.7, 0.05}, {10.25, 4.72, 0.1}};
  const Simulation s = simulate(plan.grid, c, 1);
  ASSERT_EQ(s.truth.scans.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(s.truth.scans[i].robot.x, c.true_poses[i].x);
    EXPECT_EQ(s.truth.scans[i].robot.theta, c.true_poses[i].theta);
  }
}

// ---------------------------------------------------------------------------------------------
// Validation

void expect_invalid(const std::function<void()>& f, const std::string& field) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one naming " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(SimulatorValidation, EveryBadFieldIsNamed) {
  const double nan = std::nan("");
  RangeNoiseConfig n;
  n.sigma = -0.1;
  expect_invalid([&] { check_range_noise(n); }, "noise.sigma");
  n = {};
  n.dropout = 1.5;
  expect_invalid([&] { check_range_noise(n); }, "noise.dropout");
  n = {};
  n.contamination = nan;
  expect_invalid([&] { check_range_noise(n); }, "noise.contamination");

  SensorConfig s;
  s.beams = 0;
  expect_invalid([&] { check_sensor_config(s); }, "sensor.beams");
  s = {};
  s.max_range = 0.0;
  expect_invalid([&] { check_sensor_config(s); }, "sensor.max_range");
  s = {};
  s.max_range = nan;
  expect_invalid([&] { check_sensor_config(s); }, "sensor.max_range");
  s = cone_ring_sensor();
  s.cone_fov = 0.0;
  expect_invalid([&] { check_sensor_config(s); }, "sensor.cone_fov");
  s = {};
  s.mount.theta = nan;
  expect_invalid([&] { check_sensor_config(s); }, "sensor.mount");

  OdometryNoiseConfig o;
  o.alpha2 = nan;
  expect_invalid([&] { check_odometry_noise(o); }, "odometry.alpha2");
  o = {};
  o.alpha4 = -1;
  expect_invalid([&] { check_odometry_noise(o); }, "odometry.alpha4");

  TrajectoryConfig t;
  t.scans = 0;
  expect_invalid([&] { check_trajectory_config(t); }, "trajectory.scans");
  t = {};
  t.scan_period = nan;
  expect_invalid([&] { check_trajectory_config(t); }, "trajectory.scan_period");
  t = {};
  t.speed = -1;
  expect_invalid([&] { check_trajectory_config(t); }, "trajectory.speed");

  FloorplanConfig f;
  f.cell = 0.0;
  expect_invalid([&] { check_floorplan_config(f); }, "floorplan.cell");
  f = {};
  f.width = 8.0;
  expect_invalid([&] { check_floorplan_config(f); }, "floorplan.width");
  f = {};
  f.cell = 0.5;
  expect_invalid([&] { check_floorplan_config(f); }, "floorplan.door");

  ObstacleConfig ob;
  ob.min_diameter = 0.5;
  ob.max_diameter = 0.3;
  expect_invalid([&] { check_obstacle_config(ob); }, "obstacles.min_diameter");
  ob = {};
  ob.large_distance = -1.0;
  expect_invalid([&] { check_obstacle_config(ob); }, "obstacles.large_distance");

  SimulationConfig sim;
  sim.true_poses = {{0, 0, nan}};
  expect_invalid([&] { check_simulation_config(sim); }, "true_poses[0]");
  sim = {};
  sim.trajectory.free_threshold = 0.9;
  expect_invalid([&] { check_simulation_config(sim); }, "trajectory.free_threshold");

  // Too many obstacles for the space is named too.
  SimulationConfig crowded;
  crowded.trajectory.scans = 20;
  crowded.obstacles.count = 5;
  crowded.obstacles.clearance = 100.0;
  expect_invalid([&] { simulate(procedural_floorplan(FloorplanConfig{}, 1), crowded, 1); },
                 "obstacles.count");
}

}  // namespace
}  // namespace intgrid
