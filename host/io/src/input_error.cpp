#include "intgrid/io/input_error.hpp"

#include <string_view>
#include <utility>

namespace intgrid::io {
namespace {

// At most this many bytes of a message: room for a sentence and a quoted value, not for a
// library's message that embeds a damaged file's bytes.
constexpr std::size_t kMaxMessageBytes = 400;

// Appends byte as \xNN.
void append_hex_escape(std::string& out, unsigned char byte) {
  static constexpr char kHex[] = "0123456789abcdef";
  out += "\\x";
  out += kHex[byte >> 4];
  out += kHex[byte & 0xf];
}

// c as it is, or as \xNN if it is a control byte.
void append_printable(std::string& out, char c) {
  const auto byte = static_cast<unsigned char>(c);
  if (byte < 0x20 || byte == 0x7f)
    append_hex_escape(out, byte);
  else
    out += c;
}

// The message on one line of printable text, whoever wrote it: control bytes (a library's
// message may carry the input's raw newlines or escapes) as \xNN, cut with "..." past
// kMaxMessageBytes.
std::string one_line(std::string_view message) {
  std::string out;
  for (const char c : message) {
    if (out.size() >= kMaxMessageBytes) return out + "...";
    append_printable(out, c);
  }
  return out;
}

std::string describe(const std::filesystem::path& file, std::size_t line, const std::string& field,
                     const std::string& message) {
  std::string text = printable(file.string());
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

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) append_printable(out, c);
  return out;
}

std::string quote_input(std::string_view text, std::size_t max_chars) {
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
      append_hex_escape(quoted, byte);
    }
  }
  return quoted + "\"";
}

InputError::InputError(std::filesystem::path file, std::size_t line, std::string field,
                       std::string message)
    : std::runtime_error(describe(file, line, field, one_line(message))),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)),
      message_(one_line(message)) {}

}  // namespace intgrid::io
