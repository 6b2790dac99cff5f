// Plain data types shared by every golden module: poses, scans, logs.
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

namespace intgrid::core {

// The two arithmetics of every algorithm: integer indices (S_eps, U_gamma) or double precision.
enum class Arithmetic { integer, floating };

// A planar pose: position in metres, heading in radians (counter-clockwise from +x).
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;

  bool operator==(const Pose2&) const = default;  // the same three numbers
};

// An angle wrapped to (-pi, pi].
inline double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

// The composition a (+) b: b expressed in a's frame, returned in the world frame.
inline Pose2 compose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, a.theta + b.theta};
}

// The pose b seen from a: the inverse of compose, so compose(a, relative(a, b)) == b.
inline Pose2 relative(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, b.theta - a.theta};
}

// One 2D range scan. Beam i has bearing angle0 + i * dangle in the sensor frame.
// A range that is 0, NaN, negative, infinite or at/over max_range is no valid return.
struct Scan {
  double t = 0.0;      // UNIX time, seconds
  Pose2 robot;         // robot pose when the scan was taken (odometry or reference)
  Pose2 sensor_mount;  // sensor pose in the robot frame
  double angle0 = 0.0;
  double dangle = 0.0;
  double max_range = 0.0;
  std::vector<double> ranges;

  Pose2 sensor_pose() const { return compose(robot, sensor_mount); }
  double bearing(std::size_t i) const { return angle0 + static_cast<double>(i) * dangle; }
  bool is_valid_range(double r) const { return std::isfinite(r) && r > 0.0 && r < max_range; }
};

struct OdometryRecord {
  double t = 0.0;
  Pose2 pose;
};

// A sensor log: scans and odometry records, each in time order as recorded.
struct Log {
  std::vector<Scan> scans;
  std::vector<OdometryRecord> odometry;
  std::size_t reordered_scans = 0;  // scans a reader moved to put them in time order
};

}  // namespace intgrid::core
