#include "intgrid/io/relations_io.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/text_io.hpp"

namespace intgrid::io {
namespace {

namespace fs = std::filesystem;

// '\r' counts as a blank, so lines of CRLF files parse like LF ones.
constexpr std::string_view kBlanks = " \t\r\v\f";

constexpr std::array<const char*, 8> kRelationFields = {"t1", "t2",   "x",     "y",
                                                        "z",  "roll", "pitch", "yaw"};
constexpr std::array<const char*, 4> kPoseFields = {"t", "x", "y", "theta"};

// The next blank-separated token of rest, consumed; nothing at the line's end.
std::optional<std::string_view> take_token(std::string_view& rest) {
  const std::size_t begin = rest.find_first_not_of(kBlanks);
  if (begin == std::string_view::npos) return std::nullopt;
  const std::size_t end = rest.find_first_of(kBlanks, begin);
  const std::string_view token = rest.substr(begin, end - begin);
  rest.remove_prefix(end == std::string_view::npos ? rest.size() : end);
  return token;
}

// One line of finite numbers, exactly the named fields; `record` names the line's form in
// messages ("a relation is t1 t2 x y z roll pitch yaw").
template <std::size_t N>
std::array<double, N> parse_fields(const fs::path& file, std::size_t line, std::string_view text,
                                   const std::array<const char*, N>& fields,
                                   const std::string& record) {
  std::array<double, N> values{};
  for (std::size_t i = 0; i < N; ++i) {
    const std::optional<std::string_view> token = take_token(text);
    if (!token)
      throw InputError(file, line, fields[i],
                       "missing: the line ends before this field (" + record + ")");
    values[i] = parse_number<double>(*token, file, line, fields[i]);
    if (!std::isfinite(values[i]))
      throw InputError(file, line, fields[i],
                       "must be a finite number, got " + std::string(*token));
  }
  if (const std::optional<std::string_view> extra = take_token(text)) {
    std::size_t count = 1;
    while (take_token(text)) ++count;
    throw InputError(file, line, fields[N - 1],
                     std::to_string(count) + " unexpected field(s) after " + fields[N - 1] +
                         ", starting with " + quote_input(*extra));
  }
  return values;
}

// Calls parse(line number, text) for every line that is neither blank nor a '#' comment.
template <class Parse>
void for_each_record(const std::string& content, Parse&& parse) {
  std::string_view rest = content;
  std::size_t number = 0;
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    const std::string_view text = rest.substr(0, end);
    rest.remove_prefix(end == std::string_view::npos ? rest.size() : end + 1);
    ++number;
    const std::size_t first = text.find_first_not_of(kBlanks);
    if (first == std::string_view::npos || text[first] == '#') continue;
    parse(number, text);
  }
}

}  // namespace

std::vector<RelationRecord> read_relations(const fs::path& file) {
  std::vector<RelationRecord> records;
  for_each_record(read_input_file(file), [&](std::size_t line, std::string_view text) {
    const auto v =
        parse_fields(file, line, text, kRelationFields, "a relation is t1 t2 x y z roll pitch yaw");
    records.push_back({line, {v[0], v[1], {v[2], v[3], v[7]}}});
  });
  if (records.empty())
    throw InputError(file, 0, "relations",
                     "the file holds no relation (one a line: t1 t2 x y z roll pitch yaw)");
  return records;
}

std::vector<core::TimedPose> read_trajectory(const fs::path& file) {
  std::vector<core::TimedPose> poses;
  for_each_record(read_input_file(file), [&](std::size_t line, std::string_view text) {
    const auto v = parse_fields(file, line, text, kPoseFields, "a pose is t x y theta");
    if (!poses.empty() && v[0] < poses.back().t)
      throw InputError(file, line, "t", "earlier than the line before: poses in time order");
    poses.push_back({v[0], {v[1], v[2], v[3]}});
  });
  if (poses.empty())
    throw InputError(file, 0, "poses", "the file holds no pose (one a line: t x y theta)");
  return poses;
}

std::vector<core::Relation> relations_of(std::span<const RelationRecord> records) {
  std::vector<core::Relation> out;
  out.reserve(records.size());
  for (const RelationRecord& r : records) out.push_back(r.relation);
  return out;
}

void write_tum_trajectory(const fs::path& file, std::span<const core::TimedPose> trajectory) {
  write_file_atomically(file, [&](std::ostream& out) {
    for (const core::TimedPose& p : trajectory) {
      const double half = core::wrap_angle(p.pose.theta) / 2.0;
      out << format_number(p.t) << ' ' << format_number(p.pose.x) << ' ' << format_number(p.pose.y)
          << " 0 0 0 " << format_number(std::sin(half)) << ' ' << format_number(std::cos(half))
          << '\n';
    }
  });
}

}  // namespace intgrid::io
