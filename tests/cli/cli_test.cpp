// `intgrid ism`, `resolution`, `map` and `figure`: outputs, and one clear error line with exit
// status 2 for every bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cli_fixture.hpp"
#include "data_dir.hpp"

namespace {

using namespace intgrid::cli_test;

TEST_F(Cli, IsmPrintsOneRowPerCellWithIndices) {
  const CliRun r = run("ism --sigma 0.02 --cell 0.05 --z 1.0 --length 2 --bits 8 --eps 0.05");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.rfind("k,d,p,index\n1,0.050000,", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 41);
}

TEST_F(Cli, ResolutionPrintsCellAndWorstCase) {
  const CliRun r = run("resolution --sigma 0.02 --pmax 0.9 --json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("\"worst_case_pmax\""), std::string::npos);
  EXPECT_NE(r.output.find("\"cell_for_worst_case\": null"), std::string::npos) << r.output;
}

TEST_F(Cli, MapWritesRosMapAndPngAndCountsInvalidReadings) {
  const fs::path log = write("good.log", "RLASER 4 -0.5 0.3 10 1.0 nan -1 2.0" + kScanTail +
                                             "RLASER 4 -0.5 0.3 10 1.5 0 12 2.5" + kScanTail);
  const CliRun r = run("map --log " + log.string() + " --out " + (dir_ / "out").string() +
                       " --cell 0.05 --json");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"map.yaml", "map.pgm", "map.png"})
    EXPECT_TRUE(fs::exists(dir_ / "out" / f)) << f;
  EXPECT_NE(r.output.find("\"not_finite\": 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"negative\": 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"at_or_over_max_range\": 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"zero\": 1"), std::string::npos) << r.output;
}

TEST_F(Cli, TruncatedLogLineNamesFileLineAndField) {
  const fs::path log = write("bad.log", "RLASER 4 -0.5 0.3 10 1.0 1.0 1.0 1.0" + kScanTail +
                                            "RLASER 4 -0.5 0.3 10 1.0 1.0\n");
  expect_error(
      run("map --log " + log.string() + " --out " + (dir_ / "out").string() + " --cell 0.05"),
      log.string() + ":2: r_2");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "map.pgm"));
}

TEST_F(Cli, UnparsableNumberNamesFileLineAndField) {
  const fs::path log = write("bad.log", "RLASER 4 -0.5 0.3 10 1.0 1.0 x1 1.0" + kScanTail);
  expect_error(
      run("map --log " + log.string() + " --out " + (dir_ / "out").string() + " --cell 0.05"),
      log.string() + ":1: r_2");
}

TEST_F(Cli, MissingFileIsNamed) {
  expect_error(run("map --log " + (dir_ / "nope.log").string() + " --out " + (dir_ / "o").string() +
                   " --cell 0.05"),
               (dir_ / "nope.log").string());
}

// Two scans 3 km apart: a 112-byte log whose 5 cm map would hold 3.6e9 cells (about 47 GB).
// The estimate is made before the grid is allocated: refused at once, naming --cell, and under a
// limit that holds the smaller map of a log 3 km long and 2 m wide (about 77 MB), refused below
// it and made above it.
TEST_F(Cli, MapOverTheMemoryLimitIsRefusedNamingTheOption) {
  const std::string far =
      "RLASER 4 -0.5 0.3 10 1.0 1.0 1.0 1.0 0 0 0 0 0 0 1.0\n"
      "RLASER 4 -0.5 0.3 10 1.0 1.0 1.0 1.0 3000 ";
  const fs::path square = write("square.log", far + "3000 0 0 0 0 2.0\n");
  const fs::path strip = write("strip.log", far + "2 0 0 0 0 2.0\n");
  const std::string out = " --out " + (dir_ / "o").string() + " --cell 0.05";
  CliRun r = run("map --log " + square.string() + out + " --max-memory 16000");
  expect_error(r, "--cell: a grid of 60060 x 60058 cells");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("more than the memory limit of 16.0 GB (--max-memory)"),
            std::string::npos);
  r = run("map --log " + strip.string() + out + " --max-memory 50");
  expect_error(r, "--cell: a grid of 60060 x 98 cells");
  EXPECT_EQ(r.status, 2);
  EXPECT_FALSE(fs::exists(dir_ / "o" / "map.yaml"));
  r = run("map --log " + strip.string() + out + " --max-memory 200");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "o" / "map.yaml"));
}

// An ISM spread of 8e9 m (--sigma 1e9) is refused naming --sigma, not std::bad_alloc; a
// growth of sigma with range that makes it large names --k-d; --max-memory takes a positive
// finite number of megabytes from 1 on.
TEST_F(Cli, IsmOverTheMemoryLimitIsRefusedNamingTheModelOption) {
  const fs::path log = write("l.log", "RLASER 4 -0.5 0.3 10 1.0 1.0 1.0 1.0" + kScanTail);
  const std::string args = "map --log " + log.string() + " --out " + (dir_ / "o").string() +
                           " --cell 0.05 --max-memory 16000";
  for (const char* arith : {"int", "float"}) {
    CliRun r = run(args + " --arith " + arith + " --sigma 1e9");
    expect_error(r, "--sigma: the ISM of the log's longest reading (1 m, spread over 8 sigma");
    EXPECT_EQ(r.status, 2);
    r = run(args + " --arith " + arith + " --k-d 1e9");
    expect_error(r, "--k-d: the ISM of the log's longest reading");
    EXPECT_EQ(r.status, 2);
  }
  for (const char* bad : {"0.5", "-1", "nan", "inf", "lots"}) {
    const CliRun r = run("map --log " + log.string() + " --out " + (dir_ / "o").string() +
                         " --cell 0.05 --max-memory " + bad);
    expect_error(r, "--max-memory");
    EXPECT_EQ(r.status, 2);
  }
}

// --max-memory is one option: the same help, default and range in every command that has it
// (globloc had its own, 1000 MB by default whatever the machine).
TEST_F(Cli, MaxMemoryIsTheSameOptionInEveryCommand) {
  const auto option_help = [](const std::string& command) {
    const CliRun r = run(command + " --help");
    EXPECT_EQ(r.status, 0) << command << r.output;
    const std::size_t start = r.output.find("--max-memory");
    if (start == std::string::npos) return std::string("absent");
    const std::size_t end = r.output.find("\n  -", start);
    std::string text;  // the option's help with every run of white space as one space
    for (const char c : r.output.substr(start, end - start))
      if (!std::isspace(static_cast<unsigned char>(c)))
        text += c;
      else if (!text.empty() && text.back() != ' ')
        text += ' ';
    return text;
  };
  const std::string map = option_help("map");
  EXPECT_NE(map.find("3/4 of this machine's"), std::string::npos) << map;
  for (const char* command : {"slam", "globloc"}) EXPECT_EQ(option_help(command), map) << command;
}

TEST_F(Cli, PgmSizeDisagreeingWithHeaderIsNamed) {
  write("m.pgm", std::string("P5\n4 4\n255\n") + std::string(10, '\xff'));
  const fs::path yaml = write("m.yaml",
                              "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  expect_error(run("compare --map " + yaml.string() + " --reference " + yaml.string()), "pixels");
}

// A CARMEN log whose second FLASER keyword was damaged: its line is skipped, as CARMEN records
// the pipeline does not use are, and the count shows on stderr and in the JSON.
TEST_F(Cli, SkippedCarmenRecordsAreCountedAndShown) {
  std::string beams = " 181";
  for (int i = 0; i < 181; ++i) beams += " 1.5";
  beams += " 1 2 0 1 2 0 ";
  const fs::path log = write("damaged.clf",
                             "PARAM robot_front_laser_max 50.0 nohost 0.0\n"
                             "FLASER" +
                                 beams +
                                 "1000.0 h 0.0\n"
                                 "FLXSER" +
                                 beams +
                                 "1001.0 h 0.0\n"
                                 "FLASER" +
                                 beams + "1002.0 h 0.0\n");
  const CliRun r =
      run("map --json --cell 0.1 --log " + log.string() + " --out " + (dir_ / "o").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(log.string() + ": skipped records: \"FLXSER\" 1, \"PARAM\" 1\n"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("\"FLXSER\": 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"scans\": 2"), std::string::npos) << r.output;
}

TEST_F(Cli, NegativeResolutionInMapYamlIsNamed) {
  write("m.pgm", std::string("P5\n2 2\n255\n") + std::string(4, '\xff'));
  const fs::path yaml = write("m.yaml",
                              "image: m.pgm\nresolution: -0.05\norigin: [0, 0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  expect_error(run("compare --map " + yaml.string() + " --reference " + yaml.string()),
               "resolution");
}

TEST_F(Cli, NegativeResolutionOrSigmaOnTheCommandLineIsRefused) {
  const fs::path log = write("good.log", "RLASER 4 -0.5 0.3 10 1.0 1.0 1.0 1.0" + kScanTail);
  const std::string base = "map --log " + log.string() + " --out " + (dir_ / "o").string();
  CliRun r = run(base + " --cell -0.05");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--cell"), std::string::npos) << r.output;
  // The old name still works, and the error names the documented one.
  r = run(base + " --res -0.05");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--cell"), std::string::npos) << r.output;
  r = run(base + " --cell 0.05 --sigma -1");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--sigma"), std::string::npos) << r.output;
  r = run("ism --sigma -0.02 --cell 0.05 --z 1 --length 2");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--sigma"), std::string::npos) << r.output;
}

TEST_F(Cli, LargeFovIsmPrintsOneRowPerPolarCellOneBased) {
  const CliRun r = run("ism --fov 30 --bins 16 --rings 40 --sectors 4 --cell 0.05 --z 1.0");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::vector<std::string> lines = lines_of(r.output);
  ASSERT_EQ(lines.size(), 1u + 40 * 16);
  EXPECT_EQ(lines[0], "ring,bin,p");
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> f = fields_of(lines[i]);
    ASSERT_EQ(f.size(), 3u) << lines[i];
    EXPECT_EQ(std::stoi(f[0]), static_cast<int>((i - 1) / 16 + 1)) << lines[i];
    EXPECT_EQ(std::stoi(f[1]), static_cast<int>((i - 1) % 16 + 1)) << lines[i];
    const double p = std::stod(f[2]);
    EXPECT_TRUE(p >= 0.0 && p <= 1.0) << lines[i];
  }
}

TEST_F(Cli, IntegerArithmeticAddsTheKernelsIndexColumn) {
  const CliRun r = run("ism --fov 30 --z 0.8 --arith int --bits 6 --eps 0.1");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::vector<std::string> lines = lines_of(r.output);
  ASSERT_EQ(lines.size(), 1u + 40 * 16);
  EXPECT_EQ(lines[0], "ring,bin,p,index");
  int free = 0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> f = fields_of(lines[i]);
    ASSERT_EQ(f.size(), 4u) << lines[i];
    std::size_t used = 0;
    const int index = std::stoi(f[3], &used);
    EXPECT_EQ(used, f[3].size()) << lines[i];
    EXPECT_TRUE(index >= -31 && index <= 31) << lines[i];  // 6 bits
    free += index < 0 ? 1 : 0;
  }
  EXPECT_GT(free, 0);
}

TEST_F(Cli, LargeFovIsmWritesAPng) {
  const fs::path png = dir_ / "ism.png";
  const CliRun r = run("ism --fov 45 --bins 12 --sectors 3 --z 1.2 --png " + png.string());
  ASSERT_EQ(r.status, 0) << r.output;
  expect_png(png);
}

TEST_F(Cli, KernelAgreementHasNoCellFurtherThanOneStep) {
  CliRun r = run("ism --fov 30 --agreement 300 --seed 7");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("readings: 342 (300 drawn with seed 7, 42 at the edges)"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("further off: 0\n"), std::string::npos) << r.output;
  r = run("ism --fov 20 --bins 24 --sectors 8 --rings 30 --agreement 100 --json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("\"further\": 0,"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"readings\": 132,"), std::string::npos) << r.output;
}

TEST_F(Cli, FiguresWriteTheirPngsAndNumbers) {
  CliRun r = run("figure ns-sweep --z 0.9 --out " + (dir_ / "sweep.png").string());
  ASSERT_EQ(r.status, 0) << r.output;
  expect_png(dir_ / "sweep.png");
  std::ifstream csv(dir_ / "sweep.csv");
  const std::string csv_text{std::istreambuf_iterator<char>(csv), std::istreambuf_iterator<char>()};
  const std::vector<std::string> lines = lines_of(csv_text);
  ASSERT_EQ(lines.size(), 1u + 5 * 40 * 30);
  EXPECT_EQ(lines[0], "ns,ring,bin,p");
  EXPECT_EQ(lines[1].rfind("30,1,1,", 0), 0u) << lines[1];
  EXPECT_EQ(lines.back().rfind("10,40,30,", 0), 0u) << lines.back();

  r = run("figure fusion --out " + (dir_ / "fusion.png").string());
  ASSERT_EQ(r.status, 0) << r.output;
  expect_png(dir_ / "fusion.png");
  std::ifstream json(dir_ / "fusion.json");
  const std::string summary{std::istreambuf_iterator<char>(json), std::istreambuf_iterator<char>()};
  for (const char* key : {"\"fused_double\"", "\"fused_seps\"", "\"informed\"", "\"max_p\""})
    EXPECT_NE(summary.find(key), std::string::npos) << key;
}

TEST_F(Cli, FigureRefusesAFileThatIsNoPng) {
  expect_error(run("figure fusion --out " + (dir_ / "fusion.jpg").string()), ".png");
  EXPECT_FALSE(fs::exists(dir_ / "fusion.jpg"));
  expect_error(run("figure ns-sweep --z -1 --out " + (dir_ / "s.png").string()), "--z");
  EXPECT_FALSE(fs::exists(dir_ / "s.png"));
}

TEST_F(Cli, InvalidLargeFovConfigurationsAreNamedAndWriteNoPng) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--bins 16 --sectors 5", "--bins: 16 is no multiple of --sectors 5"},
      {"--bins 16 --sectors 32", "--sectors: 32 exceeds --bins 16"},
      {"--bins 128 --sectors 128", "--sectors: must be a whole number in 1..64"},
      {"--bins 64 --sectors 32 --arith int", "kernel"},
      {"--rings 0", "--rings"},
      {"--rings -3", "--rings"},
      {"--bins 0", "--bins"},
      {"--sectors 0", "--sectors"},
      {"--cell 0", "--cell"},
      {"--cell -0.05", "--cell"},
      {"--sigma 0", "--sigma"},
      {"--sigma0 0", "--sigma"},  // the old name of --sigma with --fov
      {"--k-theta -1", "--k-theta"},
  };
  const fs::path png = dir_ / "bad.png";
  for (const auto& [options, keyword] : cases) {
    SCOPED_TRACE(options);
    const CliRun r = run("ism --fov 30 --z 1 " + options + " --png " + png.string());
    expect_error(r, keyword);
    EXPECT_EQ(r.status, 2);
    EXPECT_FALSE(fs::exists(png));
  }
  for (const char* fov : {"0", "180", "-10", "200"}) {
    SCOPED_TRACE(fov);
    expect_error(run(std::string("ism --z 1 --fov ") + fov + " --png " + png.string()), "--fov");
    EXPECT_FALSE(fs::exists(png));
  }
  for (const char* z : {"nan", "-0.5", "inf"}) {
    for (const char* arith : {"float", "int"}) {
      SCOPED_TRACE(std::string(z) + " " + arith);
      expect_error(run(std::string("ism --fov 30 --arith ") + arith + " --z " + z + " --png " +
                       png.string()),
                   "--z");
      EXPECT_FALSE(fs::exists(png));
    }
  }
  expect_error(run("ism --fov 30 --agreement 10 --bins 64 --sectors 32"), "kernel");
}

TEST_F(Cli, LogWithoutAnyValidReadingIsAnError) {
  const fs::path log = write("dead.log", "RLASER 4 -0.5 0.3 10 0 0 nan 11" + kScanTail);
  expect_error(
      run("map --log " + log.string() + " --out " + (dir_ / "o").string() + " --cell 0.05"),
      "no scan holds a valid reading");
}

}  // namespace
