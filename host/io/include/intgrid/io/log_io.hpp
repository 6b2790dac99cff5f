// Reading and writing sensor logs: the project's own text format and CARMEN logs (the Freiburg
// SLAM benchmark's FLASER logs, ROBOTLASER1 logs). Every problem in an input file is an InputError
// naming file, line and field.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "intgrid/core/types.hpp"

namespace intgrid::io {

// Beam counts above this are taken for a corrupt line rather than a sensor.
inline constexpr std::size_t kMaxBeamsPerScan = 100000;

// Plausibility limits of the readers: a value past one is taken for a corrupt or absurd log
// (refused naming file, line and field) rather than passed to the algorithms, where a mount of
// 6.4e38 m turned into a grid size that does not fit an int. Each is far past any robot's:
// poses within 1000 km of the log's origin, a sensor within 100 m of the robot's reference
// point, a maximum range up to 10 km (laser scanners reach a few hundred metres), scan angles
// within one turn either way.
inline constexpr double kMaxPositionMetres = 1e6;
inline constexpr double kMaxMountMetres = 100.0;
inline constexpr double kMaxRangeLimitMetres = 1e4;
inline constexpr double kMaxScanAngleRadians = 6.283185307179586;

// The nominal maximum range of the SICK LMS lasers of the CARMEN data sets, for FLASER records
// of a log that states none and shows no saturation value (see read_carmen_log).
inline constexpr double kCarmenDefaultMaxRange = 80.0;

// Record types a CARMEN reader turned into neither scans nor odometry, with how many of each
// (e.g. "PARAM" -> 52; PARAM lines count here although the reader uses a few of them).
using SkippedRecords = std::map<std::string, std::size_t>;

// Reads a log in either format, chosen by its first record: RLASER, or ODOM with the project's
// 4 fields, means the project format; anything else is read as CARMEN (read_carmen_log with no
// max_range). skipped (if given) receives the CARMEN record types passed over.
core::Log read_log(const std::filesystem::path& file, SkippedRecords* skipped = nullptr);

// The project format:
//   ODOM x y theta t
//   RLASER n angle0 dangle maxrange r_0 ... r_{n-1} x y theta sx sy stheta t
// Blank lines and lines starting with '#' are ignored; any other record type is an error.
// Ranges are kept as written, even NaN, negative or out of range ones; records keep file order.
core::Log read_intgrid_log(const std::filesystem::path& file);

// CARMEN logs as the Freiburg SLAM benchmark and its users write them. Records read:
//   FLASER n r_0..r_{n-1} x y theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname
//     logger_timestamp: n beams (180, 181, 360, 361, ...) over 180 degrees from -pi/2, odd n
//     including both ends; x y theta the laser pose, odom_* the robot pose.
//   ROBOTLASER1 laser_type start_angle field_of_view angular_resolution maximum_range accuracy
//     remission_mode num_readings r_1..r_n num_remissions rem_1..rem_m laser_x laser_y
//     laser_theta robot_x robot_y robot_theta laser_tv laser_rv forward_safety_dist
//     side_safety_dist turn_axis ipc_timestamp hostname logger_timestamp: bearing i is
//     start_angle + i * angular_resolution, max range maximum_range; num_readings must be
//     round(field_of_view / angular_resolution), or one more (both ends).
//   ODOM x y theta tv rv accel ipc_timestamp ipc_hostname logger_timestamp -> log.odometry. A log
//     with no ODOM line has empty odometry; its scans still carry their robot poses.
//   PARAM name value [...]: robot_front_laser_max (or any *_laser_max / *_laser_max_range not
//     naming the rear laser) and robot_frontlaser_offset / _side_offset / _angular_offset.
// Other record types (SYNC, TRUEPOS, CARMEN's rear-laser RLASER, ...) are skipped and counted.
// A scan's time is its ipc_timestamp and its robot pose the record's odometry (robot) pose.
//
// Sensor mount, one for the whole log: relative(robot pose, laser pose) of the records if it is
// the same for every laser record (within 1 mm and 1e-3 rad); otherwise (the laser pose is, e.g.,
// a corrected pose while the odometry is raw) the PARAM robot_frontlaser_offset (x),
// _side_offset (y) and _angular_offset (theta) if any is present, else the zero mount. A laser
// pose that changes against the robot pose is never refused.
//
// FLASER max range (ROBOTLASER1 states its own): max_range if given; else the PARAM's value;
// else the log's largest FLASER reading if it is a saturation value (written at least 3 times,
// more often than all readings within 5% below it together), so that those readings are no
// returns; else kCarmenDefaultMaxRange, which also leaves the 81.9 m of saturated SICK lasers no
// return. On the benchmark logs this gives 81.83 m for intel.clf (81.83 written 68,313 times, the
// next largest reading is 26.37) and 50 m for aces.clf (50.00 written 11,139 times, 229 readings
// in [47.5, 50)); neither has the PARAM.
//
// Time order: laser records and odometry records are each stably sorted by ipc_timestamp;
// log.reordered_scans counts the scans whose position that changed. A record more than 1.0 s
// earlier than the latest one of its kind before it is an InputError on its line, field
// ipc_timestamp. intel.clf has 631 laser records earlier than the one before, by at most 0.897 s;
// sorting moves 2,591 of its 13,631 scans. aces.clf is in order.
//
// Throws InputError for a malformed record (file, line, field) and for a log with no FLASER or
// ROBOTLASER1 record; std::invalid_argument unless max_range (if given) is finite and positive.
core::Log read_carmen_log(const std::filesystem::path& file,
                          std::optional<double> max_range = std::nullopt,
                          SkippedRecords* skipped = nullptr);

// Writes log atomically in the project format, scans and odometry merged in time order, with
// the shortest digits that read back to the same doubles. Throws std::invalid_argument for a
// scan with no ranges or more than kMaxBeamsPerScan, std::runtime_error if writing fails.
void write_log(const std::filesystem::path& file, const core::Log& log);

}  // namespace intgrid::io
