// Text helpers shared by the readers and writers: loading an input file whole, parsing numbers
// with errors reported as InputError, and writing numbers so that they read back exactly.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace intgrid::io {

// printf into a std::string, for the commands' tables and messages.
[[gnu::format(printf, 1, 2)]] std::string printed(const char* format, ...);

// The largest input file the readers take: 2 GiB (the Freiburg benchmark's logs are 8 and 16 MB).
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{2} << 30;

// The whole content of a file. A missing or unreadable file, one that is not a regular file or
// one larger than kMaxInputFileBytes is an InputError with field "file".
std::string read_input_file(const std::filesystem::path& file);

// A field name for error messages. An index is appended ("r_" and 17 make "r_17") only when an
// error needs the text, so hot loops over beams build no strings.
class FieldName {
 public:
  // Implicit, so that a plain field is passed as just "theta".
  FieldName(const char* name) : base_(name) {}
  FieldName(std::string_view name) : base_(name) {}
  FieldName(std::string_view base, std::size_t index) : base_(base), index_(index) {}

  std::string str() const;

 private:
  std::string_view base_;
  std::optional<std::size_t> index_;
};

// Parses token, which must be exactly one number (std::from_chars: no locale; "nan", "-nan" and
// "inf" are numbers; a leading '+' is accepted), or throws an InputError naming file, line and
// field. T is double or long long.
template <class T>
T parse_number(std::string_view token, const std::filesystem::path& file, std::size_t line,
               const FieldName& field);

// The shortest text that parses back to exactly value ("0.05", "1137834225.713386", "nan").
std::string format_number(double value);

}  // namespace intgrid::io
