#include "host/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

namespace intgrid {
namespace {

[[noreturn]] void throw_write_error(const std::filesystem::path& target, const std::string& reason) {
  throw std::runtime_error("cannot write " + target.string() + ": " + reason);
}

// Unique per process and per call, so concurrent writers of one target never share a file.
std::filesystem::path temporary_path_for(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path temporary = target;
  temporary += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  return temporary;
}

// Without this a crash just after the rename could leave an empty file under the final name on
// file systems that delay allocation (ext4).
void sync_to_disk(const std::filesystem::path& file, const std::filesystem::path& target) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw_write_error(target, std::strerror(errno));
  const bool synced = ::fsync(fd) == 0;
  const int sync_error = errno;
  ::close(fd);
  if (!synced) throw_write_error(target, std::strerror(sync_error));
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target)
    : target_(std::move(target)), temporary_(temporary_path_for(target_)) {
  errno = 0;
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) throw_write_error(target_, errno != 0 ? std::strerror(errno) : "cannot create file");
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void AtomicFile::commit() {
  errno = 0;
  out_.flush();
  out_.close();
  if (!out_) throw_write_error(target_, errno != 0 ? std::strerror(errno) : "write failed");
  sync_to_disk(temporary_, target_);
  std::error_code error;
  std::filesystem::rename(temporary_, target_, error);
  if (error) throw_write_error(target_, error.message());
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  AtomicFile file(path);
  write(file.stream());
  file.commit();
}

}  // namespace intgrid
