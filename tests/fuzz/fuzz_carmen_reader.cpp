// The CARMEN reader on any bytes (FLASER, ROBOTLASER1, ODOM, PARAM and the records it skips): a
// log, or one InputError naming the file; what is read is finite and within the readers'
// plausibility limits.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "intgrid/io/log_io.hpp"

using namespace intgrid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = fuzz::write_input("input.clf", {reinterpret_cast<const char*>(data), size});
  try {
    io::SkippedRecords skipped;
    const core::Log log = io::read_carmen_log(file, std::nullopt, &skipped);
    fuzz::require(!log.scans.empty());
    for (std::size_t i = 0; i < log.scans.size(); ++i) {
      const core::Scan& scan = log.scans[i];
      fuzz::require(!scan.ranges.empty() && std::isfinite(scan.t));
      fuzz::require(i == 0 || log.scans[i - 1].t <= scan.t);  // sorted by time
      fuzz::require(scan.max_range > 0.0 && scan.max_range <= io::kMaxRangeLimitMetres);
      fuzz::require(std::hypot(scan.sensor_mount.x, scan.sensor_mount.y) <= io::kMaxMountMetres);
      fuzz::require(std::abs(scan.robot.x) <= io::kMaxPositionMetres &&
                    std::abs(scan.robot.y) <= io::kMaxPositionMetres);
    }
  } catch (const io::InputError& e) {
    fuzz::check_refusal(e, file);
  }
  return 0;
}
