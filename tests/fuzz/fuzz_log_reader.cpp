// The log readers (read_log: the project format, or CARMEN by its first record) on any bytes:
// a log, or one InputError naming the file; what is read is finite and within the readers'
// plausibility limits, and the project format writes and reads back to the same doubles.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_input.hpp"
#include "intgrid/io/log_io.hpp"

using namespace intgrid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = fuzz::write_input("input.log", {reinterpret_cast<const char*>(data), size});
  core::Log log;
  try {
    io::SkippedRecords skipped;
    log = io::read_log(file, &skipped);
  } catch (const io::InputError& e) {
    fuzz::check_refusal(e, file);
    return 0;
  }
  for (const core::Scan& scan : log.scans) {
    fuzz::require(!scan.ranges.empty() && scan.ranges.size() <= io::kMaxBeamsPerScan);
    fuzz::require(std::isfinite(scan.t) && std::isfinite(scan.angle0) &&
                  std::isfinite(scan.dangle));
    fuzz::require(scan.max_range > 0.0 && scan.max_range <= io::kMaxRangeLimitMetres);
    for (const core::Pose2& p : {scan.robot, scan.sensor_mount})
      fuzz::require(std::abs(p.x) <= io::kMaxPositionMetres &&
                    std::abs(p.y) <= io::kMaxPositionMetres && std::isfinite(p.theta));
  }
  for (const core::OdometryRecord& o : log.odometry)
    fuzz::require(std::isfinite(o.t) && std::isfinite(o.pose.theta));
  if (log.scans.empty()) return 0;
  // Written in the project format and read back: the same scans, to the bit.
  const auto copy = fuzz::work_dir() / "copy.log";
  io::write_log(copy, log);
  const core::Log again = io::read_intgrid_log(copy);
  fuzz::require(again.scans.size() == log.scans.size());
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const core::Scan &a = log.scans[i], &b = again.scans[i];
    fuzz::require(a.t == b.t && a.robot.x == b.robot.x && a.robot.theta == b.robot.theta &&
                  a.max_range == b.max_range && a.ranges.size() == b.ranges.size());
    for (std::size_t k = 0; k < a.ranges.size(); ++k)
      fuzz::require(a.ranges[k] == b.ranges[k] ||
                    (std::isnan(a.ranges[k]) && std::isnan(b.ranges[k])));
  }
  return 0;
}
