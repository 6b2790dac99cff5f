#include "intgrid/io/log_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/text_io.hpp"

namespace intgrid::io {
namespace {

namespace fs = std::filesystem;

// '\r' counts as a blank, so lines of CRLF files parse like LF ones.
constexpr std::string_view kBlanks = " \t\r\v\f";

struct Line {
  std::size_t number = 0;  // 1-based
  std::string_view text;
};

// The record lines of a log text, in order; blank lines and '#' comments are passed over.
class RecordLines {
 public:
  explicit RecordLines(std::string_view text) : rest_(text) {}

  std::optional<Line> next() {
    while (!rest_.empty()) {
      const std::size_t end = rest_.find('\n');
      const std::string_view text = rest_.substr(0, end);
      rest_.remove_prefix(end == std::string_view::npos ? rest_.size() : end + 1);
      ++number_;
      const std::size_t first = text.find_first_not_of(kBlanks);
      if (first != std::string_view::npos && text[first] != '#') return Line{number_, text};
    }
    return std::nullopt;
  }

 private:
  std::string_view rest_;
  std::size_t number_ = 0;
};

// The blank-separated fields of one record, consumed left to right. Every read names its field,
// so a missing or bad value is reported as FILE:LINE: FIELD: MESSAGE.
class RecordFields {
 public:
  RecordFields(const fs::path& file, const Line& line)
      : file_(file), line_number_(line.number), rest_(line.text) {
    keyword_ = next_token({"record type"});
  }

  std::string_view keyword() const { return keyword_; }
  std::size_t line() const { return line_number_; }

  [[noreturn]] void fail(const FieldName& field, const std::string& message) const {
    throw InputError(file_, line_number_, field.str(), message);
  }

  std::string_view next_token(const FieldName& field) {
    const std::optional<std::string_view> token = take_token();
    if (!token) fail(field, "missing: the line ends before this field");
    last_field_ = field;
    return *token;
  }

  // Any number, NaN and infinities included.
  double next_number(const FieldName& field) {
    return parse_number<double>(next_token(field), file_, line_number_, field);
  }

  double next_finite(const FieldName& field) {
    const double value = next_number(field);
    if (!std::isfinite(value)) fail(field, "must be a finite number");
    return value;
  }

  double next_positive(const FieldName& field) {
    const double value = next_finite(field);
    if (!(value > 0.0)) fail(field, "must be positive");
    return value;
  }

  // A finite number of magnitude at most `limit` (what the limit is: "metres from the log's
  // origin").
  double next_within(const FieldName& field, double limit, const char* what) {
    const double value = next_finite(field);
    if (!(std::abs(value) <= limit))
      fail(field,
           format_number(value) + " is past the plausible " + format_number(limit) + " " + what);
    return value;
  }

  double next_max_range(const FieldName& field) {
    const double value = next_positive(field);
    if (!(value <= kMaxRangeLimitMetres))
      fail(field, format_number(value) + " m is past the plausible " +
                      format_number(kMaxRangeLimitMetres) + " m of a range sensor");
    return value;
  }

  // A position of the robot or the sensor in the log's frame, and an offset of the sensor from
  // the robot's reference point.
  double next_position(const FieldName& field) {
    return next_within(field, kMaxPositionMetres, "metres from the log's origin");
  }
  double next_mount_offset(const FieldName& field) {
    return next_within(field, kMaxMountMetres, "metres from the robot's reference point");
  }

  core::Pose2 next_pose(std::string_view x, std::string_view y, std::string_view theta) {
    core::Pose2 pose;
    pose.x = next_position({x});
    pose.y = next_position({y});
    pose.theta = next_finite({theta});
    return pose;
  }

  core::Pose2 next_mount(std::string_view x, std::string_view y, std::string_view theta) {
    core::Pose2 mount;
    mount.x = next_mount_offset({x});
    mount.y = next_mount_offset({y});
    mount.theta = next_finite({theta});
    return mount;
  }

  // A count of 0 to kMaxBeamsPerScan values.
  std::size_t next_count(const FieldName& field) {
    const long long count = parse_number<long long>(next_token(field), file_, line_number_, field);
    if (count < 0) fail(field, "must be a non-negative integer, got " + std::to_string(count));
    if (static_cast<unsigned long long>(count) > kMaxBeamsPerScan) {
      fail(field, std::to_string(count) + " values is absurd (at most " +
                      std::to_string(kMaxBeamsPerScan) + ")");
    }
    return static_cast<std::size_t>(count);
  }

  std::size_t next_beam_count(const FieldName& field) {
    const long long count = parse_number<long long>(next_token(field), file_, line_number_, field);
    if (count <= 0) fail(field, "must be a positive integer, got " + std::to_string(count));
    if (static_cast<unsigned long long>(count) > kMaxBeamsPerScan) {
      fail(field, std::to_string(count) + " beams is absurd (at most " +
                      std::to_string(kMaxBeamsPerScan) + ")");
    }
    return static_cast<std::size_t>(count);
  }

  std::vector<double> next_ranges(std::size_t count) {
    std::vector<double> ranges(count);
    for (std::size_t i = 0; i < count; ++i) ranges[i] = next_number({"r_", i});
    return ranges;
  }

  std::size_t remaining_count() const {
    RecordFields copy = *this;
    std::size_t count = 0;
    while (copy.take_token()) ++count;
    return count;
  }

  void expect_end() const {
    RecordFields rest = *this;
    const std::optional<std::string_view> first_extra = rest.take_token();
    if (!first_extra) return;
    fail({keyword_}, std::to_string(1 + rest.remaining_count()) + " unexpected field(s) after " +
                         last_field_.str() + ", starting with " + quote_input(*first_extra));
  }

 private:
  std::optional<std::string_view> take_token() {
    const std::size_t begin = rest_.find_first_not_of(kBlanks);
    if (begin == std::string_view::npos) return std::nullopt;
    const std::size_t end = rest_.find_first_of(kBlanks, begin);
    const std::string_view token = rest_.substr(begin, end - begin);
    rest_.remove_prefix(end == std::string_view::npos ? rest_.size() : end);
    return token;
  }

  const fs::path& file_;
  std::size_t line_number_;
  std::string_view rest_;
  std::string_view keyword_;
  FieldName last_field_{"record type"};
};

void require_scans(const fs::path& file, const core::Log& log, std::string_view scan_record) {
  if (log.scans.empty()) {
    throw InputError(file, 0, "file",
                     "the log holds no scans (no " + std::string(scan_record) + " records)");
  }
}

// ---- the project format ----

core::Scan read_intgrid_scan(RecordFields& fields) {
  core::Scan scan;
  const std::size_t count = fields.next_beam_count({"n"});
  scan.angle0 = fields.next_within({"angle0"}, kMaxScanAngleRadians, "radians");
  scan.dangle = fields.next_within({"dangle"}, kMaxScanAngleRadians, "radians");
  scan.max_range = fields.next_max_range({"maxrange"});
  scan.ranges = fields.next_ranges(count);
  scan.robot = fields.next_pose("x", "y", "theta");
  scan.sensor_mount = fields.next_mount("sx", "sy", "stheta");
  scan.t = fields.next_finite({"t"});
  fields.expect_end();
  return scan;
}

core::OdometryRecord read_intgrid_odometry(RecordFields& fields) {
  core::OdometryRecord record;
  record.pose = fields.next_pose("x", "y", "theta");
  record.t = fields.next_finite({"t"});
  fields.expect_end();
  return record;
}

core::Log parse_intgrid_log(const fs::path& file, std::string_view text) {
  core::Log log;
  RecordLines lines(text);
  while (const std::optional<Line> line = lines.next()) {
    RecordFields fields(file, *line);
    if (fields.keyword() == "RLASER") {
      log.scans.push_back(read_intgrid_scan(fields));
    } else if (fields.keyword() == "ODOM") {
      log.odometry.push_back(read_intgrid_odometry(fields));
    } else {
      fields.fail({"record type"}, "unknown record type " + quote_input(fields.keyword()) +
                                       " (expected RLASER or ODOM)");
    }
  }
  require_scans(file, log, "RLASER");
  return log;
}

// ---- CARMEN ----

// A laser record may be this much earlier than the latest one before it (logging jitter, sorted
// into place); more is refused.
constexpr double kMaxTimestampJitter = 1.0;  // s

// Per-scan mounts that agree within this (m, rad) are one mount.
constexpr double kMountTolerance = 1e-3;

// A largest reading at least this many times, more often than all readings within
// kSaturationBand below it together, is the sensor's saturation value.
constexpr std::size_t kMinSaturationCount = 3;
constexpr double kSaturationBand = 0.05;  // of the value

// A laser record as read, before the choices made for the whole log (mount, FLASER max range).
struct CarmenLaser {
  core::Scan scan;
  core::Pose2 laser;   // the laser's pose in the world frame, as written
  bool flaser = true;  // FLASER carries no max range, ROBOTLASER1 does
};

// The PARAM values the reader uses.
struct CarmenParams {
  std::optional<double> front_laser_max;
  std::optional<double> offset, side_offset, angular_offset;

  bool has_mount() const { return offset || side_offset || angular_offset; }
  core::Pose2 mount() const {
    return {offset.value_or(0.0), side_offset.value_or(0.0), angular_offset.value_or(0.0)};
  }
};

// The front laser's maximum range: robot_front_laser_max in the logs of the Freiburg benchmark,
// or any other name ending in _laser_max or _laser_max_range that is not the rear laser's.
bool is_front_laser_max_param(std::string_view name) {
  return (name.ends_with("_laser_max") || name.ends_with("_laser_max_range")) &&
         name.find("rear") == std::string_view::npos;
}

// PARAM name value [ipc_timestamp hostname logger_timestamp]: the trailer varies, and is ignored.
void read_carmen_param(RecordFields& fields, CarmenParams& params) {
  const std::string_view name = fields.next_token({"param_name"});
  if (is_front_laser_max_param(name)) {
    params.front_laser_max = fields.next_max_range({"param_value"});
  } else if (name == "robot_frontlaser_offset") {
    params.offset = fields.next_mount_offset({"param_value"});
  } else if (name == "robot_frontlaser_side_offset") {
    params.side_offset = fields.next_mount_offset({"param_value"});
  } else if (name == "robot_frontlaser_angular_offset") {
    params.angular_offset = fields.next_finite({"param_value"});
  }
}

// Records of one stream (laser or odometry) may come slightly out of time order; a record more
// than kMaxTimestampJitter earlier than the latest one before it is an error on its line.
class TimeOrder {
 public:
  explicit TimeOrder(const char* records) : records_(records) {}

  void check(const RecordFields& fields, double t) {
    if (latest_line_ != 0 && t < latest_ - kMaxTimestampJitter) {
      fields.fail({"ipc_timestamp"},
                  printed("%.6f goes back %.3f s from the %s record at line %zu (%.6f); only up "
                          "to %.1f s of logging jitter is sorted into place",
                          t, latest_ - t, records_, latest_line_, latest_, kMaxTimestampJitter));
    }
    if (latest_line_ == 0 || t > latest_) {
      latest_ = t;
      latest_line_ = fields.line();
    }
  }

 private:
  const char* records_;
  double latest_ = 0.0;
  std::size_t latest_line_ = 0;
};

// Every CARMEN message ends with these; the IPC time is when the data was taken.
double read_carmen_timestamps(RecordFields& fields) {
  const double ipc_timestamp = fields.next_finite({"ipc_timestamp"});
  fields.next_token({"ipc_hostname"});
  fields.next_finite({"logger_timestamp"});
  fields.expect_end();
  return ipc_timestamp;
}

// FLASER beams span 180 degrees: n odd (181, 361) includes both ends, n even (180, 360) does not.
double carmen_beam_step(std::size_t count) {
  const std::size_t steps = count % 2 == 1 ? count - 1 : count;
  return std::numbers::pi / static_cast<double>(steps);
}

// FLASER n r_0..r_{n-1} x y theta odom_x odom_y odom_theta + timestamps.
CarmenLaser read_flaser(RecordFields& fields) {
  CarmenLaser record;
  core::Scan& scan = record.scan;
  const std::size_t count = fields.next_beam_count({"n"});
  if (count < 2) fields.fail({"n"}, "a FLASER scan needs at least 2 beams");
  scan.ranges = fields.next_ranges(count);
  record.laser = fields.next_pose("x", "y", "theta");
  scan.robot = fields.next_pose("odom_x", "odom_y", "odom_theta");
  scan.t = read_carmen_timestamps(fields);
  scan.angle0 = -std::numbers::pi / 2.0;
  scan.dangle = carmen_beam_step(count);
  return record;
}

// ROBOTLASER1 laser_type start_angle field_of_view angular_resolution maximum_range accuracy
// remission_mode num_readings r_.. num_remissions rem_.. laser_x laser_y laser_theta robot_x
// robot_y robot_theta laser_tv laser_rv forward_safety_dist side_safety_dist turn_axis +
// timestamps.
CarmenLaser read_robotlaser(RecordFields& fields) {
  CarmenLaser record;
  record.flaser = false;
  core::Scan& scan = record.scan;
  fields.next_number({"laser_type"});
  scan.angle0 = fields.next_within({"start_angle"}, kMaxScanAngleRadians, "radians");
  const double field_of_view = fields.next_positive({"field_of_view"});
  scan.dangle = fields.next_positive({"angular_resolution"});
  scan.max_range = fields.next_max_range({"maximum_range"});
  fields.next_number({"accuracy"});
  fields.next_number({"remission_mode"});
  const std::size_t count = fields.next_beam_count({"num_readings"});
  // Writers put n = fov / res beams, or one more to include both ends.
  const double steps = std::round(field_of_view / scan.dangle);
  const double beams = static_cast<double>(count);
  if (beams != steps && beams != steps + 1.0) {
    fields.fail({"num_readings"},
                printed("%zu readings do not fit field_of_view %g / angular_resolution %g = %.0f "
                        "steps (expected %.0f or %.0f readings)",
                        count, field_of_view, scan.dangle, steps, steps, steps + 1.0));
  }
  scan.ranges = fields.next_ranges(count);
  const std::size_t remissions = fields.next_count({"num_remissions"});
  for (std::size_t i = 0; i < remissions; ++i) fields.next_number({"rem_", i});
  record.laser = fields.next_pose("laser_x", "laser_y", "laser_theta");
  scan.robot = fields.next_pose("robot_x", "robot_y", "robot_theta");
  for (const char* field :
       {"laser_tv", "laser_rv", "forward_safety_dist", "side_safety_dist", "turn_axis"}) {
    fields.next_number({field});
  }
  scan.t = read_carmen_timestamps(fields);
  return record;
}

core::OdometryRecord read_carmen_odometry(RecordFields& fields) {
  core::OdometryRecord record;
  record.pose = fields.next_pose("x", "y", "theta");
  for (const char* velocity : {"tv", "rv", "accel"}) fields.next_number({velocity});
  record.t = read_carmen_timestamps(fields);
  return record;
}

// The laser pose seen from the robot pose, its angle in (-pi, pi].
core::Pose2 laser_seen_from_robot(const CarmenLaser& record) {
  core::Pose2 mount = core::relative(record.scan.robot, record.laser);
  mount.theta = core::wrap_angle(mount.theta);
  return mount;
}

bool same_mount(const core::Pose2& a, const core::Pose2& b) {
  return std::abs(a.x - b.x) <= kMountTolerance && std::abs(a.y - b.y) <= kMountTolerance &&
         std::abs(core::wrap_angle(a.theta - b.theta)) <= kMountTolerance;
}

// One mount for the log (the rule is in log_io.hpp).
core::Pose2 carmen_mount(const std::vector<CarmenLaser>& records, const CarmenParams& params) {
  const core::Pose2 first = laser_seen_from_robot(records.front());
  const bool constant = std::ranges::all_of(records, [&](const CarmenLaser& record) {
    return same_mount(laser_seen_from_robot(record), first);
  });
  if (constant) return first;
  return params.has_mount() ? params.mount() : core::Pose2{};
}

// The largest FLASER reading if it is a saturation value: repeated at least kMinSaturationCount
// times and more often than all readings within kSaturationBand below it together (a far wall
// spreads over neighbouring values, a saturated sensor writes one).
std::optional<double> flaser_saturation_value(const std::vector<CarmenLaser>& records) {
  double largest = 0.0;
  for (const CarmenLaser& record : records) {
    if (!record.flaser) continue;
    for (const double r : record.scan.ranges) {
      if (std::isfinite(r) && r > largest) largest = r;
    }
  }
  if (!(largest > 0.0)) return std::nullopt;
  const double band = largest * (1.0 - kSaturationBand);
  std::size_t at_largest = 0, below = 0;
  for (const CarmenLaser& record : records) {
    if (!record.flaser) continue;
    for (const double r : record.scan.ranges) {
      if (r == largest) {
        ++at_largest;
      } else if (r >= band && r < largest) {
        ++below;
      }
    }
  }
  if (at_largest >= kMinSaturationCount && at_largest > below) return largest;
  return std::nullopt;
}

// Sorts records by t, keeping the order of equal times; returns how many changed position.
template <class Record>
std::size_t sort_by_time(std::vector<Record>& records) {
  std::vector<std::size_t> order(records.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::ranges::stable_sort(order, {}, [&](std::size_t i) { return records[i].t; });
  std::size_t moved = 0;
  for (std::size_t i = 0; i < order.size(); ++i) moved += order[i] != i ? 1 : 0;
  if (moved == 0) return 0;
  std::vector<Record> sorted;
  sorted.reserve(records.size());
  for (const std::size_t i : order) sorted.push_back(std::move(records[i]));
  records = std::move(sorted);
  return moved;
}

core::Log parse_carmen_log(const fs::path& file, std::string_view text,
                           std::optional<double> max_range, SkippedRecords* skipped) {
  if (max_range && (!std::isfinite(*max_range) || !(*max_range > 0.0))) {
    throw std::invalid_argument("CARMEN max_range must be a positive finite number of metres");
  }
  std::vector<CarmenLaser> lasers;
  core::Log log;
  CarmenParams params;
  TimeOrder laser_order("laser"), odometry_order("ODOM");
  RecordLines lines(text);
  while (const std::optional<Line> line = lines.next()) {
    RecordFields fields(file, *line);
    const std::string_view keyword = fields.keyword();
    if (keyword == "FLASER" || keyword == "ROBOTLASER1") {
      lasers.push_back(keyword == "FLASER" ? read_flaser(fields) : read_robotlaser(fields));
      laser_order.check(fields, lasers.back().scan.t);
    } else if (keyword == "ODOM") {
      log.odometry.push_back(read_carmen_odometry(fields));
      odometry_order.check(fields, log.odometry.back().t);
    } else {
      if (keyword == "PARAM") read_carmen_param(fields, params);
      if (skipped != nullptr) ++(*skipped)[std::string(keyword)];
    }
  }
  if (lasers.empty()) require_scans(file, log, "FLASER or ROBOTLASER1");

  const double flaser_max_range =
      max_range                ? *max_range
      : params.front_laser_max ? *params.front_laser_max
                               : flaser_saturation_value(lasers).value_or(kCarmenDefaultMaxRange);
  const core::Pose2 mount = carmen_mount(lasers, params);
  if (!(std::hypot(mount.x, mount.y) <= kMaxMountMetres))
    throw InputError(file, 0, "laser pose",
                     "every laser record puts the laser " +
                         printed("%.4g", std::hypot(mount.x, mount.y)) +
                         " m from its robot pose, past the plausible " +
                         format_number(kMaxMountMetres) + " m of a sensor mount");
  log.scans.reserve(lasers.size());
  for (CarmenLaser& record : lasers) {
    if (record.flaser) record.scan.max_range = flaser_max_range;
    record.scan.sensor_mount = mount;
    log.scans.push_back(std::move(record.scan));
  }
  log.reordered_scans = sort_by_time(log.scans);
  sort_by_time(log.odometry);
  return log;
}

// ---- format detection ----

// Message types that open CARMEN logs. Anything else unknown is read as the project format, which
// reports it on its line instead of skipping the whole file as unknown CARMEN records.
bool is_carmen_keyword(std::string_view keyword) {
  static constexpr std::string_view kKeywords[] = {
      "PARAM",     "SYNC",      "FLASER",        "TRUEPOS",     "RAWLASER1",
      "RAWLASER2", "RAWLASER3", "RAWLASER4",     "ROBOTLASER1", "ROBOTLASER2",
      "NMEAGGA",   "NMEARMC",   "POSITIONLASER", "SONAR"};
  return std::ranges::find(kKeywords, keyword) != std::end(kKeywords);
}

bool is_carmen_log(const fs::path& file, std::string_view text) {
  RecordLines lines(text);
  const std::optional<Line> first = lines.next();
  if (!first) return false;
  const RecordFields fields(file, *first);
  // Both formats have ODOM: the project's carries 4 numbers, CARMEN's 9 fields.
  constexpr std::size_t kIntgridOdometryFields = 4;
  if (fields.keyword() == "ODOM") return fields.remaining_count() != kIntgridOdometryFields;
  return is_carmen_keyword(fields.keyword());
}

// ---- writing ----

void append_number(std::string& out, double value) {
  out += ' ';
  out += format_number(value);
}

void append_pose(std::string& out, const core::Pose2& pose) {
  append_number(out, pose.x);
  append_number(out, pose.y);
  append_number(out, pose.theta);
}

void append_scan(std::string& out, const core::Scan& scan) {
  out += "RLASER ";
  out += std::to_string(scan.ranges.size());
  append_number(out, scan.angle0);
  append_number(out, scan.dangle);
  append_number(out, scan.max_range);
  for (const double range : scan.ranges) append_number(out, range);
  append_pose(out, scan.robot);
  append_pose(out, scan.sensor_mount);
  append_number(out, scan.t);
  out += '\n';
}

void append_odometry(std::string& out, const core::OdometryRecord& record) {
  out += "ODOM";
  append_pose(out, record.pose);
  append_number(out, record.t);
  out += '\n';
}

void check_writable(const core::Log& log) {
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const std::size_t count = log.scans[i].ranges.size();
    if (count == 0 || count > kMaxBeamsPerScan) {
      throw std::invalid_argument("scan " + std::to_string(i) + " has " + std::to_string(count) +
                                  " ranges; a log record holds 1 to " +
                                  std::to_string(kMaxBeamsPerScan));
    }
  }
}

// Odometry goes first on equal times, as in the recorded logs.
std::string format_intgrid_log(const core::Log& log) {
  std::string out;
  std::size_t scan = 0, odometry = 0;
  while (scan < log.scans.size() || odometry < log.odometry.size()) {
    const bool odometry_next =
        odometry < log.odometry.size() &&
        (scan == log.scans.size() || log.odometry[odometry].t <= log.scans[scan].t);
    if (odometry_next) {
      append_odometry(out, log.odometry[odometry++]);
    } else {
      append_scan(out, log.scans[scan++]);
    }
  }
  return out;
}

}  // namespace

core::Log read_log(const fs::path& file, SkippedRecords* skipped) {
  const std::string text = read_input_file(file);
  if (is_carmen_log(file, text)) {
    return parse_carmen_log(file, text, std::nullopt, skipped);
  }
  return parse_intgrid_log(file, text);
}

core::Log read_intgrid_log(const fs::path& file) {
  return parse_intgrid_log(file, read_input_file(file));
}

core::Log read_carmen_log(const fs::path& file, std::optional<double> max_range,
                          SkippedRecords* skipped) {
  return parse_carmen_log(file, read_input_file(file), max_range, skipped);
}

void write_log(const fs::path& file, const core::Log& log) {
  check_writable(log);
  write_file_atomically(file, format_intgrid_log(log));
}

}  // namespace intgrid::io
