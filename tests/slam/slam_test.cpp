// Unit tests of the event-driven grid SLAM (golden/slam*.hpp, docs/algorithms.md 6), through its
// public API only, with independent oracles computed here in double precision: a synthetic
// room (6 m x 6 m, one pillar) whose ranges come from an analytic ray-box intersection, seen by
// a full-circle scanner mounted off the robot's centre and turned.
//
// The oracles, and the bounds (each test prints its measured values as "[slam] ..."):
// - set-up: the sine table, bearings and mount against the doubles (half a unit); the SLAM
//   origin's cell centred on (0, 0); the narrow ISM table equal to the scan inserter's beams;
//   every bad setting named in the message.
// - mapping: the first scan's cells against its analytic hit points (occupied within one cell
//   of a hit, every hit next to an occupied cell, the line of sight empty, nothing outside the
//   room or past max range); a spread Pi's map against the mixture of single-pose maps.
// - motion: the mean of Pi follows the composed odometry within half a cell and one heading
//   bin, sigma grows, the mass stays 1 (double exactly, U_gamma within its rounding).
// - localization: from a map made at a known pose, a displaced reading moves the estimate
//   toward the truth and the mode to the nearest grid pose.
// - a 40-scan loop with a biased odometry: both arithmetics within the pose grid's rounding of
//   the truth, far better than the odometry, close to each other, bit-identical when re-run.
// - logs, the schedule, the trajectory error by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "intgrid/core/scan_insertion.hpp"
#include "intgrid/core/sensor_model.hpp"
#include "intgrid/slam/grid_slam.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"
#include "intgrid/slam/log_run.hpp"
#include "intgrid/slam/probabilities.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

using namespace intgrid::core;
using namespace intgrid::slam;

namespace intgrid {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kUnit = 2.0 * kPi / kAngleUnitsPerTurn;  // radians per angle unit

// ---------------------------------------------------------------------------------------------
// The synthetic world: the inside of a room box plus solid pillars.

struct Box {
  double x0, y0, x1, y1;
};

struct World {
  Box room{-3.0, -3.0, 3.0, 3.0};  // 6 m x 6 m
  std::vector<Box> pillars;

  // Distance from (ox, oy) along direction a to the first surface (the ray starts inside).
  double cast(double ox, double oy, double a) const {
    const double dx = std::cos(a), dy = std::sin(a);
    double t = std::numeric_limits<double>::infinity();
    if (dx > 0.0) t = std::min(t, (room.x1 - ox) / dx);
    if (dx < 0.0) t = std::min(t, (room.x0 - ox) / dx);
    if (dy > 0.0) t = std::min(t, (room.y1 - oy) / dy);
    if (dy < 0.0) t = std::min(t, (room.y0 - oy) / dy);
    for (const Box& b : pillars) {
      // Slab method: entry distance of the ray into the box, if it enters it ahead.
      double lo = -std::numeric_limits<double>::infinity();
      double hi = std::numeric_limits<double>::infinity();
      bool miss = false;
      const auto slab = [&](double o, double d, double b0, double b1) {
        if (d == 0.0) {
          if (o < b0 || o > b1) miss = true;
          return;
        }
        double t0 = (b0 - o) / d, t1 = (b1 - o) / d;
        if (t0 > t1) std::swap(t0, t1);
        lo = std::max(lo, t0);
        hi = std::min(hi, t1);
      };
      slab(ox, dx, b.x0, b.x1);
      slab(oy, dy, b.y0, b.y1);
      if (!miss && lo <= hi && lo > 0.0) t = std::min(t, lo);
    }
    return t;
  }

  // Distance from (x, y) to the nearest surface.
  double clearance(double x, double y) const {
    double d = std::min({std::abs(x - room.x0), std::abs(room.x1 - x), std::abs(y - room.y0),
                         std::abs(room.y1 - y)});
    for (const Box& b : pillars) {
      const double ex = std::max({b.x0 - x, 0.0, x - b.x1});
      const double ey = std::max({b.y0 - y, 0.0, y - b.y1});
      d = std::min(d, std::hypot(ex, ey));
    }
    return d;
  }

  bool inside_room(double x, double y, double margin) const {
    return x > room.x0 - margin && x < room.x1 + margin && y > room.y0 - margin &&
           y < room.y1 + margin;
  }
};

World room_with_pillar() {
  World w;
  w.pillars.push_back({1.6, 1.4, 2.0, 1.9});
  return w;
}

const Pose2 kMount{0.15, 0.05, 0.3};

// A full-circle scan of `beams` readings from the true pose `truth`, logged at the odometry pose
// `odom`, with the range noise noise(i) added to beam i.
template <class Noise>
Scan make_scan(const World& world, const Pose2& truth, const Pose2& odom, double t, int beams,
               Noise&& noise) {
  Scan s;
  s.t = t;
  s.robot = odom;
  s.sensor_mount = kMount;
  s.angle0 = -kPi;
  s.dangle = 2.0 * kPi / beams;
  s.max_range = 20.0;
  const Pose2 sensor = compose(truth, kMount);
  for (int i = 0; i < beams; ++i)
    s.ranges.push_back(world.cast(sensor.x, sensor.y, sensor.theta + s.bearing(i)) + noise(i));
  return s;
}

Scan make_scan(const World& world, const Pose2& truth, const Pose2& odom, double t, int beams) {
  return make_scan(world, truth, odom, t, beams, [](int) { return 0.0; });
}

// A deterministic sequence in [-1, 1) (std::mt19937's output is fixed by the standard; its
// distributions are not).
class Jitter {
 public:
  explicit Jitter(unsigned seed) : g_(seed) {}
  double operator()() { return static_cast<double>(g_()) / 2147483648.0 - 1.0; }

 private:
  std::mt19937 g_;
};

double wrap(double a) {
  return std::remainder(a, 2.0 * kPi);
}

GridSlamConfig small_config() {
  GridSlamConfig c;
  c.beam.max_range = 10.0;
  c.map.margin = 2.0;
  return c;
}

// Every scan of the log as the per-scan path's input, through the public quantization.
std::vector<QuantizedScan> quantize(const Log& log, const GridSlamConfig& config) {
  SlamRun counts;
  return quantize_scans(log, config, counts);
}

template <class Pr>
double probability_of(const GridSlamEngine<Pr>& slam, typename Pr::P p) {
  if constexpr (std::is_same_v<Pr, IndexProbabilities>)
    return slam.probabilities().u.to_probability(p);
  else
    return p;
}

template <class Pr>
double mass(const GridSlamEngine<Pr>& slam) {
  double total = 0.0;
  for (const auto p : slam.pose_grid()) total += probability_of(slam, p);
  return total;
}

// The roundings on the longest path of GridSlamEngine's pairwise sum of n terms: up to 4 terms are
// added in a chain from 0 (the first addition is exact), more are split in halves.
int pairwise_depth(std::size_t n) {
  if (n <= 4) return n == 0 ? 0 : static_cast<int>(n) - 1;
  return 1 + std::max(pairwise_depth(n / 2), pairwise_depth(n - n / 2));
}

template <class Pr>
std::size_t mode_of(const GridSlamEngine<Pr>& slam) {
  const auto& pi = slam.pose_grid();
  std::size_t best = 0;
  for (std::size_t q = 1; q < pi.size(); ++q)
    if (slam.probabilities().more_probable(pi[q], pi[best])) best = q;
  return best;
}

// The estimate as a pose in the SLAM frame (metres, radians).
Pose2 pose_of(const SlamEstimate& e) {
  return {static_cast<double>(e.x_um) * 1e-6, static_cast<double>(e.y_um) * 1e-6,
          static_cast<double>(e.theta_q8) / 256.0 * kUnit};
}

// ---------------------------------------------------------------------------------------------
// 1. Set-up.

TEST(SlamSetup, SineTableIsWithinOneStepOfStdSin) {
  const World world;
  const SlamSetup s = make_slam_setup(small_config(), make_scan(world, {}, {}, 0.0, 90), 1.0);
  ASSERT_EQ(s.sin_q16.size(), static_cast<std::size_t>(kAngleUnitsPerTurn));
  double worst = 0.0;
  for (int a = 0; a < kAngleUnitsPerTurn; ++a) {
    const double exact = std::sin(2.0 * kPi * a / kAngleUnitsPerTurn);
    const double err = std::abs(s.sin_q16[static_cast<std::size_t>(a)] / 65536.0 - exact);
    worst = std::max(worst, err);
    ASSERT_LE(err, 1.0 / 65536.0) << a;
  }
  // Exact where sin is: 0, 1, -1.
  EXPECT_EQ(s.sin_q16[0], 0);
  EXPECT_EQ(s.sin_q16[16384], 65536);
  EXPECT_EQ(s.sin_q16[32768], 0);
  EXPECT_EQ(s.sin_q16[49152], -65536);
  std::printf("[slam] sine table: worst error %.3g (bound %.3g)\n", worst, 1.0 / 65536.0);
}

TEST(SlamSetup, SensorGeometryInIntegerUnitsMatchesTheDoubles) {
  const World world;
  for (const int beams : {36, 90, 361}) {
    Scan geometry = make_scan(world, {}, {}, 0.0, beams);
    geometry.angle0 = -2.1;  // not a whole number of units
    const SlamSetup s = make_slam_setup(small_config(), geometry, 0.5);
    ASSERT_EQ(s.sensor.bearing.size(), static_cast<std::size_t>(beams));
    for (int i = 0; i < beams; ++i)
      ASSERT_LE(std::abs(s.sensor.bearing[static_cast<std::size_t>(i)] * kUnit -
                         geometry.bearing(static_cast<std::size_t>(i))),
                0.5 * kUnit + 1e-12)
          << i;
    EXPECT_LE(std::abs(s.sensor.mount_x_mm - 1000.0 * kMount.x), 0.5);
    EXPECT_LE(std::abs(s.sensor.mount_y_mm - 1000.0 * kMount.y), 0.5);
    EXPECT_LE(std::abs(s.sensor.mount_theta * kUnit - kMount.theta), 0.5 * kUnit);
    EXPECT_EQ(s.cell_mm, 100);
    EXPECT_EQ(s.sigma_mm, 50);
    EXPECT_EQ(s.max_range_mm, 10000);
  }
}

TEST(SlamSetup, MapPutsTheSlamOriginCellOnTheOrigin) {
  const World world;
  for (const double cell : {0.1, 0.05, 0.037}) {
    GridSlamConfig c = small_config();
    c.cell = cell;
    const double reach = 3.3;
    const SlamSetup s = make_slam_setup(c, make_scan(world, {}, {}, 0.0, 90), reach);
    const GridGeometry& g = s.map_geometry;
    EXPECT_NEAR(g.centre_x(s.origin_cell_x), 0.0, 1e-9) << cell;
    EXPECT_NEAR(g.centre_y(s.origin_cell_y), 0.0, 1e-9) << cell;
    EXPECT_EQ(g.resolution, cell);
    EXPECT_EQ(g.cell_x(0.0), s.origin_cell_x);
    EXPECT_EQ(g.cell_y(0.0), s.origin_cell_y);
    // Every point within the odometry's reach plus a full-range reading, plus the margin, is in.
    const double needed = reach + c.beam.max_range + c.map.margin;
    for (const double sx : {-1.0, 1.0})
      for (const double sy : {-1.0, 1.0})
        EXPECT_TRUE(g.contains(g.cell_x(sx * needed), g.cell_y(sy * needed))) << cell;
  }
}

TEST(SlamSetup, NarrowIsmTableIsTheScanInsertersBeams) {
  const World world;
  for (const int divisor : {1, 3}) {
    GridSlamConfig c = small_config();
    c.beam.max_range = 6.0;
    c.map.empty_divisor = divisor;
    const SlamSetup s = make_slam_setup(c, make_scan(world, {}, {}, 0.0, 90), 0.0);
    const NarrowIsmTable& t = s.ism;
    EXPECT_EQ(t.z_step_mm, 12);  // cell / 8
    const std::size_t bins = static_cast<std::size_t>(s.max_range_mm / t.z_step_mm + 2);
    ASSERT_EQ(t.begin.size(), bins + 1);
    EXPECT_EQ(t.begin[0], t.begin[1]);  // a reading of 0 has no cells
    EXPECT_EQ(t.begin.back(), t.values.size());
    // The oracle: the integer scan inserter with the same model, codec and veto.
    IndexScanInserter<std::int8_t> inserter(GaussianBeamModel{c.beam.sigma, 0.0}, c.cell, s.codec,
                                            VetoBound::strongest_claim, t.z_step_mm / 1000.0);
    std::size_t checked = 0;
    for (std::size_t b = 1; b < bins; b += 7) {
      const std::vector<std::int8_t>& beam =
          inserter.beam_indices(static_cast<double>(b) * t.z_step_mm / 1000.0);
      ASSERT_EQ(t.begin[b + 1] - t.begin[b], beam.size()) << b;
      bool positive = false;
      for (std::size_t k = 0; k < beam.size(); ++k) {
        const int n = beam[k];
        const int expected = n >= 0 ? n : -((-n + divisor - 1) / divisor);
        ASSERT_EQ(t.values[t.begin[b] + k], expected) << "bin " << b << " cell " << k;
        positive = positive || n > 0;
      }
      // Every reading claims some cell occupied, near z.
      EXPECT_TRUE(positive) << b;
      ++checked;
    }
    EXPECT_GT(checked, 50u);
    EXPECT_LE(std::abs(s.max_seps_index), 127);
    EXPECT_EQ(s.max_seps_index, s.codec.max_index());
  }
}

TEST(SlamSetup, ConfigCheckNamesEachBadField) {
  EXPECT_NO_THROW(check_grid_slam_config(GridSlamConfig{}));
  struct Case {
    const char* field;
    void (*spoil)(GridSlamConfig&);
  };
  const Case cases[] = {
      {"cell", [](GridSlamConfig& c) { c.cell = 0.1234; }},  // not a whole number of mm
      {"cell", [](GridSlamConfig& c) { c.cell = 0.0; }},
      {"headings", [](GridSlamConfig& c) { c.headings = 1000; }},
      {"headings", [](GridSlamConfig& c) { c.headings = 4; }},
      {"window.cells", [](GridSlamConfig& c) { c.window.cells = 10; }},
      {"window.headings", [](GridSlamConfig& c) { c.window.headings = 12; }},
      {"window.headings",
       [](GridSlamConfig& c) {
         c.headings = 8;
         c.window.headings = 9;
       }},
      {"schedule.lambda", [](GridSlamConfig& c) { c.schedule.lambda = 0; }},
      {"schedule.xi", [](GridSlamConfig& c) { c.schedule.xi = 0; }},
      {"beam.sigma",
       [](GridSlamConfig& c) { c.beam.sigma = std::numeric_limits<double>::quiet_NaN(); }},
      {"beam.sigma", [](GridSlamConfig& c) { c.beam.sigma = 0.0005; }},
      {"beam.likelihood_floor", [](GridSlamConfig& c) { c.beam.likelihood_floor = 0.0; }},
      {"beam.beams", [](GridSlamConfig& c) { c.beam.beams = 0; }},
      {"beam.tempering", [](GridSlamConfig& c) { c.beam.tempering = 0; }},
      {"beam.max_range", [](GridSlamConfig& c) { c.beam.max_range = -1.0; }},
      {"window.pose_cutoff", [](GridSlamConfig& c) { c.window.pose_cutoff = 0.0; }},
      {"window.pose_prune", [](GridSlamConfig& c) { c.window.pose_prune = -1e-9; }},
      {"window.pose_prune",
       [](GridSlamConfig& c) { c.window.pose_prune = std::numeric_limits<double>::quiet_NaN(); }},
      {"window.pose_prune", [](GridSlamConfig& c) { c.window.pose_prune = c.window.pose_cutoff; }},
      {"motion", [](GridSlamConfig& c) { c.motion.xy_per_m = -0.1; }},
      {"motion",
       [](GridSlamConfig& c) { c.motion.theta0 = std::numeric_limits<double>::infinity(); }},
      {"map.seps_bits", [](GridSlamConfig& c) { c.map.seps_bits = 9; }},
      // 128 > the largest index 127. (127 itself is accepted, though the message says "below
      // the largest index".)
      {"map.seps_levels", [](GridSlamConfig& c) { c.map.seps_levels = 128; }},
      {"map.empty_divisor", [](GridSlamConfig& c) { c.map.empty_divisor = 0; }},
      {"ugamma.bits", [](GridSlamConfig& c) { c.ugamma.bits = 32; }},
      {"ugamma.steps_per_halving", [](GridSlamConfig& c) { c.ugamma.steps_per_halving = 0; }},
      {"map.margin",
       [](GridSlamConfig& c) { c.map.margin = std::numeric_limits<double>::quiet_NaN(); }},
  };
  for (const Case& k : cases) {
    GridSlamConfig c;
    k.spoil(c);
    try {
      check_grid_slam_config(c);
      ADD_FAILURE() << "accepted a bad " << k.field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(k.field), std::string::npos)
          << "message for " << k.field << ": " << e.what();
    }
    // make_slam_setup checks too.
    EXPECT_THROW(make_slam_setup(c, make_scan(World{}, {}, {}, 0.0, 36), 0.0),
                 std::invalid_argument)
        << k.field;
  }
  EXPECT_THROW(make_slam_setup(GridSlamConfig{}, make_scan(World{}, {}, {}, 0.0, 36), -1.0),
               std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// 2. Mapping geometry: the first scan is mapped from the single pose at the origin.

// The map cell holding the SLAM-frame point (x, y).
int cell_of(double v, double cell) {
  return static_cast<int>(std::floor(v / cell + 0.5));
}

template <class Pr>
Grid<std::int8_t> first_scan_map(const SlamSetup& setup, const QuantizedScan& scan) {
  GridSlamEngine<Pr> slam(setup, make_probabilities<Pr>(setup));
  slam.process(scan);
  EXPECT_EQ(slam.mappings(), 1u);
  EXPECT_EQ(slam.localizations(), 0u);
  EXPECT_EQ(slam.estimate().x_um, 0);
  EXPECT_EQ(slam.estimate().y_um, 0);
  EXPECT_EQ(slam.estimate().theta_q8, 0);
  EXPECT_EQ(slam.estimate().sigma_um, 0);
  return slam.map();
}

TEST(SlamMapping, FirstScanMarksTheHitsAndClearsTheLineOfSight) {
  const World world = room_with_pillar();
  // The robot's world pose; the SLAM frame is this pose, so the room appears rotated in it.
  const Pose2 robot{0.3, -0.4, 0.5};
  GridSlamConfig config = small_config();
  config.schedule.lambda = 1000;
  config.beam.max_range = 3.2;  // some walls are farther: those readings are dropped
  Log log;
  log.scans.push_back(make_scan(world, robot, robot, 0.0, 90));
  const Scan& scan = log.scans[0];
  const SlamSetup setup = make_slam_setup(config, scan, 0.0);
  const std::vector<QuantizedScan> q = quantize(log, config);
  const Grid<std::int8_t> map = first_scan_map<DoubleProbabilities>(setup, q[0]);
  // The map does not depend on the arithmetic of Pi while Pi is one pose.
  EXPECT_EQ(map.cells, first_scan_map<IndexProbabilities>(setup, q[0]).cells);

  const double c = config.cell;
  const Pose2 sensor = kMount;  // in the SLAM frame
  const auto to_world = [&](double x, double y) { return compose(robot, {x, y, 0.0}); };
  // Hits of the usable readings, as SLAM-frame cells.
  std::vector<std::pair<int, int>> hits;
  std::size_t dropped = 0;
  const auto usable = [&](std::size_t i) { return q[0].range_mm[i] > 0; };
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double z = scan.ranges[i];
    if (!usable(i)) {
      ASSERT_GE(z, config.beam.max_range - 0.001) << i;
      ++dropped;
      continue;
    }
    const double a = sensor.theta + scan.bearing(i);
    hits.emplace_back(cell_of(sensor.x + z * std::cos(a), c),
                      cell_of(sensor.y + z * std::sin(a), c));
  }
  ASSERT_GT(dropped, 5u);
  ASSERT_GT(hits.size(), 30u);

  // (a) every positive cell is within one cell of a hit; (b) every touched cell is inside the
  // room (plus two cells) and within max_range (plus two cells) of the sensor.
  int positive = 0, negative = 0, worst_hit_distance = 0;
  double farthest = 0.0;
  const GridGeometry& g = map.geometry;
  for (int iy = 0; iy < g.height; ++iy)
    for (int ix = 0; ix < g.width; ++ix) {
      const int n = map.at(ix, iy);
      if (n == 0) continue;
      const int cx = ix - setup.origin_cell_x, cy = iy - setup.origin_cell_y;
      const Pose2 w = to_world(cx * c, cy * c);
      ASSERT_TRUE(world.inside_room(w.x, w.y, 2 * c)) << cx << "," << cy;
      const double r = std::hypot(cx * c - sensor.x, cy * c - sensor.y);
      farthest = std::max(farthest, r);
      ASSERT_LE(r, config.beam.max_range + 2 * c) << cx << "," << cy;
      if (n > 0) {
        ++positive;
        int nearest = 1 << 30;
        for (const auto& [hx, hy] : hits)
          nearest = std::min(nearest, std::max(std::abs(hx - cx), std::abs(hy - cy)));
        worst_hit_distance = std::max(worst_hit_distance, nearest);
        EXPECT_LE(nearest, 1) << "positive cell " << cx << "," << cy << " far from every hit";
      } else {
        ++negative;
      }
    }
  // (c) every hit has a positive cell within one cell.
  for (const auto& [hx, hy] : hits) {
    bool found = false;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        found = found || map.at(hx + dx + setup.origin_cell_x, hy + dy + setup.origin_cell_y) > 0;
    EXPECT_TRUE(found) << "no occupied cell at the hit " << hx << "," << hy;
  }
  // (d) the line of sight, from 1.5 cells to 2 cells before the hit, is empty, away from the
  // walls (a grazing beam's last cells lie beside the wall, which other beams hit).
  std::size_t sampled = 0;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (!usable(i)) continue;
    const double z = scan.ranges[i];
    const double a = sensor.theta + scan.bearing(i);
    for (double t = 1.5 * c; t < z - 2.0 * c; t += 0.25 * c) {
      const double x = sensor.x + t * std::cos(a), y = sensor.y + t * std::sin(a);
      // Not within 2 mm of a cell boundary: the integer ray may pass on either side.
      const double fx = x / c + 0.5 - std::floor(x / c + 0.5);
      const double fy = y / c + 0.5 - std::floor(y / c + 0.5);
      if (std::min({fx, 1.0 - fx, fy, 1.0 - fy}) * c < 0.002) continue;
      const int cx = cell_of(x, c), cy = cell_of(y, c);
      const Pose2 w = to_world(cx * c, cy * c);
      if (world.clearance(w.x, w.y) < 1.5 * c) continue;
      ++sampled;
      ASSERT_LT(map.at(cx + setup.origin_cell_x, cy + setup.origin_cell_y), 0)
          << "beam " << i << " at " << t << " m";
    }
  }
  EXPECT_GT(sampled, 500u);
  std::printf(
      "[slam] first scan: %d occupied, %d empty cells; worst occupied-to-hit distance %d "
      "cell(s); farthest touched cell %.3f m (max range %.1f m); %zu line-of-sight samples\n",
      positive, negative, worst_hit_distance, farthest, config.beam.max_range, sampled);
}

// The mapping event with a spread Pi: P(o_c) = sum_x w_x P_x(o_c) + (1 - W_c) / 2 over the poses
// x above the cut-off (weights renormalized), P_x the ISM of the scan seen from x, W_c the
// weight of the poses whose ISM reaches c. The oracle maps the same scan from each pose alone
// (a GridSlamEngine driven there by exact odometry, without motion noise) and mixes the indices
// here.
struct MixtureError {
  std::size_t poses = 0, cells = 0, exact = 0, more_confident = 0;
  int worst = 0;
  double mean = 0.0;  // mean |difference| in S_eps steps
};

template <class Pr>
MixtureError mixture_map_error(int ugamma_steps_per_halving) {
  const World world = room_with_pillar();
  GridSlamConfig config = small_config();
  config.ugamma.steps_per_halving = ugamma_steps_per_halving;
  config.motion.xy0 = 0.05;  // half a cell: Pi spreads over the neighbouring cells
  config.motion.theta0 = 0.004;
  Log log;
  log.scans.push_back(make_scan(world, {}, {}, 0.0, 90));
  log.scans.push_back(make_scan(world, {}, {}, 0.1, 90));
  std::vector<QuantizedScan> scans = quantize(log, config);
  std::fill(scans[0].range_mm.begin(), scans[0].range_mm.end(), 0);  // no mapping at scan 0
  const SlamSetup setup = make_slam_setup(config, log.scans[0], 1.0);
  GridSlamEngine<Pr> mixed(setup, make_probabilities<Pr>(setup));
  mixed.process(scans[0]);
  mixed.process(scans[1]);  // motion update (spreads Pi), then mapping with that Pi
  EXPECT_EQ(mixed.mappings(), 1u);
  EXPECT_EQ(mixed.localizations(), 0u);
  MixtureError r;

  // The poses above the cut-off and their weights, in double.
  const Pr& pr = mixed.probabilities();
  struct Weighted {
    SlamPose pose;
    double w;
  };
  std::vector<Weighted> poses;
  double total = 0.0;
  for (std::size_t q = 0; q < mixed.pose_grid().size(); ++q) {
    const auto p = mixed.pose_grid()[q];
    if (pr.below_cutoff(p)) continue;
    double w = 0.0;
    if constexpr (std::is_same_v<Pr, IndexProbabilities>)
      w = pr.u.to_probability(p);
    else
      w = p;
    poses.push_back({mixed.pose_of(q), w});
    total += w;
  }
  r.poses = poses.size();
  if (poses.size() < 9) return r;  // not a real mixture: the caller fails

  // Each pose's own ISM image: one pose reached by exact odometry, mapped alone.
  GridSlamConfig exact = config;
  exact.motion.xy0 = exact.motion.xy_per_m = exact.motion.xy_per_rad = 0.0;
  exact.motion.theta0 = exact.motion.theta_per_m = exact.motion.theta_per_rad = 0.0;
  const SlamSetup exact_setup = make_slam_setup(exact, log.scans[0], 1.0);
  const std::size_t cells = mixed.map().cells.size();
  std::vector<double> occ(cells, 0.0), emp(cells, 0.0), weight(cells, 0.0);
  for (const Weighted& x : poses) {
    GridSlamEngine<DoubleProbabilities> alone(exact_setup,
                                              make_probabilities<DoubleProbabilities>(exact_setup));
    QuantizedScan there = scans[1];
    there.odom_dx_mm = static_cast<std::int32_t>(x.pose.x_mm);
    there.odom_dy_mm = static_cast<std::int32_t>(x.pose.y_mm);
    there.odom_dtheta = static_cast<std::int32_t>(x.pose.theta);
    alone.process(scans[0]);
    alone.process(there);
    const std::size_t at = mode_of(alone);
    EXPECT_EQ(alone.pose_of(at).x_mm, x.pose.x_mm);
    EXPECT_EQ(alone.pose_of(at).y_mm, x.pose.y_mm);
    EXPECT_EQ(alone.pose_of(at).theta, x.pose.theta);
    EXPECT_EQ(alone.pose_grid()[at], 1.0);  // alone indeed
    const double w = x.w / total;
    for (std::size_t c = 0; c < cells; ++c) {
      const int k = alone.map().cells[c];
      if (k == 0) continue;
      occ[c] += w * setup.codec.probability(k);
      emp[c] += w * setup.codec.probability(-k);
      weight[c] += w;
    }
  }
  double total_error = 0.0;
  for (std::size_t c = 0; c < cells; ++c) {
    const int got = mixed.map().cells[c];
    if (weight[c] == 0.0) {
      EXPECT_EQ(got, 0) << "cell " << c << " reached by no pose";
      continue;
    }
    const double rest = 0.5 * (1.0 - weight[c]);
    const int expected =
        setup.codec.quantize_conservative((occ[c] + rest) / (occ[c] + emp[c] + 2.0 * rest));
    ++r.cells;
    r.exact += got == expected;
    r.more_confident += std::abs(got) > std::abs(expected) && (got > 0) == (expected > 0);
    r.worst = std::max(r.worst, std::abs(got - expected));
    total_error += std::abs(got - expected);
  }
  r.mean = r.cells > 0 ? total_error / static_cast<double>(r.cells) : 0.0;
  return r;
}

template <class Pr>
void expect_mixture_map(const char* name, int ugamma_steps_per_halving, int worst, double mean,
                        double exact) {
  const MixtureError r = mixture_map_error<Pr>(ugamma_steps_per_halving);
  std::printf(
      "[slam] mixture map, %s (U_gamma %d steps a halving): %zu poses; %zu cells, %zu exactly "
      "as the oracle, %zu more confident; worst difference %d, mean %.3f S_eps steps\n",
      name, ugamma_steps_per_halving, r.poses, r.cells, r.exact, r.more_confident, r.worst, r.mean);
  ASSERT_GE(r.poses, 9u) << name;  // a real mixture
  EXPECT_GT(r.cells, 1000u);
  EXPECT_LE(r.worst, worst) << name;
  EXPECT_LE(r.mean, mean) << name;
  EXPECT_GE(static_cast<double>(r.exact), exact * static_cast<double>(r.cells)) << name;
}

// Double: the same sums in another order; only a sum landing on a quantization boundary could
// round the other way (measured: none of 3862 cells).
TEST(SlamMapping, MixtureOfPosesIsTheWeightedSumOfTheirIsmsInDouble) {
  expect_mixture_map<DoubleProbabilities>("double", 16, 1, 0.01, 0.99);
}

// U_gamma: one S_eps step (lambda = 0.107 nats here) is only 2.5 steps of the default U_gamma
// (ln 2 / 16 = 0.043 nats), and each probability, weight and addition of the ~15-term sums
// rounds by half a step, so the mixed index is off by one step for about 40% of the cells, by
// two for about 1% (measured: worst 2, mean 0.43). With 128 steps a halving (one S_eps step =
// 20 U_gamma steps) the same code must come within one step and mostly exact: what is left is
// rounding, not a wrong formula.
TEST(SlamMapping, MixtureOfPosesIsTheWeightedSumOfTheirIsmsInInteger) {
  expect_mixture_map<IndexProbabilities>("integer", 16, 3, 0.6, 0.5);
  expect_mixture_map<IndexProbabilities>("integer", 128, 1, 0.1, 0.9);
}

TEST(SlamMapping, ScanWithoutUsableReadingsTouchesNothing) {
  const World world;
  GridSlamConfig config = small_config();
  config.beam.max_range = 1.0;  // every wall is farther
  Log log;
  log.scans.push_back(make_scan(world, {}, {}, 0.0, 36));
  const SlamSetup setup = make_slam_setup(config, log.scans[0], 0.0);
  GridSlamEngine<IndexProbabilities> slam(setup, make_probabilities<IndexProbabilities>(setup));
  slam.process(quantize(log, config)[0]);
  EXPECT_EQ(slam.skipped_scans(), 1u);
  EXPECT_EQ(slam.mappings(), 0u);
  EXPECT_TRUE(std::all_of(slam.map().cells.begin(), slam.map().cells.end(),
                          [](std::int8_t n) { return n == 0; }));
}

TEST(SlamMapping, ProcessRejectsAScanOfAnotherBeamCount) {
  const World world;
  const GridSlamConfig config = small_config();
  const SlamSetup setup = make_slam_setup(config, make_scan(world, {}, {}, 0.0, 36), 0.0);
  GridSlamEngine<DoubleProbabilities> slam(setup, make_probabilities<DoubleProbabilities>(setup));
  QuantizedScan scan;
  scan.range_mm.assign(35, 1000);
  EXPECT_THROW(slam.process(scan), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// 3. Motion update: scans without usable readings only move Pi.

struct MotionTrace {
  std::vector<Pose2> expected;  // the composed odometry, SLAM frame
  std::vector<SlamEstimate> estimates;
  std::vector<double> mass;
};

GridSlamConfig motion_config() {
  GridSlamConfig c = small_config();
  c.motion.xy0 = 0.03;  // a kernel of at least 0.3 cells: its sampled mean is its centre
  c.window.headings = 31;
  return c;
}

// Odometry increments (robot frame) of a curving path.
std::vector<Pose2> motion_increments() {
  std::vector<Pose2> u;
  for (int i = 0; i < 12; ++i)
    u.push_back({0.2 + 0.013 * (i % 5), 0.02 * ((i % 3) - 1), i < 6 ? 0.05 : -0.08});
  return u;
}

template <class Pr>
MotionTrace run_motion_only() {
  const GridSlamConfig config = motion_config();
  Log log;
  Pose2 pose{1.0, 2.0, -0.7};  // the first pose, in the log's frame
  const Pose2 first = pose;
  std::vector<Pose2> poses{pose};
  for (const Pose2& u : motion_increments()) poses.push_back(pose = compose(pose, u));
  for (std::size_t i = 0; i < poses.size(); ++i) {
    Scan s = make_scan(World{}, {}, poses[i], 0.1 * static_cast<double>(i), 36);
    std::fill(s.ranges.begin(), s.ranges.end(), 0.0);
    log.scans.push_back(s);
  }
  const std::vector<QuantizedScan> scans = quantize(log, config);
  const SlamSetup setup = make_slam_setup(config, log.scans[0], 4.0);
  GridSlamEngine<Pr> slam(setup, make_probabilities<Pr>(setup));
  MotionTrace trace;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    slam.process(scans[i]);
    trace.expected.push_back(relative(first, poses[i]));
    trace.estimates.push_back(slam.estimate());
    trace.mass.push_back(mass(slam));
  }
  EXPECT_EQ(slam.skipped_scans(), scans.size());
  EXPECT_EQ(slam.mappings(), 0u);
  EXPECT_EQ(slam.localizations(), 0u);
  EXPECT_TRUE(std::all_of(slam.map().cells.begin(), slam.map().cells.end(),
                          [](std::int8_t n) { return n == 0; }));
  return trace;
}

template <class Pr>
void expect_mean_follows_odometry(const char* name) {
  const MotionTrace t = run_motion_only<Pr>();
  const GridSlamConfig c = motion_config();
  const double bin = 2.0 * kPi / c.headings;
  double worst_xy = 0.0, worst_theta = 0.0, worst_mass = 0.0;
  for (std::size_t i = 0; i < t.estimates.size(); ++i) {
    const Pose2 e = pose_of(t.estimates[i]);
    const double dxy = std::hypot(e.x - t.expected[i].x, e.y - t.expected[i].y);
    const double dth = std::abs(wrap(e.theta - t.expected[i].theta));
    worst_xy = std::max(worst_xy, dxy);
    worst_theta = std::max(worst_theta, dth);
    worst_mass = std::max(worst_mass, std::abs(t.mass[i] - 1.0));
    EXPECT_LE(dxy, 0.5 * c.cell) << name << " step " << i;
    EXPECT_LE(dth, bin) << name << " step " << i;
    if (i > 0) {
      // The spread grows with every motion.
      EXPECT_GT(t.estimates[i].sigma_um, t.estimates[i - 1].sigma_um) << name << " step " << i;
    }
  }
  EXPECT_EQ(t.estimates[0].sigma_um, 0);
  // After 12 steps of ~0.2 m the spread is that of a random walk, some 0.05 m a step: between
  // 0.1 and 0.3 m.
  EXPECT_GT(t.estimates.back().sigma_um, 100000) << name;
  EXPECT_LT(t.estimates.back().sigma_um, 300000) << name;
  if constexpr (std::is_same_v<Pr, DoubleProbabilities>) {
    EXPECT_LE(worst_mass, 1e-12);
  } else {
    // Normalizing divides by the pairwise sum of the grid, exact in U_gamma; that sum rounds
    // by half a step per level of the pairwise tree, so the mass is 1 within gamma^(-+d/2).
    const double steps = 0.5 * pairwise_depth(static_cast<std::size_t>(c.window.cells) *
                                              static_cast<std::size_t>(c.window.cells) *
                                              static_cast<std::size_t>(c.window.headings));
    EXPECT_LE(worst_mass, std::exp2(steps / c.ugamma.steps_per_halving) - 1.0);
  }
  std::printf(
      "[slam] motion only, %s: worst mean error %.4f m (bound %.3f), %.5f rad (bound %.5f); "
      "final sigma %.4f m; worst |mass - 1| %.3g\n",
      name, worst_xy, 0.5 * c.cell, worst_theta, bin,
      static_cast<double>(t.estimates.back().sigma_um) * 1e-6, worst_mass);
}

TEST(SlamMotion, MeanFollowsTheComposedOdometryInDouble) {
  expect_mean_follows_odometry<DoubleProbabilities>("double");
}

TEST(SlamMotion, MeanFollowsTheComposedOdometryInInteger) {
  expect_mean_follows_odometry<IndexProbabilities>("integer");
}

TEST(SlamMotion, IntegerAndDoubleMeansAgree) {
  const MotionTrace d = run_motion_only<DoubleProbabilities>();
  const MotionTrace n = run_motion_only<IndexProbabilities>();
  ASSERT_EQ(d.estimates.size(), n.estimates.size());
  double worst_xy = 0.0, worst_theta = 0.0, worst_sigma = 0.0;
  for (std::size_t i = 0; i < d.estimates.size(); ++i) {
    const Pose2 a = pose_of(d.estimates[i]), b = pose_of(n.estimates[i]);
    worst_xy = std::max(worst_xy, std::hypot(a.x - b.x, a.y - b.y));
    worst_theta = std::max(worst_theta, std::abs(a.theta - b.theta));
    if (i > 0)
      worst_sigma =
          std::max(worst_sigma, std::abs(static_cast<double>(n.estimates[i].sigma_um) /
                                             static_cast<double>(d.estimates[i].sigma_um) -
                                         1.0));
  }
  EXPECT_LE(worst_xy, 0.01);
  EXPECT_LE(worst_theta, 0.002);
  EXPECT_LE(worst_sigma, 0.05);
  std::printf(
      "[slam] motion only, integer vs double: worst mean gap %.5f m, %.6f rad, sigma %.2f%%\n",
      worst_xy, worst_theta, 100.0 * worst_sigma);
}

TEST(SlamMotion, WindowReachingTheMapEdgeThrows) {
  GridSlamConfig config = small_config();
  config.beam.max_range = 1.0;
  config.map.margin = 1.0;
  const SlamSetup setup = make_slam_setup(config, make_scan(World{}, {}, {}, 0.0, 36), 0.0);
  GridSlamEngine<DoubleProbabilities> slam(setup, make_probabilities<DoubleProbabilities>(setup));
  QuantizedScan scan;
  scan.range_mm.assign(36, 0);
  ASSERT_NO_THROW(slam.process(scan));
  scan.odom_dx_mm = 500;
  try {
    for (int i = 0; i < 100; ++i) slam.process(scan);
    ADD_FAILURE() << "drove off the map without an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("edge of the map"), std::string::npos) << e.what();
  }
}

// make_slam_setup's contract: a map for a run whose odometry stays within reach_m of the first
// pose, plus max_range, plus map_margin. With no margin the run must still fit while the
// robot stays within that reach.
TEST(SlamMotion, RunWithinTheAnnouncedReachFitsTheMapWithoutMargin) {
  for (const double max_range : {1.0, 10.0}) {
    GridSlamConfig config = small_config();
    config.beam.max_range = max_range;
    config.map.margin = 0.0;
    const double reach = 2.0;
    const SlamSetup setup = make_slam_setup(config, make_scan(World{}, {}, {}, 0.0, 36), reach);
    GridSlamEngine<DoubleProbabilities> slam(setup, make_probabilities<DoubleProbabilities>(setup));
    QuantizedScan scan;
    scan.range_mm.assign(36, 0);
    int done = 0;
    try {
      for (; done <= 10; ++done) {
        slam.process(scan);
        scan.odom_dx_mm = 200;  // ten steps of 0.2 m: exactly the reach
      }
    } catch (const std::runtime_error& e) {
      ADD_FAILURE() << "max range " << max_range << ": threw at step " << done << " of 10, "
                    << static_cast<double>(slam.estimate().x_um) * 1e-6
                    << " m from the start (reach " << reach << " m; map " << setup.origin_cell_x
                    << " cells each side): " << e.what();
    }
  }
}

// The integer estimate of a broad pose grid: weights up to 2^20 times sums of squared window
// indices, over a large window, in 64 bits. The double estimate is the oracle.
TEST(SlamMotion, IntegerEstimateOfABroadPoseGridOnALargeWindow) {
  struct Window {
    int cells, headings;
  };
  for (const Window w : {Window{161, 1}, Window{61, 61}}) {
    GridSlamConfig config = small_config();
    config.window.cells = w.cells;
    config.window.headings = w.headings;
    config.motion.xy0 = 5.0;  // one update spreads Pi nearly evenly over the window
    config.motion.theta0 = 2.0;
    config.beam.max_range = 1.0;
    config.map.margin = 10.0;
    const SlamSetup setup = make_slam_setup(config, make_scan(World{}, {}, {}, 0.0, 36), 0.0);
    GridSlamEngine<DoubleProbabilities> d(setup, make_probabilities<DoubleProbabilities>(setup));
    GridSlamEngine<IndexProbabilities> n(setup, make_probabilities<IndexProbabilities>(setup));
    QuantizedScan scan;
    scan.range_mm.assign(36, 0);
    for (int i = 0; i < 2; ++i) {  // the second scan's motion update
      d.process(scan);
      n.process(scan);
    }
    const double sd = static_cast<double>(d.estimate().sigma_um) * 1e-6;
    const double sn = static_cast<double>(n.estimate().sigma_um) * 1e-6;
    std::printf(
        "[slam] broad pose grid, %d cells x %d headings: sigma double %.4f m, integer %.4f m\n",
        w.cells, w.headings, sd, sn);
    EXPECT_GT(sd, 1.0) << w.cells;
    EXPECT_NEAR(sn, sd, 0.05 * sd) << w.cells << " x " << w.headings;
    EXPECT_NEAR(static_cast<double>(n.estimate().x_um) * 1e-6,
                static_cast<double>(d.estimate().x_um) * 1e-6, 0.05);
    EXPECT_NEAR(static_cast<double>(n.estimate().y_um) * 1e-6,
                static_cast<double>(d.estimate().y_um) * 1e-6, 0.05);
    EXPECT_NEAR(static_cast<double>(n.estimate().theta_q8) / 256.0 * kUnit,
                static_cast<double>(d.estimate().theta_q8) / 256.0 * kUnit, 0.01);
  }
}

// ---------------------------------------------------------------------------------------------
// 4. Localization: map from the origin, then read from a displaced pose with "no motion".
//
// The map is one scan's: its cells are known only along that scan's rays, and a ray of another
// pose that runs through unknown cells (P = 1/2 each) is improbable. With 90 beams (4 degrees
// apart) such a map holds the posterior at the mapped pose whatever the truth (measured: the
// estimate did not move at all, for every displacement below); with 360 beams (1 degree, 5 cm
// apart at 3 m) the walls and the free space are dense enough to localize against.

GridSlamConfig localization_config() {
  GridSlamConfig c = small_config();
  // Pi spreads over the neighbouring cells and headings on a still update.
  c.motion.xy0 = 0.05;
  c.motion.theta0 = 0.02;
  // One scan of a simulated room, whose readings are independent given the map: weighed as such,
  // not with the real log's tempering (GridSlamConfig::tempering).
  c.beam.tempering = 1;
  return c;
}

struct Localized {
  Pose2 estimate;
  SlamPose mode, window;  // the mode's pose and the window's origin (element 0)
  std::size_t localizations = 0;
};

// The room mapped from one pose, then read from the pose displaced by `displacement` while the
// odometry says the robot did not move: the SLAM after those two scans.
template <class Pr>
GridSlamEngine<Pr> map_then_localize(const GridSlamConfig& config, const Pose2& displacement) {
  const World world = room_with_pillar();
  const Pose2 robot{-0.4, 0.3, 0.2};
  const Pose2 truth = compose(robot, displacement);
  Log log;
  log.scans.push_back(make_scan(world, robot, robot, 0.0, 360));
  log.scans.push_back(make_scan(world, truth, robot, 0.1, 360));  // odometry: no motion
  const std::vector<QuantizedScan> scans = quantize(log, config);
  EXPECT_EQ(scans[1].odom_dx_mm, 0);
  EXPECT_EQ(scans[1].odom_dy_mm, 0);
  EXPECT_EQ(scans[1].odom_dtheta, 0);
  const SlamSetup setup = make_slam_setup(config, log.scans[0], 0.0);
  GridSlamEngine<Pr> slam(setup, make_probabilities<Pr>(setup));
  slam.process(scans[0]);
  slam.process(scans[1]);
  return slam;
}

template <class Pr>
Localized localize_once(const Pose2& displacement) {
  const GridSlamEngine<Pr> slam = map_then_localize<Pr>(localization_config(), displacement);
  Localized r;
  r.estimate = pose_of(slam.estimate());
  r.mode = slam.pose_of(mode_of(slam));
  r.window = slam.pose_of(0);
  r.localizations = slam.localizations();
  return r;
}

template <class Pr>
void expect_localization_moves_toward_the_truth(const char* name) {
  const GridSlamConfig config = localization_config();
  const int n = config.window.cells, nt = config.window.headings;
  const double c = config.cell, bin = 2.0 * kPi / config.headings;
  const double unit = 2.0 * kPi / kAngleUnitsPerTurn;  // radians per angle unit
  const long cell_mm = std::lround(c * 1000.0);
  for (const Pose2& truth :
       {Pose2{0.04, -0.03, 0.0175}, Pose2{0.09, -0.04, 0.0175}, Pose2{-0.08, 0.09, -0.012},
        Pose2{0.0, 0.1, 0.0}, Pose2{0.0, 0.0, 0.02}, Pose2{-0.11, -0.07, -0.015}}) {
    const Localized r = localize_once<Pr>(truth);
    EXPECT_EQ(r.localizations, 1u);
    const double before_xy = std::hypot(truth.x, truth.y), before_theta = std::abs(truth.theta);
    const double after_xy = std::hypot(r.estimate.x - truth.x, r.estimate.y - truth.y);
    const double after_theta = std::abs(r.estimate.theta - truth.theta);
    // The estimate comes closer to the truth (or, with the truth at the centre, stays within
    // 1 cm of it).
    if (before_xy > 0.0)
      EXPECT_LT(after_xy, before_xy) << name << " " << truth.x << "," << truth.y;
    else
      EXPECT_LT(after_xy, 0.01) << name;
    if (before_theta > 0.0)
      EXPECT_LT(after_theta, before_theta) << name << " " << truth.theta;
    else
      EXPECT_LT(after_theta, bin) << name;
    // The mode is the grid pose nearest the truth: its cell, and its heading within one bin.
    EXPECT_EQ(r.mode.x_mm, std::lround(truth.x / c) * cell_mm) << name << " " << truth.x;
    EXPECT_EQ(r.mode.y_mm, std::lround(truth.y / c) * cell_mm) << name << " " << truth.y;
    EXPECT_LE(std::abs(static_cast<double>(r.mode.theta) * unit - truth.theta), 1.5 * bin)
        << name << " " << truth.theta;
    std::printf(
        "[slam] localization, %s: truth (%.3f, %.3f, %.4f): position error %.4f -> %.4f m, "
        "heading error %.4f -> %.4f rad; mode (%lld mm, %lld mm, %lld units)\n",
        name, truth.x, truth.y, truth.theta, before_xy, after_xy, before_theta, after_theta,
        static_cast<long long>(r.mode.x_mm), static_cast<long long>(r.mode.y_mm),
        static_cast<long long>(r.mode.theta));
  }
  // Read from the mapped pose itself: the mode stays at the centre of an unmoved window.
  const Localized still = localize_once<Pr>({});
  EXPECT_EQ(still.mode.x_mm, 0) << name;
  EXPECT_EQ(still.mode.y_mm, 0) << name;
  EXPECT_EQ(still.mode.theta, 0) << name;
  EXPECT_EQ(still.window.x_mm, -(n / 2) * cell_mm);
  EXPECT_EQ(still.window.y_mm, -(n / 2) * cell_mm);
  EXPECT_EQ(still.window.theta, -(nt / 2) * (kAngleUnitsPerTurn / config.headings));
  EXPECT_LT(std::hypot(still.estimate.x, still.estimate.y), 0.01) << name;
  EXPECT_LT(std::abs(still.estimate.theta), 0.5 * bin) << name;
  std::printf("[slam] localization, %s, still: estimate (%.4f, %.4f, %.5f)\n", name,
              still.estimate.x, still.estimate.y, still.estimate.theta);
}

TEST(SlamLocalization, EstimateMovesTowardTheTruePoseInDouble) {
  expect_localization_moves_toward_the_truth<DoubleProbabilities>("double");
}

TEST(SlamLocalization, EstimateMovesTowardTheTruePoseInInteger) {
  expect_localization_moves_toward_the_truth<IndexProbabilities>("integer");
}

// A scan's joint likelihood, raised to 1 / tempering, against the log-domain oracle
// exp(sum ln p / k): 2000 beams of 1e-3 to 1 pass far below the smallest double (1e-308) and the
// smallest 16-bit U_gamma index (2^-2048), which a running product of them would reach and keep.
template <class Pr>
void expect_joint_likelihood_survives_underflow(const char* name) {
  const GridSlamConfig config = small_config();
  const Log log = [] {
    Log l;
    l.scans.push_back(make_scan(room_with_pillar(), {}, {}, 0.0, 90));
    return l;
  }();
  const SlamSetup setup = make_slam_setup(config, log.scans[0], 0.0);
  const Pr pr = make_probabilities<Pr>(setup);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-3.0, 0.0);  // log10 p
  typename Pr::Joint joint;
  double log_sum = 0.0;
  for (int beam = 0; beam < 2000; ++beam) {
    const double p = std::pow(10.0, uniform(random));
    if constexpr (std::is_same_v<Pr, IndexProbabilities>) {
      const UIndex i = pr.u.from_probability(p);
      pr.multiply_into(joint, i);
      log_sum += pr.u.to_log(i);  // the index's own value: the oracle sums what was added
    } else {
      pr.multiply_into(joint, p);
      log_sum += std::log(p);
    }
  }
  ASSERT_LT(log_sum, -2000.0) << name;  // below both arithmetics' smallest probability
  for (const int k : {12, 20, 40}) {    // roots a double holds: ln of its smallest is -744
    const typename Pr::P root = pr.root_of(joint, k);
    ASSERT_FALSE(pr.is_zero(root)) << name << " k " << k;
    if constexpr (std::is_same_v<Pr, IndexProbabilities>)
      // Truncating the index sum by k: at most one step, ln(1/gamma).
      EXPECT_NEAR(pr.u.to_log(root), log_sum / k, std::log(2.0) / 16.0 + 1e-9)
          << name << " k " << k;
    else
      EXPECT_NEAR(std::log(root), log_sum / k, 1e-9 * std::abs(log_sum)) << name << " k " << k;
  }
}

TEST(SlamLocalization, JointLikelihoodOfManyBeamsSurvivesUnderflowInDouble) {
  expect_joint_likelihood_survives_underflow<DoubleProbabilities>("double");
}

TEST(SlamLocalization, JointLikelihoodOfManyBeamsSurvivesUnderflowInInteger) {
  expect_joint_likelihood_survives_underflow<IndexProbabilities>("integer");
}

// A localization drops the poses it leaves below pose_prune, and only those: the same scans
// without pruning give the same grid on every kept pose (bit for bit) and something below the
// threshold on every dropped one.
template <class Pr>
void expect_localization_prunes_only_negligible_poses(const char* name) {
  GridSlamConfig pruned = localization_config();
  pruned.window.pose_prune = 1e-6;
  GridSlamConfig kept = pruned;
  kept.window.pose_prune = 0.0;
  const Pose2 displacement{0.04, -0.03, 0.0175};
  const GridSlamEngine<Pr> with = map_then_localize<Pr>(pruned, displacement),
                           without = map_then_localize<Pr>(kept, displacement);
  ASSERT_EQ(with.localizations(), 1u);
  std::size_t dropped = 0;
  for (std::size_t q = 0; q < with.pose_grid().size(); ++q) {
    const double p = probability_of(without, without.pose_grid()[q]);
    if (with.probabilities().is_zero(with.pose_grid()[q])) {
      dropped += p > 0.0;
      EXPECT_LT(p, 1e-6) << name << " pose " << q;
    } else {
      EXPECT_EQ(with.pose_grid()[q], without.pose_grid()[q]) << name << " pose " << q;
    }
  }
  EXPECT_GT(dropped, 0u) << name;
}

TEST(SlamLocalization, PruningDropsOnlyPosesBelowTheThresholdInDouble) {
  expect_localization_prunes_only_negligible_poses<DoubleProbabilities>("double");
}

TEST(SlamLocalization, PruningDropsOnlyPosesBelowTheThresholdInInteger) {
  expect_localization_prunes_only_negligible_poses<IndexProbabilities>("integer");
}

// ---------------------------------------------------------------------------------------------
// 5, 6. A loop in the room, with a biased and noisy odometry.

struct LoopLog {
  Log log;
  std::vector<TimedPose> truth;
};

LoopLog make_loop_log() {
  const World world = room_with_pillar();
  LoopLog out;
  Jitter jitter(20240611);
  const int scans = 40;
  const double radius = 1.2;
  Pose2 odom;
  Pose2 previous_truth;
  for (int i = 0; i < scans; ++i) {
    const double phi = 2.0 * kPi * i / scans;
    const Pose2 truth{radius * std::cos(phi), radius * std::sin(phi), phi + kPi / 2};
    if (i == 0) {
      odom = truth;
    } else {
      // The odometry's increment: 4% too long, 0.01 rad a step too far left, and noise.
      Pose2 u = relative(previous_truth, truth);
      u.x = u.x * 1.04 + 0.005 * jitter();
      u.y += 0.005 * jitter();
      u.theta += 0.01 + 0.004 * jitter();
      odom = compose(odom, u);
    }
    previous_truth = truth;
    const double t = 1000.0 + 0.2 * i;
    out.log.scans.push_back(
        make_scan(world, truth, odom, t, 90, [&](int) { return 0.01 * jitter(); }));
    out.truth.push_back({t, truth});
  }
  return out;
}

const LoopLog& loop_log() {
  static const LoopLog log = make_loop_log();
  return log;
}

GridSlamConfig loop_config() {
  return small_config();
}

const SlamRun& loop_run(Arithmetic arithmetic) {
  static const SlamRun integer = run_grid_slam(loop_log().log, loop_config(), Arithmetic::integer);
  static const SlamRun floating =
      run_grid_slam(loop_log().log, loop_config(), Arithmetic::floating);
  return arithmetic == Arithmetic::integer ? integer : floating;
}

TEST(SlamLoop, BothArithmeticsTrackTheLoopFarBetterThanOdometry) {
  const LoopLog& l = loop_log();
  const TrajectoryError odom = absolute_trajectory_error(scan_poses(l.log), l.truth);
  for (const Arithmetic a : {Arithmetic::floating, Arithmetic::integer}) {
    const SlamRun& run = loop_run(a);
    const char* name = a == Arithmetic::integer ? "integer" : "double";
    ASSERT_EQ(run.trajectory.size(), l.log.scans.size());
    EXPECT_EQ(run.scans, 40u);
    EXPECT_EQ(run.mappings, 40u);
    EXPECT_EQ(run.localizations, 39u);
    EXPECT_EQ(run.skipped_scans, 0u);
    EXPECT_EQ(run.readings, 40u * 90u);
    EXPECT_EQ(run.unusable_readings, 0u);
    const TrajectoryError e = absolute_trajectory_error(run.trajectory, l.truth);
    EXPECT_EQ(e.matched, 40u);
    // Pi's hypotheses sit at cell centres and the posterior is nearly one cell, so the error is
    // that of rounding the position to a cell: uniform over a cell, RMS c / sqrt(6) = 0.041 m,
    // at most c / sqrt(2) = 0.071 m (measured: 0.0395 and 0.054 m, both arithmetics).
    const double c = loop_config().cell;
    EXPECT_LT(e.rmse, 1.5 * c / std::sqrt(6.0)) << name;
    EXPECT_LT(e.max, c / std::sqrt(2.0) + 0.01) << name;
    EXPECT_LT(e.mean_heading, 0.03) << name;
    EXPECT_LT(e.rmse, 0.25 * odom.rmse) << name;
    EXPECT_GT(run.mean_sigma(), 0.0);
    EXPECT_LT(run.mean_sigma(), 0.1);
    std::printf(
        "[slam] loop, %s: ATE rmse %.4f m, max %.4f m, mean heading error %.4f rad, E(sigma) "
        "%.4f m; odometry ATE rmse %.4f m, max %.4f m, heading %.4f rad\n",
        name, e.rmse, e.max, e.mean_heading, run.mean_sigma(), odom.rmse, odom.max,
        odom.mean_heading);
  }
  ASSERT_GT(odom.rmse, 0.2);  // the test would not show anything with a good odometry
}

TEST(SlamLoop, IntegerAndDoubleTrajectoriesAgree) {
  const SlamRun& d = loop_run(Arithmetic::floating);
  const SlamRun& n = loop_run(Arithmetic::integer);
  const TrajectoryError gap = absolute_trajectory_error(n.trajectory, d.trajectory);
  EXPECT_LT(gap.rmse, 0.05);
  EXPECT_LT(gap.mean_heading, 0.02);
  // The maps agree on most cells' sign.
  ASSERT_EQ(d.map.cells.size(), n.map.cells.size());
  std::size_t touched = 0, agree = 0;
  for (std::size_t i = 0; i < d.map.cells.size(); ++i) {
    if (d.map.cells[i] == 0 && n.map.cells[i] == 0) continue;
    ++touched;
    agree += (d.map.cells[i] > 0) == (n.map.cells[i] > 0);
  }
  EXPECT_GT(static_cast<double>(agree), 0.95 * static_cast<double>(touched));
  std::printf(
      "[slam] loop, integer vs double: trajectory gap rmse %.4f m, max %.4f m, heading %.4f "
      "rad; map sign agreement %.2f%% of %zu cells\n",
      gap.rmse, gap.max, gap.mean_heading,
      100.0 * static_cast<double>(agree) / static_cast<double>(touched), touched);
}

TEST(SlamLoop, MapShowsTheWallsAndTheFreeSpaceInTheLogFrame) {
  const World world = room_with_pillar();
  for (const Arithmetic a : {Arithmetic::floating, Arithmetic::integer}) {
    const char* name = a == Arithmetic::integer ? "integer" : "double";
    const ProbabilityGrid map = slam_map_probabilities(loop_run(a));
    const GridGeometry& g = map.geometry;
    const double c = g.resolution;
    const auto p = [&](double x, double y) {
      const int ix = g.cell_x(x), iy = g.cell_y(y);
      return g.contains(ix, iy) ? map.at(ix, iy) : 0.5;
    };
    // Along every wall, some cell within one cell of it is occupied.
    std::size_t wall_points = 0, wall_hits = 0;
    const auto on_wall = [&](double x, double y) {
      double best = 0.0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) best = std::max(best, p(x + dx * c, y + dy * c));
      ++wall_points;
      wall_hits += best > 0.5;
    };
    for (double s = -2.7; s <= 2.7; s += 0.1) {
      on_wall(s, -3.0);
      on_wall(s, 3.0);
      on_wall(-3.0, s);
      on_wall(3.0, s);
    }
    // Free space: more than 3 cells from every surface, inside the room.
    std::size_t free_points = 0, free_hits = 0, outside_points = 0, outside_unknown = 0;
    for (double y = -2.95; y < 3.0; y += 0.1)
      for (double x = -2.95; x < 3.0; x += 0.1) {
        if (world.clearance(x, y) <= 3 * c) continue;
        bool in_pillar = false;
        for (const Box& b : world.pillars)
          in_pillar = in_pillar || (x > b.x0 && x < b.x1 && y > b.y0 && y < b.y1);
        if (in_pillar) continue;
        ++free_points;
        free_hits += p(x, y) < 0.5;
      }
    // Outside the room, more than 3 cells from it: never seen.
    for (double y = -4.0; y <= 4.0; y += 0.1)
      for (double x = -4.0; x <= 4.0; x += 0.1) {
        if (world.inside_room(x, y, 3 * c)) continue;
        ++outside_points;
        outside_unknown += p(x, y) == 0.5;
      }
    EXPECT_GT(static_cast<double>(wall_hits), 0.97 * static_cast<double>(wall_points)) << name;
    EXPECT_GT(static_cast<double>(free_hits), 0.97 * static_cast<double>(free_points)) << name;
    EXPECT_EQ(outside_unknown, outside_points) << name;
    std::printf(
        "[slam] loop map, %s: walls occupied at %zu/%zu points, free space empty at %zu/%zu, "
        "outside unknown at %zu/%zu\n",
        name, wall_hits, wall_points, free_hits, free_points, outside_unknown, outside_points);
  }
}

TEST(SlamLoop, RunsAreBitIdentical) {
  for (const Arithmetic a : {Arithmetic::floating, Arithmetic::integer}) {
    const SlamRun& first = loop_run(a);
    const SlamRun again = run_grid_slam(loop_log().log, loop_config(), a);
    ASSERT_EQ(again.trajectory.size(), first.trajectory.size());
    for (std::size_t i = 0; i < first.trajectory.size(); ++i) {
      // Bit-identical doubles: compare with ==, no tolerance.
      EXPECT_EQ(again.trajectory[i].t, first.trajectory[i].t);
      EXPECT_EQ(again.trajectory[i].pose.x, first.trajectory[i].pose.x) << i;
      EXPECT_EQ(again.trajectory[i].pose.y, first.trajectory[i].pose.y) << i;
      EXPECT_EQ(again.trajectory[i].pose.theta, first.trajectory[i].pose.theta) << i;
      EXPECT_EQ(again.sigma[i], first.sigma[i]) << i;
    }
    EXPECT_EQ(again.map.cells, first.map.cells);
    EXPECT_EQ(again.map.geometry.width, first.map.geometry.width);
    EXPECT_EQ(again.map.geometry.origin_x, first.map.geometry.origin_x);
  }
}

// ---------------------------------------------------------------------------------------------
// 7. Logs: checks, quantization, the schedule.

Log small_log(int scans, int beams = 36) {
  Log log;
  for (int i = 0; i < scans; ++i) {
    const Pose2 pose{0.05 * i, 0.0, 0.01 * i};
    log.scans.push_back(make_scan(World{}, pose, pose, 10.0 + 0.1 * i, beams));
  }
  return log;
}

std::string log_error(const Log& log) {
  try {
    check_slam_log(log);
    check_one_sensor_geometry(log);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SlamLog, CheckRejectsWhatSlamCannotUse) {
  EXPECT_NE(log_error(Log{}), "");
  EXPECT_EQ(log_error(small_log(1)), "");  // one scan, no motion needed
  EXPECT_EQ(log_error(small_log(5)), "");

  Log still = small_log(4);
  for (Scan& s : still.scans) s.robot = still.scans[0].robot;
  EXPECT_NE(log_error(still).find("odometry"), std::string::npos) << log_error(still);
  still.odometry.push_back({10.0, {}});  // an ODOM record makes it usable
  EXPECT_EQ(log_error(still), "");

  Log beams = small_log(5);
  beams.scans[2].ranges.pop_back();
  const std::string m = log_error(beams);
  EXPECT_NE(m.find("scan 3"), std::string::npos) << m;
  EXPECT_NE(m.find("beam count"), std::string::npos) << m;

  Log mount = small_log(5);
  mount.scans[3].sensor_mount.x += 0.01;
  EXPECT_NE(log_error(mount).find("scan 4"), std::string::npos) << log_error(mount);

  Log bearing = small_log(5);
  bearing.scans[1].dangle *= 1.001;
  EXPECT_NE(log_error(bearing).find("scan 2"), std::string::npos) << log_error(bearing);

  EXPECT_THROW(run_grid_slam(beams, small_config(), Arithmetic::integer), std::invalid_argument);
}

TEST(SlamLog, QuantizationCountsAndZeroesUnusableReadings) {
  Log log = small_log(3, 10);
  GridSlamConfig config = small_config();
  config.beam.max_range = 5.0;
  std::vector<double>& r = log.scans[1].ranges;
  r = {0.0,    std::numeric_limits<double>::quiet_NaN(),
       -1.0,   std::numeric_limits<double>::infinity(),
       5.0,   // at the configured max range
       25.0,  // past the sensor's
       1.2344, 4.9994,
       0.0004, 2.0};
  SlamRun counts;
  const std::vector<QuantizedScan> q = quantize_scans(log, config, counts);
  ASSERT_EQ(q.size(), 3u);
  EXPECT_EQ(counts.readings, 30u);
  // Scan 1: seven unusable (0, NaN, -1, inf, 5.0, 25, 0.0004 rounding to 0 mm).
  EXPECT_EQ(counts.unusable_readings, 7u);
  EXPECT_EQ(q[1].range_mm, (std::vector<std::int32_t>{0, 0, 0, 0, 0, 0, 1234, 4999, 0, 2000}));
  // Odometry increments: the relative pose of consecutive scans, in mm and angle units.
  EXPECT_EQ(q[0].odom_dx_mm, 0);
  const Pose2 u = relative(log.scans[0].robot, log.scans[1].robot);
  EXPECT_EQ(q[1].odom_dx_mm, std::lround(u.x * 1000.0));
  EXPECT_EQ(q[1].odom_dy_mm, std::lround(u.y * 1000.0));
  EXPECT_EQ(q[1].odom_dtheta, std::lround(u.theta / kUnit));
  EXPECT_EQ(q[1].odom_dtheta, 104);  // 0.01 rad
}

TEST(SlamLog, ScheduleAndScansWithoutReadings) {
  // 360 beams: see SlamLocalization on sparse scans. Steps of half a cell, exact odometry.
  Log log = small_log(10, 360);
  for (double& r : log.scans[4].ranges) r = std::numeric_limits<double>::quiet_NaN();
  GridSlamConfig config = small_config();
  config.schedule.lambda = 2;
  config.schedule.xi = 3;
  for (const Arithmetic a : {Arithmetic::floating, Arithmetic::integer}) {
    const SlamRun run = run_grid_slam(log, config, a);
    EXPECT_EQ(run.scans, 10u);
    EXPECT_EQ(run.trajectory.size(), 10u);
    EXPECT_EQ(run.skipped_scans, 1u);
    EXPECT_EQ(run.unusable_readings, 360u);
    // Mapping at scans 0, 3, 6, 9; localization at the even scans after the first mapping,
    // but not at the skipped scan 4: 2, 6, 8.
    EXPECT_EQ(run.mappings, 4u);
    EXPECT_EQ(run.localizations, 3u);
    // The run continued, and tracked: the last estimate is within half a cell of the last
    // (exact) odometry pose (measured: 0.45 m of 0.45 m in both arithmetics).
    const Pose2& last = run.trajectory.back().pose;
    EXPECT_NEAR(last.x, log.scans.back().robot.x, 0.05);
    EXPECT_NEAR(last.y, log.scans.back().robot.y, 0.05);
    EXPECT_EQ(run.trajectory[4].t, log.scans[4].t);
  }
}

// ---------------------------------------------------------------------------------------------
// 8. Absolute trajectory error.

TEST(TrajectoryError, HandComputedExample) {
  const std::vector<TimedPose> estimate = {
      {1.0000, {0.0, 0.0, 0.1}},
      {2.0004, {3.0, 4.0, 3.0}},  // matches 2.0 within 1 ms
      {2.9980, {9.0, 9.0, 0.0}},  // 2 ms before 3.0: no match
  };
  const std::vector<TimedPose> reference = {
      {1.0, {0.0, 1.0, 0.0}},
      {2.0, {0.0, 0.0, -3.0}},
      {3.0, {0.0, 0.0, 0.0}},
  };
  const TrajectoryError e = absolute_trajectory_error(estimate, reference);
  EXPECT_EQ(e.matched, 2u);
  // Errors 1 and 5: rmse sqrt((1 + 25) / 2) = sqrt(13), max 5.
  EXPECT_NEAR(e.rmse, std::sqrt(13.0), 1e-12);
  EXPECT_DOUBLE_EQ(e.max, 5.0);
  // Headings: 0.1, and 3 - (-3) = 6 wraps to 2 pi - 6.
  EXPECT_NEAR(e.mean_heading, (0.1 + (2.0 * kPi - 6.0)) / 2.0, 1e-12);

  const std::vector<TimedPose> late = {{5.0, {}}};
  EXPECT_THROW(absolute_trajectory_error(late, reference), std::invalid_argument);
  EXPECT_THROW(absolute_trajectory_error(estimate, std::span<const TimedPose>{}),
               std::invalid_argument);
}

TEST(TrajectoryError, ScanPosesAreTheLogsRobotPoses) {
  const Log log = small_log(3);
  const std::vector<TimedPose> p = scan_poses(log);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[2].t, log.scans[2].t);
  EXPECT_EQ(p[2].pose.x, log.scans[2].robot.x);
  const TrajectoryError e = absolute_trajectory_error(p, p);
  EXPECT_EQ(e.rmse, 0.0);
  EXPECT_EQ(e.matched, 3u);
}

// GridSlam, scan by scan in SI units, against the per-scan path driven by hand: GridSlamEngine over
// quantize_scans' integer inputs, its estimate composed with the first pose.
template <class Pr>
void expect_grid_slam_is_the_per_scan_path(Arithmetic arithmetic) {
  const Log& log = loop_log().log;
  const GridSlamConfig config = loop_config();
  const Pose2 first = log.scans.front().robot;
  const double reach = odometry_reach(log.scans);
  const SlamSetup setup = make_slam_setup(config, log.scans.front(), reach);
  GridSlamEngine<Pr> by_hand(setup, make_probabilities<Pr>(setup));
  GridSlam online(config, arithmetic, log.scans.front(), reach);
  const std::vector<QuantizedScan> scans = quantize(log, config);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    by_hand.process(scans[i]);
    online.insert(log.scans[i]);
    const Pose2 expected = compose(first, pose_of(by_hand.estimate()));
    const Pose2 got = online.pose();
    ASSERT_EQ(got.x, expected.x) << "scan " << i;
    ASSERT_EQ(got.y, expected.y) << "scan " << i;
    ASSERT_EQ(got.theta, wrap_angle(expected.theta)) << "scan " << i;
    ASSERT_EQ(online.sigma(), static_cast<double>(by_hand.estimate().sigma_um) * 1e-6);
  }
  EXPECT_EQ(online.map().cells, by_hand.map().cells);
  EXPECT_EQ(online.scans(), log.scans.size());
  EXPECT_EQ(online.localizations(), by_hand.localizations());
  EXPECT_EQ(online.mappings(), by_hand.mappings());
  // The whole-log run is the same scans through GridSlam.
  const SlamRun& run = loop_run(arithmetic);
  EXPECT_EQ(run.trajectory.back().pose.x, online.pose().x);
  EXPECT_EQ(run.map.cells, online.map().cells);
}

TEST(GridSlam, IsThePerScanPathInInteger) {
  expect_grid_slam_is_the_per_scan_path<IndexProbabilities>(Arithmetic::integer);
}

TEST(GridSlam, IsThePerScanPathInDouble) {
  expect_grid_slam_is_the_per_scan_path<DoubleProbabilities>(Arithmetic::floating);
}

TEST(GridSlam, RefusesAScanOfAnotherGeometryNamingIt) {
  const Log& log = loop_log().log;
  GridSlam slam(loop_config(), Arithmetic::integer, log.scans.front(), 5.0);
  slam.insert(log.scans[0]);
  Scan other = log.scans[1];
  other.sensor_mount.x += 0.01;
  try {
    slam.insert(other);
    FAIL() << "accepted another sensor mount";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scan 2 (t = 1000.200000) has another sensor mount"),
              std::string::npos)
        << e.what();
  }
  Scan far = log.scans[1];
  far.robot.x += 2000.0;
  EXPECT_THROW(slam.insert(far), std::invalid_argument);
}

}  // namespace
}  // namespace intgrid
