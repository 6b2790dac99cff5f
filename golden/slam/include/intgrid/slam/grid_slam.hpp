// SLAM scan by scan, in SI units: the online form of the event-driven grid SLAM. Each scan comes
// as a core::Scan (ranges in metres, the robot's odometry pose); the integer inputs of the
// per-scan path (millimetres, angle units, odometry increments) are made here and nowhere else.
// run_grid_slam (log_run.hpp) is this, over a whole log.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"

namespace intgrid::slam {

// "scan N (t = T)", N counted from 1: how errors name a scan.
std::string scan_label(std::size_t number, double t);

// What makes scan b's sensor geometry differ from a's ("beam count", "bearings", "maximum range",
// "sensor mount"), or nullptr.
const char* geometry_difference(const core::Scan& b, const core::Scan& a);

// One scan's inputs to the per-scan path, from its core::Scan and the previous scan's robot pose:
// ranges in mm (0: no usable return: not a valid reading of the scan, or at or past the beam
// model's max_range, in metres) and the odometry increment in the previous robot frame. Counts the
// readings and the unusable ones. Throws std::invalid_argument, naming `name`, for an odometry step
// that is not finite or longer than 1 km.
QuantizedScan quantize_scan(const core::Scan& scan, const core::Pose2* previous_robot,
                            double max_range, const std::string& name, std::size_t& readings,
                            std::size_t& unusable);
inline QuantizedScan quantize_scan(const core::Scan& scan, const core::Pose2* previous_robot,
                                   const GridSlamConfig& config, const std::string& name,
                                   std::size_t& readings, std::size_t& unusable) {
  return quantize_scan(scan, previous_robot, config.sensor.max_range, name, readings, unusable);
}

class GridSlam {
 public:
  // A run whose sensor geometry (beam count, bearings, max range, mount) is `first`'s and whose
  // odometry stays within reach_m metres of first.robot (the map is sized for it). The SLAM frame
  // is first.robot. Throws std::invalid_argument for a bad configuration (naming the field).
  GridSlam(const GridSlamConfig& config, core::Arithmetic arithmetic, const core::Scan& first,
           double reach_m);
  ~GridSlam();
  GridSlam(GridSlam&&) noexcept;
  GridSlam& operator=(GridSlam&&) noexcept;

  // The next scan, `first` included: the motion update from the previous scan's odometry pose,
  // then localization and mapping as the schedule says. Throws std::invalid_argument for a scan
  // of another geometry or an odometry jump over 1 km, std::runtime_error if the pose window
  // reaches the map's edge.
  void insert(const core::Scan& scan);

  core::Pose2 pose() const;  // the estimate (mean of the pose grid), in the log's frame
  double sigma() const;      // its positional standard deviation (m)
  core::Pose2 frame() const { return frame_; }  // the SLAM frame in the log's frame
  const core::Grid<std::int8_t>& map() const;   // S_eps indices, in the SLAM frame
  const core::SepsCodec& codec() const;
  // The map's probabilities in the log's frame (slam_map_probabilities).
  core::ProbabilityGrid map_probabilities() const;
  std::size_t scans() const;
  std::size_t localizations() const;
  std::size_t mappings() const;
  std::size_t skipped_scans() const;  // no usable reading: only the motion update ran
  std::size_t readings() const { return readings_; }
  std::size_t unusable_readings() const { return unusable_; }

 private:
  struct Engine;  // GridSlamEngine in the chosen arithmetic
  std::unique_ptr<Engine> engine_;
  core::Scan geometry_;  // the first scan, without its ranges
  core::Pose2 frame_, previous_robot_;
  std::size_t readings_ = 0, unusable_ = 0;
};

}  // namespace intgrid::slam
