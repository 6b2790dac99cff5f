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

InputError::InputError(std::filesystem::path file, std::size_t line, std::string field,
                       std::string message)
    : std::runtime_error(describe(file, line, field, message)),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)),
      message_(std::move(message)) {}

}  // namespace intgrid::io
