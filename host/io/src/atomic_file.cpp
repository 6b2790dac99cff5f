#include "intgrid/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <system_error>
#include <utility>

namespace intgrid::io {

// A write-only stream buffer on a POSIX file descriptor. Unlike std::filebuf it keeps the errno
// of the first failed write, so that the error can say why (no space, file too large, I/O).
class FileStreamBuffer : public std::streambuf {
 public:
  explicit FileStreamBuffer(int fd) : fd_(fd) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }

  // errno of the first failed write, 0 if none failed.
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!write_buffered()) return traits_type::eof();
    if (traits_type::eq_int_type(ch, traits_type::eof())) return traits_type::not_eof(ch);
    *pptr() = traits_type::to_char_type(ch);
    pbump(1);
    return ch;
  }

  int sync() override { return write_buffered() ? 0 : -1; }

 private:
  bool write_buffered() {
    const char* data = pbase();
    std::size_t size = static_cast<std::size_t>(pptr() - pbase());
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    while (size > 0 && error_ == 0) {
      const ssize_t written = ::write(fd_, data, size);
      if (written < 0) {
        if (errno != EINTR) error_ = errno;
        continue;
      }
      data += written;
      size -= static_cast<std::size_t>(written);
    }
    return error_ == 0;
  }

  int fd_;
  int error_ = 0;
  std::array<char, 1 << 16> buffer_{};
};

namespace {

[[noreturn]] void throw_write_error(const std::filesystem::path& target, int error) {
  throw std::runtime_error("cannot write " + target.string() + ": " + std::strerror(error));
}

// Unique per process and per call, so concurrent writers of one target never share a file.
std::filesystem::path temporary_path_for(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path temporary = target;
  temporary += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  return temporary;
}

// Removes the temporary files of target left by writers that were killed before they could:
// "NAME.tmp.<pid>.<n>" whose process no longer exists. A live process's are kept (another run
// may be writing the same output); a dead writer's pid taken by a new process keeps its file
// until that process ends.
void remove_leftovers_of_dead_writers(const std::filesystem::path& target) {
  const std::string prefix = target.filename().string() + ".tmp.";
  const std::filesystem::path directory =
      target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  std::error_code error;
  std::filesystem::directory_iterator entries(directory, error);
  if (error) return;  // the open below reports a directory that cannot be written
  for (const std::filesystem::directory_entry& entry : entries) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with(prefix)) continue;
    const char* first = name.data() + prefix.size();
    const char* last = name.data() + name.size();
    long long pid = 0;
    const auto [end, parsed] = std::from_chars(first, last, pid);
    if (parsed != std::errc() || end == last || *end != '.' || pid <= 0 || pid == ::getpid())
      continue;
    if (::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH)
      std::filesystem::remove(entry.path(), error);
  }
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target)
    : target_(std::move(target)), temporary_(temporary_path_for(target_)), out_(nullptr) {
  remove_leftovers_of_dead_writers(target_);
  fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd_ < 0) throw_write_error(target_, errno);
  buffer_ = std::make_unique<FileStreamBuffer>(fd_);
  out_.rdbuf(buffer_.get());
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (committed_) return;
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void AtomicFile::commit() {
  out_.flush();
  if (buffer_->error() != 0) throw_write_error(target_, buffer_->error());
  if (!out_) throw std::runtime_error("cannot write " + target_.string() + ": stream failed");
  // Without fsync a crash just after the rename could leave an empty file under the final name
  // on file systems that delay allocation (ext4).
  if (::fsync(fd_) != 0) throw_write_error(target_, errno);
  if (::close(std::exchange(fd_, -1)) != 0) throw_write_error(target_, errno);
  std::error_code error;
  std::filesystem::rename(temporary_, target_, error);
  if (error) throw_write_error(target_, error.value());
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  AtomicFile file(path);
  write(file.stream());
  file.commit();
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  write_file_atomically(path, [content](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

}  // namespace intgrid::io
