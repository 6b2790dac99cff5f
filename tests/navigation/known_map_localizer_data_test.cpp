// KnownMapLocalizer on the bundled real log in the bundled map of the same courtyard, scored
// against the reference's poses directly (the map's frame is the reference's): found with no
// initial pose and tracked to the end without a loss; and carried off (a simulated kidnapping:
// the log cut and rejoined 40 scans later or earlier, its odometry continued as if the robot had
// not moved), declared lost and found again; started from a wrong pose, corrected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <vector>

#include "data_dir.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/io/map_io.hpp"
#include "intgrid/navigation/known_map_localizer.hpp"
#include "intgrid/slam/trajectory_metrics.hpp"

namespace intgrid::navigation {
namespace {

struct Bundled {
  core::Log log;
  std::map<double, core::Pose2> reference;
  io::RosMap map;
};

Bundled bundled() {
  const std::filesystem::path data = intgrid::test::data_dir();
  Bundled b{io::read_log(data / "malaga_telecom_loop.log"),
            {},
            io::read_ros_map(data / "malaga_telecom_map.yaml")};
  for (const slam::TimedPose& p :
       slam::scan_poses(io::read_log(data / "malaga_telecom_loop_reference.log")))
    b.reference[p.t] = p.pose;
  return b;
}

KnownMapLocalizer localizer_for(const Bundled& b, std::optional<core::Pose2> initial = {}) {
  KnownMapLocalizerConfig config;
  config.tracking.cell = b.map.grid.geometry.resolution;
  return KnownMapLocalizer(b.map.grid, b.map.occupied_thresh, b.map.free_thresh, config,
                           core::Arithmetic::integer, initial);
}

double error(const core::Pose2& pose, const core::Pose2& truth) {
  return std::hypot(pose.x - truth.x, pose.y - truth.y);
}

TEST(KnownMapLocalizerData, FindsTheRobotWithNoInitialPoseAndTracksItToTheEnd) {
  const Bundled b = bundled();
  KnownMapLocalizer localizer = localizer_for(b);
  std::optional<std::size_t> first_pose;
  std::size_t lost = 0, scored = 0;
  double sum2 = 0.0;
  // Each scan's fit against the median of the fits before it: how far a tracked run dips.
  std::vector<double> fits;
  double least_share = 1.0;
  for (std::size_t i = 0; i < b.log.scans.size(); ++i) {
    const LocalizerStep step = localizer.localize(b.log.scans[i]);
    lost += step.state == LocalizerState::lost;
    if (!step.pose) continue;
    if (!first_pose) first_pose = i;
    if (step.fix.matched) {
      if (fits.size() >= 3) {
        std::vector<double> recent(fits.end() - std::min<std::ptrdiff_t>(50, fits.size()),
                                   fits.end());
        std::nth_element(recent.begin(), recent.begin() + recent.size() / 2, recent.end());
        least_share = std::min(least_share, step.fix.fit / recent[recent.size() / 2]);
      }
      fits.push_back(step.fix.fit);
    }
    const auto truth = b.reference.find(b.log.scans[i].t);
    if (truth == b.reference.end()) continue;
    sum2 += std::pow(error(*step.pose, truth->second), 2);
    ++scored;
  }
  const double rmse = std::sqrt(sum2 / static_cast<double>(scored));
  std::printf(
      "no initial pose: first pose at scan %zu, %zu losses, %.3f m RMS over %zu reference poses; "
      "the lowest fit %.2f of the recent median\n",
      first_pose.value_or(999), lost, rmse, scored, least_share);
  ASSERT_TRUE(first_pose.has_value());
  // The first scan is unambiguous in this map (globloc --track: every scan within 4 fused).
  EXPECT_LE(*first_pose, 4u);
  EXPECT_EQ(lost, 0u);
  EXPECT_GT(scored, 90u);
  EXPECT_LT(rmse, 0.15);  // the SLAM's target on this log; measured 0.105 m
  // The lost criterion's margin on a tracked run: its lowest fit (measured 0.36 of the median)
  // stays above the share that declares a scan misfit.
  EXPECT_GT(least_share, KnownMapLocalizerConfig{}.lost.fit_share);
}

// The robot carried off after scan `cut` - 1 to where it was at scan `rejoin` (later or earlier):
// the log goes on from `rejoin`, its times shifted to follow on and its odometry continued from
// scan `cut` - 1 as if the robot had not moved.
struct Kidnapping {
  core::Log log;
  double shift = 0.0;  // s added to the rejoined scans' times
};

Kidnapping kidnapped(const core::Log& log, std::size_t cut, std::size_t rejoin) {
  Kidnapping k;
  k.shift = log.scans[cut].t - log.scans[rejoin].t;
  for (std::size_t i = 0; i < cut; ++i) k.log.scans.push_back(log.scans[i]);
  for (std::size_t i = rejoin; i < log.scans.size(); ++i) {
    core::Scan scan = log.scans[i];
    scan.robot = core::compose(log.scans[cut - 1].robot,
                               core::relative(log.scans[rejoin].robot, scan.robot));
    scan.robot.theta = core::wrap_angle(scan.robot.theta);
    scan.t += k.shift;
    k.log.scans.push_back(std::move(scan));
  }
  return k;
}

TEST(KnownMapLocalizerData, FindsTheRobotAgainAfterItIsCarriedOff) {
  const Bundled b = bundled();
  // Carried 40 scans ahead, and 40 scans back to where it had been.
  for (const auto& [cut, rejoin] : {std::pair<std::size_t, std::size_t>{120, 160}, {60, 20}}) {
    const Kidnapping k = kidnapped(b.log, cut, rejoin);
    KnownMapLocalizer localizer = localizer_for(b, b.reference.begin()->second);
    std::optional<std::size_t> lost_at, found_at;
    std::size_t losses = 0, scored_after = 0;
    double sum2 = 0.0;
    for (std::size_t i = 0; i < k.log.scans.size(); ++i) {
      const LocalizerStep step = localizer.localize(k.log.scans[i]);
      if (step.state == LocalizerState::lost) {
        ++losses;
        if (!lost_at) lost_at = i;
      }
      if (lost_at && !found_at && step.state == LocalizerState::tracking) found_at = i;
      if (!found_at || !step.pose) continue;
      const auto truth = b.reference.find(k.log.scans[i].t - k.shift);
      if (truth == b.reference.end()) continue;
      ++scored_after;
      sum2 += std::pow(error(*step.pose, truth->second), 2);
    }
    const double rmse =
        std::sqrt(sum2 / static_cast<double>(std::max<std::size_t>(1, scored_after)));
    std::printf(
        "carried off after scan %zu to scan %zu's place: lost at %zu, tracked again at %zu; "
        "%.3f m RMS over the %zu reference poses since; %zu losses\n",
        cut - 1, rejoin, lost_at.value_or(999), found_at.value_or(999), rmse, scored_after, losses);
    ASSERT_TRUE(lost_at.has_value());
    ASSERT_TRUE(found_at.has_value());
    EXPECT_GE(*lost_at, cut);        // not before the robot was carried off
    EXPECT_LE(*found_at, cut + 10);  // the target: found again within 10 scans
    EXPECT_EQ(losses, 1u);
    EXPECT_GT(scored_after, 20u);
    EXPECT_LT(rmse, 0.15);  // as tracked from the start (0.105 m); measured 0.038 and 0.111 m
  }
}

// Started from a wrong pose, which is taken as given: turned half round at the true place (its
// scans fit the map badly, but no worse than the fits before them) or 7 m off. The checks by
// global localization every 10 m of travel, and the fits, bring it back: a contest the map's
// evidence decides, or a loss and a fix.
TEST(KnownMapLocalizerData, AWrongInitialPoseIsCorrectedByTheMap) {
  const Bundled b = bundled();
  const core::Pose2 start = b.reference.begin()->second;
  for (const core::Pose2& wrong : {core::Pose2{start.x, start.y, start.theta + 3.14159},
                                   core::Pose2{start.x + 5.0, start.y + 5.0, start.theta}}) {
    KnownMapLocalizer localizer = localizer_for(b, wrong);
    std::optional<std::size_t> corrected;
    std::size_t scored = 0;
    double sum2 = 0.0;
    for (std::size_t i = 0; i < b.log.scans.size(); ++i) {
      const LocalizerStep step = localizer.localize(b.log.scans[i]);
      if (!corrected && (step.refixed || step.state == LocalizerState::lost)) corrected = i;
      if (!corrected || !step.pose) continue;
      const auto truth = b.reference.find(b.log.scans[i].t);
      if (truth == b.reference.end()) continue;
      sum2 += std::pow(error(*step.pose, truth->second), 2);
      ++scored;
    }
    const double rmse = std::sqrt(sum2 / static_cast<double>(std::max<std::size_t>(1, scored)));
    std::printf("started at (%.1f, %.1f, %.0f deg): corrected at scan %zu, %.3f m RMS since\n",
                wrong.x, wrong.y, wrong.theta * 180.0 / 3.14159265, corrected.value_or(999), rmse);
    ASSERT_TRUE(corrected.has_value());
    EXPECT_LE(*corrected, 80u);  // measured 62 in both
    EXPECT_GT(scored, 50u);
    EXPECT_LT(rmse, 0.15);
  }
}

}  // namespace
}  // namespace intgrid::navigation
