// Helpers shared by the host I/O tests: scratch directories and InputError expectations.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <system_error>

#include "data_dir.hpp"
#include "intgrid/core/grid.hpp"
#include "intgrid/io/input_error.hpp"

namespace intgrid::test {

namespace fs = std::filesystem;

// The Freiburg benchmark logs (not bundled): INTGRID_BENCHMARK_DIR, else ../shared/data/benchmark
// beside the checkout.
inline fs::path benchmark_dir() {
  const char* dir = std::getenv("INTGRID_BENCHMARK_DIR");
  return dir != nullptr && *dir != '\0' ? fs::path(dir)
                                        : fs::path(data_dir()) / "../../shared/data/benchmark";
}

// The message of a benchmark test that cannot run.
inline std::string absent(const fs::path& file) {
  return file.string() + " is absent: set INTGRID_BENCHMARK_DIR to the folder holding the " +
         "Freiburg benchmark's intel.clf and aces.clf (and their .relations)";
}

// A fresh directory under the system temporary directory, removed with its content at scope exit.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "intgrid_host_test_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const fs::path& path() const { return path_; }
  fs::path operator/(std::string_view name) const { return path_ / name; }

  // Writes content (bytes as given, no newline translation) to name; returns its path.
  fs::path write(std::string_view name, std::string_view content) const {
    const fs::path file = path_ / name;
    std::ofstream out(file, std::ios::binary);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    if (!out) throw std::runtime_error("cannot write test file " + file.string());
    return file;
  }

  std::size_t entry_count() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(path_), {}));
  }

 private:
  fs::path path_;
};

// The id of a process that has ended (a child reaped at once): what a writer killed mid-run
// leaves in its staging names.
inline pid_t dead_pid() {
  const pid_t child = ::fork();
  if (child < 0) throw std::system_error(errno, std::generic_category(), "fork");
  if (child == 0) ::_exit(0);
  if (::waitpid(child, nullptr, 0) != child)
    throw std::system_error(errno, std::generic_category(), "waitpid");
  return child;
}

inline std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs action, which must throw an InputError for file, line and field, and checks that the
// one-line message names all three. Returns the error's message part for further checks.
template <class Action>
std::string expect_input_error(Action&& action, const fs::path& file, std::size_t line,
                               std::string_view field) {
  try {
    action();
  } catch (const io::InputError& error) {
    EXPECT_EQ(error.file(), file);
    EXPECT_EQ(error.line(), line);
    EXPECT_EQ(error.field(), field);
    std::string expected_prefix = file.string();
    if (line != 0) expected_prefix += ":" + std::to_string(line);
    expected_prefix += ": " + std::string(field) + ": ";
    EXPECT_EQ(std::string(error.what()).rfind(expected_prefix, 0), 0u)
        << "what(): " << error.what() << "\nexpected prefix: " << expected_prefix;
    return error.message();
  }
  ADD_FAILURE() << "expected an InputError for " << file << " line " << line << " field " << field;
  return {};
}

// A map read back must keep the written geometry bit for bit.
inline void expect_same_geometry(const core::GridGeometry& a, const core::GridGeometry& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.resolution, b.resolution);
  EXPECT_EQ(a.origin_x, b.origin_x);
  EXPECT_EQ(a.origin_y, b.origin_y);
}

}  // namespace intgrid::test
