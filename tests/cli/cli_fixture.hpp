// What the tests of the `intgrid` command share: running it, a fresh folder a test, and the
// checks of its outputs.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "command_run.hpp"

namespace intgrid::cli_test {

namespace fs = std::filesystem;

using CliRun = intgrid::test::CommandRun;

inline CliRun run(const std::string& arguments) {
  return intgrid::test::run_command(std::string(INTGRID_CLI) + " " + arguments);
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("intgrid_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& content) {
    std::ofstream(dir_ / name, std::ios::binary) << content;
    return dir_ / name;
  }
  fs::path dir_;
};

inline const std::string kScanTail = " 0 0 0 0.1 0 0 100.5\n";

inline void expect_error(const CliRun& r, const std::string& must_contain) {
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(must_contain), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_EQ(r.output.find("terminate"), std::string::npos) << r.output;
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

// A PNG file: the signature, then the IHDR chunk with a positive width and height.
inline void expect_png(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_GE(bytes.size(), 24u) << file;
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << file;
  EXPECT_EQ(bytes.substr(12, 4), "IHDR") << file;
  const auto big_endian = [&](std::size_t at) {
    std::uint32_t value = 0;
    for (std::size_t i = 0; i < 4; ++i)
      value = value << 8 | static_cast<std::uint8_t>(bytes[at + i]);
    return value;
  };
  EXPECT_GT(big_endian(16), 0u) << file;
  EXPECT_GT(big_endian(20), 0u) << file;
}

inline std::string file_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The JSON object under "key" in metrics.json's text, up to its closing brace (no nesting).
inline std::string json_object(const std::string& text, const std::string& key) {
  const std::size_t at = text.find("\"" + key + "\": {");
  if (at == std::string::npos) return {};
  return text.substr(at, text.find('}', at) - at + 1);
}

// `intgrid globloc` and `figure globloc-sweeps`: a 4 x 3 m room at 10 cm with two blocks that
// break its symmetry.
inline fs::path write_globloc_room(const fs::path& dir) {
  std::string pgm = "P5\n40 30\n255\n";
  for (int row = 0; row < 30; ++row)
    for (int x = 0; x < 40; ++x) {
      const int y = 29 - row;  // PGM rows run from the top
      const bool wall = x == 0 || y == 0 || x == 39 || y == 29;
      const bool block =
          (x >= 8 && x <= 13 && y >= 5 && y <= 9) || (x >= 28 && x <= 30 && y >= 18 && y <= 25);
      pgm += wall || block ? '\0' : '\xfe';
    }
  std::ofstream(dir / "room.pgm", std::ios::binary) << pgm;
  std::ofstream(dir / "room.yaml") << "image: room.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n"
                                      "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  return dir / "room.yaml";
}

}  // namespace intgrid::cli_test
