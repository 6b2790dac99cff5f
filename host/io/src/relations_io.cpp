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

constexpr std::array<const char*, 8> kFields = {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"};

// The next blank-separated token of rest, consumed; nothing at the line's end.
std::optional<std::string_view> take_token(std::string_view& rest) {
  const std::size_t begin = rest.find_first_not_of(kBlanks);
  if (begin == std::string_view::npos) return std::nullopt;
  const std::size_t end = rest.find_first_of(kBlanks, begin);
  const std::string_view token = rest.substr(begin, end - begin);
  rest.remove_prefix(end == std::string_view::npos ? rest.size() : end);
  return token;
}

slam::Relation parse_relation(const fs::path& file, std::size_t line, std::string_view text) {
  std::array<double, kFields.size()> values{};
  for (std::size_t i = 0; i < kFields.size(); ++i) {
    const std::optional<std::string_view> token = take_token(text);
    if (!token)
      throw InputError(file, line, kFields[i],
                       "missing: the line ends before this field (a relation is t1 t2 x y z roll "
                       "pitch yaw)");
    values[i] = parse_number<double>(*token, file, line, kFields[i]);
    if (!std::isfinite(values[i]))
      throw InputError(file, line, kFields[i],
                       "must be a finite number, got " + std::string(*token));
  }
  if (const std::optional<std::string_view> extra = take_token(text)) {
    std::size_t count = 1;
    while (take_token(text)) ++count;
    throw InputError(file, line, "yaw",
                     std::to_string(count) + " unexpected field(s) after yaw, starting with \"" +
                         std::string(*extra) + "\"");
  }
  return {values[0], values[1], {values[2], values[3], values[7]}};
}

}  // namespace

std::vector<RelationRecord> read_relations(const fs::path& file) {
  const std::string content = read_input_file(file);
  std::vector<RelationRecord> records;
  std::string_view rest = content;
  std::size_t number = 0;
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    const std::string_view text = rest.substr(0, end);
    rest.remove_prefix(end == std::string_view::npos ? rest.size() : end + 1);
    ++number;
    const std::size_t first = text.find_first_not_of(kBlanks);
    if (first == std::string_view::npos || text[first] == '#') continue;
    records.push_back({number, parse_relation(file, number, text)});
  }
  if (records.empty())
    throw InputError(file, 0, "relations",
                     "the file holds no relation (one a line: t1 t2 x y z roll pitch yaw)");
  return records;
}

std::vector<slam::Relation> relations_of(std::span<const RelationRecord> records) {
  std::vector<slam::Relation> out;
  out.reserve(records.size());
  for (const RelationRecord& r : records) out.push_back(r.relation);
  return out;
}

void write_tum_trajectory(const fs::path& file, std::span<const slam::TimedPose> trajectory) {
  write_file_atomically(file, [&](std::ostream& out) {
    for (const slam::TimedPose& p : trajectory) {
      const double half = core::wrap_angle(p.pose.theta) / 2.0;
      out << format_number(p.t) << ' ' << format_number(p.pose.x) << ' ' << format_number(p.pose.y)
          << " 0 0 0 " << format_number(std::sin(half)) << ' ' << format_number(std::cos(half))
          << '\n';
    }
  });
}

}  // namespace intgrid::io
