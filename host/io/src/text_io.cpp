#include "intgrid/io/text_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <type_traits>

#include "intgrid/io/input_error.hpp"

namespace intgrid::io {

std::string printed(const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  std::va_list again;
  va_copy(again, args);
  std::string text(static_cast<std::size_t>(std::vsnprintf(nullptr, 0, format, args)), '\0');
  va_end(args);
  std::vsnprintf(text.data(), text.size() + 1, format, again);
  va_end(again);
  return text;
}
namespace {

[[noreturn]] void throw_unreadable(const std::filesystem::path& file, const char* what, int error) {
  throw InputError(file, 0, "file", std::string(what) + ": " + std::strerror(error));
}

// Closes a POSIX file descriptor on every path out of read_input_file.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() { ::close(fd_); }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

// POSIX calls rather than ifstream: they give errno for the message and refuse directories.
std::string read_input_file(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw_unreadable(file, "cannot open", errno);
  const FileDescriptor guard(fd);
  struct stat status {};
  if (::fstat(fd, &status) != 0) throw_unreadable(file, "cannot read", errno);
  if (S_ISDIR(status.st_mode)) throw_unreadable(file, "cannot open", EISDIR);
  // A device or a pipe may never end (/dev/zero): only regular files, and no larger than the limit.
  if (!S_ISREG(status.st_mode))
    throw InputError(file, 0, "file", "is not a regular file (a device, pipe or socket)");
  const auto too_large = [&] {
    throw InputError(file, 0, "file",
                     "is larger than " + std::to_string(kMaxInputFileBytes >> 20) +
                         " MiB, the limit of an input file");
  };
  if (static_cast<std::uintmax_t>(status.st_size) > kMaxInputFileBytes) too_large();

  std::string content;
  content.reserve(static_cast<std::size_t>(status.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t count = ::read(fd, buffer, sizeof buffer);
    if (count == 0) return content;
    if (count < 0) {
      if (errno == EINTR) continue;
      throw_unreadable(file, "cannot read", errno);
    }
    if (content.size() + static_cast<std::size_t>(count) > kMaxInputFileBytes) too_large();
    content.append(buffer, static_cast<std::size_t>(count));
  }
}

std::string FieldName::str() const {
  std::string text(base_);
  if (index_) text += std::to_string(*index_);
  return text;
}

template <class T>
T parse_number(std::string_view token, const std::filesystem::path& file, std::size_t line,
               const FieldName& field) {
  std::string_view digits = token;
  // from_chars rejects '+', which other tools write; "+-1" must stay an error.
  if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+') {
    digits.remove_prefix(1);
  }
  T value{};
  const char* const end = digits.data() + digits.size();
  const auto [stop, error] = std::from_chars(digits.data(), end, value);
  if (error != std::errc{} || stop != end) {
    const char* const kind = std::is_integral_v<T> ? "an integer" : "a number";
    throw InputError(file, line, field.str(), "cannot parse " + quote_input(token) + " as " + kind);
  }
  return value;
}

template double parse_number<double>(std::string_view, const std::filesystem::path&, std::size_t,
                                     const FieldName&);
template long long parse_number<long long>(std::string_view, const std::filesystem::path&,
                                           std::size_t, const FieldName&);

std::string format_number(double value) {
  char digits[32];
  // Without a precision, to_chars picks the shortest form that round-trips.
  const auto [end, error] = std::to_chars(digits, digits + sizeof digits, value);
  return std::string(digits, end);
}

}  // namespace intgrid::io
