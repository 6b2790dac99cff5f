// Writing an output file so that readers only ever see the old file or the complete new one:
// the content goes to a temporary file in the same directory, which is renamed onto the final
// name only once it is completely written and on disk.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <string_view>

namespace intgrid::io {

class FileStreamBuffer;

class AtomicFile {
 public:
  // Creates "NAME.tmp.<pid>.<n>" beside target, after removing those of NAME that writers
  // killed before they could left (their process no longer exists). Throws std::runtime_error
  // naming target if it cannot be created (e.g. the directory does not exist).
  explicit AtomicFile(std::filesystem::path target);
  // Removes the temporary file unless commit() succeeded.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Binary stream onto the temporary file.
  std::ostream& stream() { return out_; }
  // Flushes the data to disk and renames the temporary file onto the target. Throws
  // std::runtime_error naming the target and the reason if any write failed (e.g. disk full).
  void commit();

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporary_path() const { return temporary_; }

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  int fd_ = -1;
  std::unique_ptr<FileStreamBuffer> buffer_;
  std::ostream out_;
  bool committed_ = false;
};

// Runs write on the stream of an AtomicFile for path and commits it; if write throws, path is
// left untouched and the exception propagates.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

// Writes content to path atomically.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace intgrid::io
