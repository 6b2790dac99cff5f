// The shared number parsing and formatting, and the InputError message layout.
#include "intgrid/io/text_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "intgrid/io/input_error.hpp"
#include "test_support.hpp"

using namespace intgrid::core;

using namespace intgrid::io;

namespace intgrid {
namespace {

using test::expect_input_error;

const std::filesystem::path kFile = "some/dir/input.log";

double parse(std::string_view token) {
  return parse_number<double>(token, kFile, 1, "x");
}

TEST(InputError, WhatNamesFileLineFieldAndMessage) {
  const InputError error("some/dir/input.log", 17, "r_3", "cannot parse \"x\" as a number");
  EXPECT_STREQ(error.what(), "some/dir/input.log:17: r_3: cannot parse \"x\" as a number");
  EXPECT_EQ(error.file(), kFile);
  EXPECT_EQ(error.line(), 17u);
  EXPECT_EQ(error.field(), "r_3");
  EXPECT_EQ(error.message(), "cannot parse \"x\" as a number");
}

TEST(InputError, LineZeroIsLeftOut) {
  const InputError error("map.yaml", 0, "file", "cannot open: No such file or directory");
  EXPECT_STREQ(error.what(), "map.yaml: file: cannot open: No such file or directory");
}

// Whoever wrote the message (yaml-cpp's carry the input's raw bytes): one line, control bytes
// as \xNN, cut past 400 bytes (a message found by fuzzing the map reader broke the line).
TEST(InputError, TheMessageIsOnePrintableBoundedLine) {
  const InputError error("m.yaml", 4, "yaml", "unknown escape character: \n\x1b[2J");
  EXPECT_STREQ(error.what(), "m.yaml:4: yaml: unknown escape character: \\x0a\\x1b[2J");
  EXPECT_EQ(error.message(), "unknown escape character: \\x0a\\x1b[2J");
  const InputError long_one("m.yaml", 1, "yaml", std::string(5000, 'a'));
  EXPECT_EQ(long_one.message(), std::string(400, 'a') + "...");
}

// A file name may hold any byte but '/' and NUL: a name a log named (a ROS map's image) must not
// put a newline or a terminal escape into the message either.
TEST(InputError, TheFileNameIsShownPrintable) {
  const InputError error("dir/a\nb\x1b[2J.pgm", 3, "image", "cannot open");
  EXPECT_STREQ(error.what(), "dir/a\\x0ab\\x1b[2J.pgm:3: image: cannot open");
  EXPECT_EQ(error.file(), std::filesystem::path("dir/a\nb\x1b[2J.pgm"));
}

TEST(ParseNumber, AcceptsPlainNanInfinityAndPlusSign) {
  EXPECT_EQ(parse("1.25"), 1.25);
  EXPECT_EQ(parse("-3e-2"), -0.03);
  EXPECT_EQ(parse("+7"), 7.0);
  EXPECT_EQ(parse(".5"), 0.5);
  EXPECT_TRUE(std::isnan(parse("nan")));
  EXPECT_TRUE(std::isnan(parse("-nan")));
  EXPECT_EQ(parse("inf"), std::numeric_limits<double>::infinity());
  EXPECT_EQ(parse("-inf"), -std::numeric_limits<double>::infinity());
}

TEST(ParseNumber, RejectsJunkAndNamesTheIndexedField) {
  for (const char* token : {"", "1.5x", "abc", "+-1", "1,5", "1e999", "0x10"}) {
    SCOPED_TRACE(token);
    const std::string message = expect_input_error(
        [&] {
          parse_number<double>(token, kFile, 12, {"r_", 17});
        },
        kFile, 12, "r_17");
    EXPECT_EQ(message, "cannot parse \"" + std::string(token) + "\" as a number");
  }
}

TEST(QuoteInput, EscapesWhatIsNotPrintableAndCutsLongInput) {
  EXPECT_EQ(quote_input("FLASER"), "\"FLASER\"");
  EXPECT_EQ(quote_input(std::string_view("a\x01\n\"\\\xff", 6)), "\"a\\x01\\x0a\\x22\\x5c\\xff\"");
  const std::string long_input(600'000, '\x7f');  // a PGM header run into its pixels
  std::string expected = "\"";
  for (int i = 0; i < 32; ++i) expected += "\\x7f";
  expected += "...\"";
  EXPECT_EQ(quote_input(long_input), expected);
  EXPECT_EQ(quote_input("abcdefghij", 4), "\"abcd...\"");
  EXPECT_EQ(quote_input("abcd", 4), "\"abcd\"");
  // A token too long to show is cut in the parser's message too.
  const std::string message = expect_input_error(
      [&] { parse_number<double>(std::string(100, '9') + "x", kFile, 1, "r_0"); }, kFile, 1, "r_0");
  EXPECT_EQ(message, "cannot parse \"" + std::string(32, '9') + "...\" as a number");
}

// A device that never ends and a file past the limit are refused before they are read.
TEST(ReadInputFile, RefusesWhatIsNotARegularFileAndFilesPastTheLimit) {
  const auto message_of = [](const std::filesystem::path& file) {
    try {
      (void)read_input_file(file);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), file);
      EXPECT_EQ(e.field(), "file");
      return e.message();
    }
    ADD_FAILURE() << file << " was read";
    return std::string();
  };
  EXPECT_EQ(message_of("/dev/zero"), "is not a regular file (a device, pipe or socket)");
  const test::TempDir dir;
  const std::filesystem::path large = dir.path() / "large.log";
  std::ofstream(large).put('x');
  std::filesystem::resize_file(large, kMaxInputFileBytes + 1);  // sparse: no disk space taken
  EXPECT_EQ(message_of(large), "is larger than 2048 MiB, the limit of an input file");
  std::filesystem::resize_file(large, 3);
  EXPECT_EQ(read_input_file(large), std::string("x\0\0", 3));
}

TEST(ParseNumber, IntegersRejectFractions) {
  EXPECT_EQ(parse_number<long long>("361", kFile, 3, "n"), 361);
  const std::string message =
      expect_input_error([&] { parse_number<long long>("361.0", kFile, 3, "n"); }, kFile, 3, "n");
  EXPECT_EQ(message, "cannot parse \"361.0\" as an integer");
}

TEST(FormatNumber, IsShortAndReadsBackExactly) {
  EXPECT_EQ(format_number(0.05), "0.05");
  EXPECT_EQ(format_number(1137834225.713386), "1137834225.713386");
  EXPECT_EQ(format_number(-45.0), "-45");
  for (const double value : {1.0 / 3.0, -2e-300, 6.02214076e23, 0.1 + 0.2}) {
    EXPECT_EQ(parse(format_number(value)), value);
  }
  EXPECT_TRUE(std::isnan(parse(format_number(std::nan("")))));
}

}  // namespace
}  // namespace intgrid
