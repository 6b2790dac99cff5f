// Atomic output files: complete or absent, never half written.
#include "intgrid/io/atomic_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <ostream>
#include <stdexcept>
#include <string>

#include "test_support.hpp"

using namespace intgrid::core;

using namespace intgrid::io;

namespace intgrid {
namespace {

using test::TempDir;
using ::testing::HasSubstr;

TEST(AtomicFile, CommitWritesTheContent) {
  const TempDir dir;
  const auto file = dir / "out.txt";
  write_file_atomically(file, [](std::ostream& out) { out << "hello\n"; });
  EXPECT_EQ(test::read_bytes(file), "hello\n");
  EXPECT_EQ(dir.entry_count(), 1u);
}

TEST(AtomicFile, TemporaryFileSitsBesideTheTarget) {
  const TempDir dir;
  AtomicFile file(dir / "out.txt");
  EXPECT_EQ(file.temporary_path().parent_path(), dir.path());
  EXPECT_THAT(file.temporary_path().filename().string(), HasSubstr("out.txt.tmp."));
  EXPECT_TRUE(std::filesystem::exists(file.temporary_path()));
  EXPECT_FALSE(std::filesystem::exists(dir / "out.txt")) << "nothing under the final name yet";
}

TEST(AtomicFile, WriterThrowingMidwayLeavesNoFile) {
  const TempDir dir;
  const auto file = dir / "out.txt";
  EXPECT_THROW(write_file_atomically(file,
                                     [](std::ostream& out) {
                                       out << "first half\n";
                                       throw std::runtime_error("writer failed");
                                     }),
               std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(file));
  EXPECT_EQ(dir.entry_count(), 0u) << "the temporary file is removed too";
}

TEST(AtomicFile, WriterThrowingMidwayKeepsThePreviousFile) {
  const TempDir dir;
  const auto file = dir.write("out.txt", "old content\n");
  EXPECT_THROW(write_file_atomically(file,
                                     [](std::ostream& out) {
                                       out << "new";
                                       throw std::runtime_error("writer failed");
                                     }),
               std::runtime_error);
  EXPECT_EQ(test::read_bytes(file), "old content\n");
  EXPECT_EQ(dir.entry_count(), 1u);
}

TEST(AtomicFile, UncommittedFileIsDiscarded) {
  const TempDir dir;
  {
    AtomicFile file(dir / "out.txt");
    file.stream() << "never committed";
  }
  EXPECT_EQ(dir.entry_count(), 0u);
}

// A run killed while writing leaves NAME.tmp.<pid>.<n>: the next write of NAME removes it once
// that process is gone, and keeps a live process's (another run writing the same output) and
// other outputs' leftovers.
TEST(AtomicFile, TheNextWriteRemovesWhatAKilledWriterLeft) {
  const TempDir dir;
  const std::string dead = std::to_string(test::dead_pid()), live = std::to_string(::getppid());
  dir.write("out.txt.tmp." + dead + ".0", "half");
  dir.write("out.txt.tmp." + dead + ".17", "half");
  dir.write("out.txt.tmp." + live + ".0", "being written");
  dir.write("other.txt.tmp." + dead + ".0", "another output's");
  dir.write("out.txt.tmp.notapid", "not ours");
  write_file_atomically(dir / "out.txt", "done\n");
  EXPECT_EQ(test::read_bytes(dir / "out.txt"), "done\n");
  EXPECT_FALSE(std::filesystem::exists(dir / ("out.txt.tmp." + dead + ".0")));
  EXPECT_FALSE(std::filesystem::exists(dir / ("out.txt.tmp." + dead + ".17")));
  EXPECT_TRUE(std::filesystem::exists(dir / ("out.txt.tmp." + live + ".0")));
  EXPECT_TRUE(std::filesystem::exists(dir / ("other.txt.tmp." + dead + ".0")));
  EXPECT_TRUE(std::filesystem::exists(dir / "out.txt.tmp.notapid"));
}

TEST(AtomicFile, MissingDirectoryIsAnErrorNamingThePath) {
  const TempDir dir;
  const auto file = dir / "no_such_dir" / "out.txt";
  try {
    write_file_atomically(file, std::string_view("content"));
    ADD_FAILURE() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_THAT(error.what(), HasSubstr(file.string()));
    EXPECT_THAT(error.what(), HasSubstr("No such file or directory"));
  }
}

// Lowers the file size limit of this process, so writes fail as on a full disk (EFBIG instead of
// ENOSPC), and ignores the SIGXFSZ that would otherwise kill the test.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &saved_limit_);
    saved_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_limit_;
    limit.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_limit_);
    std::signal(SIGXFSZ, saved_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_limit_{};
  void (*saved_handler_)(int) = nullptr;
};

TEST(AtomicFile, FailedWriteIsAnErrorNamingThePathAndLeavesNoFile) {
  const TempDir dir;
  const auto file = dir / "big.bin";
  const std::string content(1 << 20, 'x');
  try {
    const FileSizeLimit limit(4096);
    write_file_atomically(file, content);
    ADD_FAILURE() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_THAT(error.what(), HasSubstr(file.string()));
    EXPECT_THAT(error.what(), HasSubstr("File too large"));
  }
  EXPECT_EQ(dir.entry_count(), 0u);
}

TEST(AtomicFile, FailedRenameOntoDirectoryIsAnError) {
  const TempDir dir;
  std::filesystem::create_directory(dir / "taken");
  std::filesystem::create_directory(dir / "taken" / "inside");
  EXPECT_THROW(write_file_atomically(dir / "taken", std::string_view("content")),
               std::runtime_error);
  EXPECT_EQ(dir.entry_count(), 1u) << "only the directory, no temporary file";
}

}  // namespace
}  // namespace intgrid
