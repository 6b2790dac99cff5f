// Reading and writing sensor logs: the project's own text format and CARMEN logs (Intel,
// Freiburg). Every problem in an input file is an InputError naming file, line and field.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>

#include "intgrid/core/types.hpp"

namespace intgrid::io {

// Beam counts above this are taken for a corrupt line rather than a sensor.
inline constexpr std::size_t kMaxBeamsPerScan = 100000;

// The nominal maximum range of the SICK LMS lasers of the CARMEN data sets, which FLASER
// records do not carry.
inline constexpr double kCarmenDefaultMaxRange = 80.0;

// Record types a CARMEN reader passed over, with how many of each (e.g. "PARAM" -> 52).
using SkippedRecords = std::map<std::string, std::size_t>;

// Reads a log in either format, chosen by its first record: RLASER, or ODOM with the project's
// 4 fields, means the project format; anything else is read as CARMEN. CARMEN scans get
// kCarmenDefaultMaxRange; skipped (if given) receives the CARMEN record types passed over.
core::Log read_log(const std::filesystem::path& file, SkippedRecords* skipped = nullptr);

// The project format:
//   ODOM x y theta t
//   RLASER n angle0 dangle maxrange r_0 ... r_{n-1} x y theta sx sy stheta t
// Blank lines and lines starting with '#' are ignored; any other record type is an error.
// Ranges are kept as written, even NaN, negative or out of range ones.
core::Log read_intgrid_log(const std::filesystem::path& file);

// CARMEN: FLASER n r_0..r_{n-1} x y theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname
// logger_timestamp, and ODOM x y theta tv rv accel ipc_timestamp ipc_hostname logger_timestamp.
// A scan's robot pose is the odometry pose, its sensor mount the laser pose seen from there; its
// beams span 180 degrees from -pi/2. Other record types are skipped and counted into skipped.
// Throws std::invalid_argument unless max_range is finite and positive.
core::Log read_carmen_log(const std::filesystem::path& file,
                          double max_range = kCarmenDefaultMaxRange,
                          SkippedRecords* skipped = nullptr);

// Writes log atomically in the project format, scans and odometry merged in time order, with
// the shortest digits that read back to the same doubles. Throws std::invalid_argument for a
// scan with no ranges or more than kMaxBeamsPerScan, std::runtime_error if writing fails.
void write_log(const std::filesystem::path& file, const core::Log& log);

}  // namespace intgrid::io
