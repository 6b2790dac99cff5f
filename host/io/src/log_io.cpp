#include "intgrid/io/log_io.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string_view>
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

  core::Pose2 next_pose(std::string_view x, std::string_view y, std::string_view theta) {
    core::Pose2 pose;
    pose.x = next_finite({x});
    pose.y = next_finite({y});
    pose.theta = next_finite({theta});
    return pose;
  }

  std::size_t next_beam_count() {
    const FieldName field{"n"};
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
                         last_field_.str() + ", starting with \"" + std::string(*first_extra) +
                         "\"");
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
  const std::size_t count = fields.next_beam_count();
  scan.angle0 = fields.next_finite({"angle0"});
  scan.dangle = fields.next_finite({"dangle"});
  scan.max_range = fields.next_positive({"maxrange"});
  scan.ranges = fields.next_ranges(count);
  scan.robot = fields.next_pose("x", "y", "theta");
  scan.sensor_mount = fields.next_pose("sx", "sy", "stheta");
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
      fields.fail({"record type"}, "unknown record type \"" + std::string(fields.keyword()) +
                                       "\" (expected RLASER or ODOM)");
    }
  }
  require_scans(file, log, "RLASER");
  return log;
}

// ---- CARMEN ----

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

core::Scan read_carmen_scan(RecordFields& fields, double max_range) {
  core::Scan scan;
  const std::size_t count = fields.next_beam_count();
  if (count < 2) fields.fail({"n"}, "a FLASER scan needs at least 2 beams");
  scan.ranges = fields.next_ranges(count);
  const core::Pose2 laser = fields.next_pose("x", "y", "theta");
  scan.robot = fields.next_pose("odom_x", "odom_y", "odom_theta");
  scan.sensor_mount = core::relative(scan.robot, laser);
  // relative() leaves the heading difference unwrapped; a mount angle reads best in (-pi, pi].
  scan.sensor_mount.theta = std::remainder(scan.sensor_mount.theta, 2.0 * std::numbers::pi);
  scan.t = read_carmen_timestamps(fields);
  scan.angle0 = -std::numbers::pi / 2.0;
  scan.dangle = carmen_beam_step(count);
  scan.max_range = max_range;
  return scan;
}

core::OdometryRecord read_carmen_odometry(RecordFields& fields) {
  core::OdometryRecord record;
  record.pose = fields.next_pose("x", "y", "theta");
  for (const char* velocity : {"tv", "rv", "accel"}) fields.next_number({velocity});
  record.t = read_carmen_timestamps(fields);
  return record;
}

core::Log parse_carmen_log(const fs::path& file, std::string_view text, double max_range,
                           SkippedRecords* skipped) {
  if (!std::isfinite(max_range) || !(max_range > 0.0)) {
    throw std::invalid_argument("CARMEN max_range must be a positive finite number of metres");
  }
  core::Log log;
  RecordLines lines(text);
  while (const std::optional<Line> line = lines.next()) {
    RecordFields fields(file, *line);
    if (fields.keyword() == "FLASER") {
      log.scans.push_back(read_carmen_scan(fields, max_range));
    } else if (fields.keyword() == "ODOM") {
      log.odometry.push_back(read_carmen_odometry(fields));
    } else if (skipped != nullptr) {
      ++(*skipped)[std::string(fields.keyword())];
    }
  }
  require_scans(file, log, "FLASER");
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
    return parse_carmen_log(file, text, kCarmenDefaultMaxRange, skipped);
  }
  return parse_intgrid_log(file, text);
}

core::Log read_intgrid_log(const fs::path& file) {
  return parse_intgrid_log(file, read_input_file(file));
}

core::Log read_carmen_log(const fs::path& file, double max_range, SkippedRecords* skipped) {
  return parse_carmen_log(file, read_input_file(file), max_range, skipped);
}

void write_log(const fs::path& file, const core::Log& log) {
  check_writable(log);
  write_file_atomically(file, format_intgrid_log(log));
}

}  // namespace intgrid::io
