#include "intgrid/io/input_error.hpp"

#include <utility>

namespace intgrid::io {
namespace {

std::string describe(const std::filesystem::path& file, std::size_t line, const std::string& field,
                     const std::string& message) {
  std::string text = file.string();
  if (line != 0) {
    text += ':';
    text += std::to_string(line);
  }
  text += ": ";
  text += field;
  text += ": ";
  text += message;
  return text;
}

}  // namespace

std::string quote_input(std::string_view text, std::size_t max_chars) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string quoted = "\"";
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (i == max_chars) {
      quoted += "...";
      break;
    }
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte >= 0x20 && byte < 0x7f && byte != '"' && byte != '\\') {
      quoted += static_cast<char>(byte);
    } else {
      quoted += "\\x";
      quoted += kHex[byte >> 4];
      quoted += kHex[byte & 0xf];
    }
  }
  return quoted + "\"";
}

InputError::InputError(std::filesystem::path file, std::size_t line, std::string field,
                       std::string message)
    : std::runtime_error(describe(file, line, field, message)),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)),
      message_(std::move(message)) {}

}  // namespace intgrid::io
