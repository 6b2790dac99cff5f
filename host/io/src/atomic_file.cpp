#include "intgrid/io/atomic_file.hpp"

#include "staging_names.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
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
