// What every fuzz target shares: the input as a file (the readers take paths, as the command
// gives them), and the invariants of a refusal: an InputError naming the file it was given, a
// field, and a message of bounded length (quoted input is cut).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "intgrid/io/input_error.hpp"

namespace intgrid::fuzz {

// A directory of this process's own, removed at exit.
inline const std::filesystem::path& work_dir() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("intgrid_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(work_dir(), ignored);
    });
    return d;
  }();
  return dir;
}

inline std::filesystem::path write_input(const std::string& name, std::string_view bytes) {
  const std::filesystem::path file = work_dir() / name;
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return file;
}

// A failed invariant: abort, which libFuzzer reports with the input that did it.
inline void require(bool holds) {
  if (!holds) std::abort();
}

// The refusal names the file the reader was given (or, with `any_file`, a file the input named,
// as a map YAML names its image), a field, and stays one short line.
inline void check_refusal(const io::InputError& e, const std::filesystem::path& file,
                          bool any_file = false) {
  require(e.file() == file || (any_file && !e.file().empty()));
  require(!e.field().empty());
  const std::string_view what = e.what();
  const std::string file_shown = io::printable(e.file().string());
  require(what.starts_with(file_shown));
  require(what.size() < 1024 + file_shown.size());
  require(what.find('\n') == std::string_view::npos);
}

}  // namespace intgrid::fuzz
