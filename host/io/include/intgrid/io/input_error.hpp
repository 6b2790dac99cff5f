// The one exception every reader throws for bad input: it names the file, the line and the
// field, so a user can go straight to the problem.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace intgrid::io {

class InputError : public std::runtime_error {
 public:
  // line is 1-based; 0 means the problem is not on one line (e.g. a missing file).
  // what() is "FILE:LINE: FIELD: MESSAGE", or "FILE: FIELD: MESSAGE" when line is 0; FILE is
  // printable(file) (a file name may hold any byte but '/' and NUL), MESSAGE is kept to one line
  // (control bytes as \xNN) of at most about 400 bytes.
  InputError(std::filesystem::path file, std::size_t line, std::string field, std::string message);

  const std::filesystem::path& file() const noexcept { return file_; }
  std::size_t line() const noexcept { return line_; }
  const std::string& field() const noexcept { return field_; }
  const std::string& message() const noexcept { return message_; }

 private:
  std::filesystem::path file_;
  std::size_t line_;
  std::string field_;
  std::string message_;
};

// text with its control bytes as \xNN: a file name as error messages show it.
std::string printable(std::string_view text);

// Raw input quoted for an error message: in double quotes, bytes other than printable ASCII as
// \xNN, cut after `max_chars` characters with "..." (a damaged file must not flood a terminal).
std::string quote_input(std::string_view text, std::size_t max_chars = 32);

}  // namespace intgrid::io
