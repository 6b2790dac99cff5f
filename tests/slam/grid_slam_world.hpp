// What the grid SLAM's tests share (tests/slam/grid_slam_*_test.cpp, slam_test.cpp): a
// synthetic world whose ranges come from an analytic ray-box intersection, and readings of the
// SLAM's state.
//
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
#pragma once

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

namespace intgrid::grid_slam_test {

using namespace intgrid::core;
using namespace intgrid::slam;

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kUnit = 2.0 * kPi / kAngleUnitsPerTurn;  // radians per angle unit

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

inline World room_with_pillar() {
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

inline Scan make_scan(const World& world, const Pose2& truth, const Pose2& odom, double t,
                      int beams) {
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

inline double wrap(double a) {
  return std::remainder(a, 2.0 * kPi);
}

inline GridSlamConfig small_config() {
  GridSlamConfig c;
  c.sensor.max_range = 10.0;
  c.map.margin = 2.0;
  return c;
}

// Every scan of the log as the per-scan path's input, through the public quantization.
inline std::vector<QuantizedScan> quantize(const Log& log, const GridSlamConfig& config) {
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
inline int pairwise_depth(std::size_t n) {
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
inline Pose2 pose_of(const SlamEstimate& e) {
  return {static_cast<double>(e.x_um) * 1e-6, static_cast<double>(e.y_um) * 1e-6,
          static_cast<double>(e.theta_q8) / 256.0 * kUnit};
}

// A loop in the room, with a biased and noisy odometry (grid_slam_loop_test.cpp; slam_test.cpp
// scores its trajectory), run once an arithmetic.
struct LoopLog {
  Log log;
  std::vector<TimedPose> truth;
};

inline LoopLog make_loop_log() {
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

inline const LoopLog& loop_log() {
  static const LoopLog log = make_loop_log();
  return log;
}

inline GridSlamConfig loop_config() {
  return small_config();
}

inline const SlamRun& loop_run(Arithmetic arithmetic) {
  static const SlamRun integer = run_grid_slam(loop_log().log, loop_config(), Arithmetic::integer);
  static const SlamRun floating =
      run_grid_slam(loop_log().log, loop_config(), Arithmetic::floating);
  return arithmetic == Arithmetic::integer ? integer : floating;
}

}  // namespace intgrid::grid_slam_test
