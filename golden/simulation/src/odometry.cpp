// Odometry: the true motion with drift and noise.
#include "intgrid/simulation/simulator.hpp"

#include "simulation_support.hpp"

namespace intgrid::simulation {

using namespace support;

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

}  // namespace intgrid::simulation
