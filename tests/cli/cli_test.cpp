// The intgrid command end to end: outputs, and one clear error line with exit
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

#include "command_run.hpp"
#include "data_dir.hpp"

namespace {

namespace fs = std::filesystem;

using CliRun = intgrid::test::CommandRun;

CliRun run(const std::string& arguments) {
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

const std::string kScanTail = " 0 0 0 0.1 0 0 100.5\n";

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

void expect_error(const CliRun& r, const std::string& must_contain) {
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(must_contain), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_EQ(r.output.find("terminate"), std::string::npos) << r.output;
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

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

// A PNG file: the signature, then the IHDR chunk with a positive width and height.
void expect_png(const fs::path& file) {
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

// The demo prints the hardware kernels' summary from <data>/../hardware_report.json and
// puts it in summary.json under "hardware"; without the report it prints how to make one.
class CliDemo : public Cli {
 protected:
  // The bundled data in dir_/data, so that dir_ can hold a report beside it: the map linked, the
  // logs cut to their first 60 lines (30 scans of the raw log, 60 of the reference run), so that
  // the sanitized pass runs the whole demo too (a few seconds, not minutes).
  fs::path data() {
    constexpr std::size_t lines = 60;
    const fs::path d = dir_ / "data";
    const fs::path bundled = intgrid::test::data_dir();
    fs::create_directories(d);
    for (const char* f : {"malaga_telecom_map.yaml", "malaga_telecom_map.pgm"})
      fs::create_symlink(bundled / f, d / f);
    for (const char* f : {"malaga_telecom_loop_reference.log", "malaga_telecom_loop.log"}) {
      std::ifstream in(bundled / f);
      std::ofstream out(d / f);
      std::string line;
      for (std::size_t n = 0; n < lines && std::getline(in, line); ++n) out << line << '\n';
    }
    return d;
  }
  std::string summary_json() {
    std::ifstream in(dir_ / "out" / "summary.json");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
};

// One whole demo run, on the logs' first lines. Without a report the demo prints
// read_hardware_summary's hint line: HardwareSummary.MissingReportGivesTheHintLineNotAnError.
TEST_F(CliDemo, PrintsTheKernelsSummaryFromTheHardwareReport) {
  const fs::path d = data();
  std::ofstream(dir_ / "hardware_report.json") << R"({"date": "2026-11-25", "summary": [
    {"kernel": "index_fusion", "configuration": "B=8 LANES=1", "cycles_per_cell": 1.0,
     "cycles_per_cell_backpressure": 2.0, "latency_cycles": 1, "latency_cycles_backpressure": 3,
     "lut4": 44, "dff": 20, "bram": 0, "fmax_mhz": 164.0, "target_mhz": 80, "target_met": true}]})";
  const CliRun r = run("demo --data " + d.string() + " --out " + (dir_ / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("  index_fusion B=8 LANES=1: 1.000 cycles/cell, latency 1 cycles "
                          "(with back-pressure: 2.000, 3); 44 LUT4 / 20 DFF / 0 BRAM; Fmax "
                          "164.0 MHz vs 80 MHz target: met\n"),
            std::string::npos)
      << r.output;
  const std::string summary = summary_json();
  EXPECT_NE(summary.find("\"hardware\""), std::string::npos);
  EXPECT_NE(summary.find("\"fmax_mhz\": 164.0"), std::string::npos) << summary;
}

// `intgrid simulate`.

std::string file_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t records(const std::string& log, const std::string& type) {
  std::size_t n = 0;
  for (const std::string& line : lines_of(log)) n += line.rfind(type + " ", 0) == 0 ? 1 : 0;
  return n;
}

TEST_F(Cli, SimulateWritesEveryFileAndTheRequestedScans) {
  const fs::path out = dir_ / "sim";
  const CliRun r = run("simulate --out " + out.string() + " --scans 25 --obstacles 3 --seed 5");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"sim.log", "truth.log", "world.yaml", "world.pgm", "world.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  expect_png(out / "world.png");
  EXPECT_NE(r.output.find("\"scans\": 25"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"seed\": 5"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find((out / "sim.log").string()), std::string::npos) << r.output;
  // sim.log: a scan and an odometry record per step; truth.log: the scans alone.
  const std::string sim = file_text(out / "sim.log"), truth = file_text(out / "truth.log");
  EXPECT_EQ(records(sim, "RLASER"), 25u);
  EXPECT_EQ(records(sim, "ODOM"), 25u);
  EXPECT_EQ(records(truth, "RLASER"), 25u);
  EXPECT_EQ(records(truth, "ODOM"), 0u);
  // The project's reader takes both back: mapping them sees 25 scans of 361 readings.
  for (const char* log : {"sim.log", "truth.log"}) {
    const CliRun m = run("map --log " + (out / log).string() + " --out " + (dir_ / "map").string() +
                         " --cell 0.1 --json");
    ASSERT_EQ(m.status, 0) << m.output;
    EXPECT_NE(m.output.find("\"scans\": 25,"), std::string::npos) << m.output;
    EXPECT_NE(m.output.find("\"readings\": 9025,"), std::string::npos) << m.output;
  }
  // The world map reads back, and the true path of the default floorplan is within it.
  const CliRun c = run("compare --map " + (out / "world.yaml").string() + " --reference " +
                       (out / "world.yaml").string() + " --json");
  ASSERT_EQ(c.status, 0) << c.output;
  EXPECT_NE(c.output.find("\"ours_near_reference\": 1.0"), std::string::npos) << c.output;
}

TEST_F(Cli, SimulateIsByteIdenticalForTheSameSeed) {
  const std::string options = " --scans 30 --obstacles 4 --dropout 0.1 --contamination 0.05";
  ASSERT_EQ(run("simulate --out " + (dir_ / "a").string() + options + " --seed 9").status, 0);
  ASSERT_EQ(run("simulate --out " + (dir_ / "b").string() + options + " --seed 9").status, 0);
  ASSERT_EQ(run("simulate --out " + (dir_ / "c").string() + options + " --seed 10").status, 0);
  for (const char* f : {"sim.log", "truth.log", "world.pgm", "world.png"})
    EXPECT_EQ(file_text(dir_ / "a" / f), file_text(dir_ / "b" / f)) << f;
  EXPECT_NE(file_text(dir_ / "a" / "sim.log"), file_text(dir_ / "c" / "sim.log"));
}

// The map is the same, bit for bit, for every thread count, in both arithmetics (each thread
// fills its own band of rows: every cell takes the same fusions in the same order).
TEST_F(Cli, MapIsByteIdenticalForEveryThreadCount) {
  const fs::path log = dir_ / "sim" / "sim.log";
  ASSERT_EQ(run("simulate --out " + (dir_ / "sim").string() + " --scans 40 --seed 3").status, 0);
  for (const char* arith : {"int", "float"}) {
    std::string first;
    for (const int threads : {1, 2, 3, 7}) {
      const fs::path out = dir_ / (std::string(arith) + std::to_string(threads));
      const CliRun m =
          run("map --log " + log.string() + " --out " + out.string() + " --cell 0.05 --arith " +
              arith + " --threads " + std::to_string(threads));
      ASSERT_EQ(m.status, 0) << m.output;
      const std::string pgm = file_text(out / "map.pgm");
      if (first.empty()) first = pgm;
      EXPECT_EQ(pgm, first) << arith << ", " << threads << " threads";
    }
  }
}

TEST_F(Cli, SimulateOnAMapAlongAReferenceTrajectory) {
  // A 4 m square room map, and a reference log of three poses inside it.
  std::string pgm = "P5\n40 40\n255\n";
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) pgm += (x == 0 || y == 0 || x == 39 || y == 39) ? '\0' : '\xfe';
  write("room.pgm", pgm);
  const fs::path yaml = write("room.yaml",
                              "image: room.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const fs::path reference = write("ref.log",
                                   "RLASER 2 0 0.1 10 1 1 1 0.5 0 0 0 0 5\n"
                                   "RLASER 2 0 0.1 10 1 1 1.5 0.5 0.1 0 0 0 6\n"
                                   "RLASER 2 0 0.1 10 1 1 2 0.6 0.2 0 0 0 7\n");
  const fs::path out = dir_ / "out";
  CliRun r = run("simulate --out " + out.string() + " --world " + yaml.string() + " --trajectory " +
                 reference.string() + " --sensor cone --beams 8 --fov 40");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string truth = file_text(out / "truth.log");
  const std::vector<std::string> lines = lines_of(truth);
  ASSERT_EQ(lines.size(), 3u) << truth;
  // RLASER 8 angle0 dangle maxrange r_0..r_7 x y theta ...: the reference's poses.
  EXPECT_NE(lines[1].find(" 1.5 0.5 0.1 0 0 0 "), std::string::npos) << lines[1];
  EXPECT_EQ(lines[0].rfind("RLASER 8 0 0.7853981633974483 5 ", 0), 0u) << lines[0];
  // More scans than the reference holds.
  expect_error(run("simulate --out " + out.string() + " --world " + yaml.string() +
                   " --trajectory " + reference.string() + " --scans 5"),
               "--scans");
  // Random waypoints in the room.
  r = run("simulate --out " + out.string() + " --world " + yaml.string() + " --scans 50");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(records(file_text(out / "sim.log"), "RLASER"), 50u);
}

TEST_F(Cli, SimulateRefusesBadOptionsNamingThem) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--noise -1", "--noise"},
      {"--noise nan", "--noise"},
      {"--dropout 1.5", "--dropout"},
      {"--contamination -0.1", "--contamination"},
      {"--beams 0", "--beams"},
      {"--sensor radar", "--sensor"},
      {"--fov 0", "--fov"},
      {"--sensor cone --fov 180", "--fov"},
      {"--max-range 0", "--max-range"},
      {"--max-range inf", "--max-range"},
      {"--scans 0", "--scans"},
      {"--obstacles -2", "--obstacles"},
      {"--odometry-noise 0.1,0.1,0.1", "--odometry-noise"},
      {"--odometry-noise 0.1,-1,0.1,0.1", "--odometry-noise"},
      {"--cell 0", "--cell"},
      {"--cell 0.6", "--cell"},
      {"--seed -1", "--seed"},
      {"--speed 0", "--speed"},
      {"--large-obstacle -1", "--large-obstacle"},
      {"--world w.yaml --floorplan", "--floorplan"},
  };
  const fs::path out = dir_ / "out";
  for (const auto& [options, keyword] : cases) {
    SCOPED_TRACE(options);
    const CliRun r = run("simulate --out " + out.string() + " " + options);
    expect_error(r, keyword);
    EXPECT_EQ(r.status, 2);
    EXPECT_FALSE(fs::exists(out / "sim.log"));
  }
}

TEST_F(Cli, SimulateRefusesAWorldWithoutFreeSpace) {
  write("dark.pgm", std::string("P5\n10 10\n255\n") + std::string(100, '\0'));
  const fs::path yaml = write("dark.yaml",
                              "image: dark.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const fs::path out = dir_ / "out";
  CliRun r = run("simulate --out " + out.string() + " --world " + yaml.string());
  expect_error(r, yaml.string() + ": image: the map has no free cell");
  EXPECT_EQ(r.status, 2);
  EXPECT_FALSE(fs::exists(out / "sim.log"));
  r = run("simulate --out " + out.string() + " --world " + (dir_ / "missing.yaml").string());
  expect_error(r, (dir_ / "missing.yaml").string());
  EXPECT_EQ(r.status, 2);
}

// SLAM: a small log that moves, with one scan whose readings are all invalid.
const char* kSlamLog =
    "RLASER 5 -1 0.5 10 2 2.1 2.2 2.1 2 0 0 0 0 0 0 100\n"
    "ODOM 0.1 0 0 100.5\n"
    "RLASER 5 -1 0.5 10 0 nan -1 10 inf 0.1 0 0 0 0 0 101\n"
    "RLASER 5 -1 0.5 10 1.8 1.9 2 1.9 1.8 0.2 0 0 0 0 0 102\n";

TEST_F(Cli, SlamWritesTrajectoryMapAndMetricsAndCountsSkippedScans) {
  const CliRun r = run("slam --engine grid --log " + write("s.log", kSlamLog).string() + " --out " +
                       (dir_ / "out").string() + " --max-range 8");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"trajectory.txt", "map.yaml", "map.pgm", "map.png", "metrics.json"})
    EXPECT_TRUE(fs::exists(dir_ / "out" / f)) << f;
  std::ifstream trajectory(dir_ / "out" / "trajectory.txt");
  std::string line;
  std::vector<std::string> poses;
  while (std::getline(trajectory, line))
    if (!line.empty() && line[0] != '#') poses.push_back(line);
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(poses[1].substr(0, 4), "101 ");  // the log's timestamps
  EXPECT_NE(r.output.find("\"skipped_scans\": 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"unusable_readings\": 5"), std::string::npos) << r.output;
  for (const fs::directory_entry& e : fs::directory_iterator(dir_ / "out"))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

// Logs of a few bytes whose odometry wanders kilometres in steps under the 1 km a step may
// take: each engine's map is estimated from the odometry before SLAM runs and refused over
// --max-memory naming --cell (the submaps engine's 1.1e9-cell map and the grid engine's
// 3e9-cell square ask for about 29 and 116 GB); a square past the grid engine's 65535 cells a
// side names --cell too (it was an internal error, exit 1).
TEST_F(Cli, SlamMapOverTheMemoryLimitIsRefusedNamingTheOption) {
  const auto log_through = [&](const std::string& name, std::initializer_list<const char*> xy) {
    std::string text;
    int t = 0;
    for (const char* p : xy)
      text += "RLASER 4 -0.5 0.3 10 1.0 1.0 1.0 1.0 " + std::string(p) + " 0 0 0 0 " +
              std::to_string(++t) + "\n";
    return write(name, text);
  };
  const fs::path wander =
      log_through("wander.log", {"0 0", "900 0", "1800 0", "2700 0", "2700 900"});
  const std::string out = " --out " + (dir_ / "o").string();
  for (const char* engine : {"submaps", "grid"}) {
    const CliRun r =
        run("slam --log " + wander.string() + out + " --engine " + engine + " --max-memory 16000");
    expect_error(r, "--cell: a map of ");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("more than the memory limit of 16.0 GB (--max-memory)"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "o" / "trajectory.txt"));
  }
  const fs::path far = log_through("far.log", {"0 0", "900 0", "1800 0", "2700 0", "3600 0"});
  const CliRun r = run("slam --log " + far.string() + out + " --engine grid");
  expect_error(r, "--cell: a map of 0.1 m cells around the first pose of " + far.string());
  EXPECT_EQ(r.status, 2);
}

TEST_F(Cli, SlamRejectsEmptyMalformedAndOdometryFreeLogs) {
  const std::string out = " --out " + (dir_ / "out").string();
  CliRun r = run("slam --log " + write("empty.log", "").string() + out);
  EXPECT_EQ(r.status, 2);
  expect_error(r, "no scans");
  r = run("slam --log " + write("bad.log", "RLASER 2 0 1 10 1 x 0 0 0 0 0 0 5\n").string() + out);
  EXPECT_EQ(r.status, 2);
  expect_error(r, "bad.log:1: r_1");
  r = run(
      "slam --log " +
      write("still.log", "RLASER 2 0 1 10 1 1 0 0 0 0 0 0 5\nRLASER 2 0 1 10 1 1 0 0 0 0 0 0 6\n")
          .string() +
      out);
  EXPECT_EQ(r.status, 2);
  expect_error(r, "no odometry");
  r = run("slam --log " + write("s.log", kSlamLog).string() + out + " --cell 0.0125");
  EXPECT_EQ(r.status, 2);
  expect_error(r, "--cell: must be a whole number of millimetres");
  r = run("slam --engine grid --log " + write("s.log", kSlamLog).string() + out +
          " --window-cells 10");
  EXPECT_EQ(r.status, 2);
  expect_error(r, "--window-cells: must be odd");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "map.yaml"));
}

// The text of a file, whole.
std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The default engine is the submap SLAM: the same files, metrics.json with its counts and no
// E(sigma), and a summary line on stderr with its nodes and loop closures; --engine grid is the
// event-driven grid SLAM, as before.
TEST_F(Cli, SlamRunsTheSubmapEngineByDefaultAndTheGridEngineOnRequest) {
  const std::string log = " --log " + write("s.log", kSlamLog).string() + " --max-range 8";
  CliRun r = run("slam" + log + " --out " + (dir_ / "submaps").string());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"trajectory.txt", "map.yaml", "map.pgm", "map.png", "metrics.json"})
    EXPECT_TRUE(fs::exists(dir_ / "submaps" / f)) << f;
  std::string metrics = slurp(dir_ / "submaps" / "metrics.json");
  EXPECT_NE(metrics.find("\"engine\": \"submaps\""), std::string::npos) << metrics;
  for (const char* field :
       {"nodes", "submaps", "wide_searches", "unmatched_scans", "loop_searches", "loop_closures",
        "optimizations", "peak_pyramid_bytes", "scans", "readings", "unusable_readings",
        "reordered_scans", "seconds", "real_time_factor", "peak_memory_bytes"})
    EXPECT_NE(metrics.find("\"" + std::string(field) + "\": "), std::string::npos)
        << field << " in " << metrics;
  EXPECT_NE(metrics.find("\"scans\": 3,"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"unusable_readings\": 5,"), std::string::npos) << metrics;
  for (const char* field : {"e_sigma_m", "skipped_scans", "lambda"})
    EXPECT_EQ(metrics.find("\"" + std::string(field) + "\""), std::string::npos)
        << field << " in " << metrics;
  EXPECT_NE(r.output.find("slam (submaps): "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" node"), std::string::npos) << r.output;  // "2 nodes in 1 submap"
  EXPECT_NE(r.output.find(" loop closure"), std::string::npos) << r.output;
  std::istringstream lines(slurp(dir_ / "submaps" / "trajectory.txt"));
  std::size_t poses = 0;
  for (std::string line; std::getline(lines, line);) poses += !line.empty() && line[0] != '#';
  EXPECT_EQ(poses, 3u);

  r = run("slam" + log + " --engine grid --out " + (dir_ / "grid").string());
  ASSERT_EQ(r.status, 0) << r.output;
  metrics = slurp(dir_ / "grid" / "metrics.json");
  EXPECT_NE(metrics.find("\"engine\": \"grid\""), std::string::npos) << metrics;
  for (const char* field : {"e_sigma_m", "skipped_scans", "localizations", "mappings"})
    EXPECT_NE(metrics.find("\"" + std::string(field) + "\": "), std::string::npos)
        << field << " in " << metrics;
  EXPECT_EQ(metrics.find("\"loop_closures\""), std::string::npos) << metrics;
  EXPECT_NE(r.output.find("slam (grid): E(sigma) "), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "grid" / "map.png"));
}

// The options both engines have set the engine that runs: --cell 0.08 with either.
TEST_F(Cli, SlamSharedOptionsSetTheEngineThatRuns) {
  const std::string log = " --log " + write("s.log", kSlamLog).string() + " --max-range 8";
  CliRun r = run("slam" + log + " --cell 0.08 --sigma 0.07 --out " + (dir_ / "s").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::string metrics = slurp(dir_ / "s" / "metrics.json");
  EXPECT_NE(metrics.find("\"cell\": 0.08"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"sigma\": 0.07"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"max_range\": 8.0"), std::string::npos) << metrics;
  r = run("slam" + log + " --engine grid --cell 0.08 --out " + (dir_ / "g").string());
  ASSERT_EQ(r.status, 0) << r.output;
  metrics = slurp(dir_ / "g" / "metrics.json");
  EXPECT_NE(metrics.find("\"res\": 0.08"), std::string::npos) << metrics;
}

// A setting of the other engine, a bad submaps value, a value check_submap_slam_config refuses:
// exit 2, one line naming the flag (and, for another engine's setting, that engine), no output.
TEST_F(Cli, SlamRefusesTheOtherEnginesOptionsAndBadSubmapValues) {
  const std::string slam =
      "slam --log " + write("s.log", kSlamLog).string() + " --out " + (dir_ / "out").string() + " ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--lambda 2", "--lambda: a setting of --engine grid, not of --engine submaps"},
      {"--engine submaps --window-cells 11",
       "--window-cells: a setting of --engine grid, not of --engine submaps"},
      {"--motion-noise 0,0,0,0,0,0", "--motion-noise: a setting of --engine grid"},
      {"--engine grid --loop-window 1",
       "--loop-window: a setting of --engine submaps, not of --engine grid"},
      {"--engine grid --huber 2", "--huber: a setting of --engine submaps"},
      {"--engine grid --bits 8", "--bits: a setting of --engine submaps"},
      {"--engine gird", "--engine"},
      {"--loop-window -1", "--loop-window: must be >= 0, got -1"},
      {"--loop-min-score 0", "--loop-min-score"},
      {"--wide-below 1.5", "--wide-below"},
      {"--submap-scans 0", "--submap-scans"},
      {"--submap-rematch maybe", "--submap-rematch"},
      {"--threads 300", "--threads"},
      {"--engine grid --threads 2", "--threads: a setting of --engine submaps"},
      {"--engine grid --submap-rematch false", "--submap-rematch: a setting of --engine submaps"},
      {"--huber nan", "--huber"},
      {"--graph-iterations 2.5", "--graph-iterations"},
      {"--filter-degrees 200", "--filter-degrees: must be in [0, 180]"},
      {"--graph-iterations 5000", "--graph-iterations: must be 1..1000"},
      {"--headings 32", "--headings: must be a power of two"},
      {"--bits 9", "--bits: must be 2..8"},
      {"--cell 0.0125", "--cell: must be a whole number of millimetres"},
      {"--tracking-window 5", "--tracking-window: "},
  };
  for (const auto& [options, message] : cases) {
    SCOPED_TRACE(options);
    const CliRun r = run(slam + options);
    EXPECT_EQ(r.status, 2) << r.output;
    expect_error(r, message);
    EXPECT_NE(r.output.find("run 'intgrid slam --help'"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "metrics.json"));
  }
}

// --help: --engine, both defaults of a shared option, the submaps engine's options.
TEST_F(Cli, SlamHelpShowsBothEngines) {
  const CliRun r = run("slam --help");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* text : {"--engine submaps|grid=submaps", "(default: submaps ", ", grid ",
                           "--loop-window", "--tracking-window", "--graph-iterations", "--lambda"})
    EXPECT_NE(r.output.find(text), std::string::npos) << text << " in " << r.output;
}

// The JSON object under "key" in metrics.json's text, up to its closing brace (no nesting).
std::string json_object(const std::string& text, const std::string& key) {
  const std::size_t at = text.find("\"" + key + "\": {");
  if (at == std::string::npos) return {};
  return text.substr(at, text.find('}', at) - at + 1);
}

// --relations: relations between pairs of kSlamLog's scan times (100, 101, 102 s), one 5 ms off
// (within the benchmark's 0.01 s) and one to a time no scan has, scored for the SLAM and the
// raw odometry, each relation's error in relations.csv; --tum: one line a scan.
TEST_F(Cli, SlamScoresBenchmarkRelationsAndWritesATumTrajectory) {
  const fs::path relations = write("s.relations",
                                   "# t1 t2 x y z roll pitch yaw\n"
                                   "100 101 0.1 0 0 0 0 0\n"
                                   "101 102.005 0.1 0 0 0 0 0\n"
                                   "\n"
                                   "100 102 0.2 0 0 0 0 0.01\n"
                                   "100 103 0.3 0 0 0 0 0\n");
  const fs::path tum = dir_ / "trajectory.tum";
  const CliRun r =
      run("slam --log " + write("s.log", kSlamLog).string() + " --out " + (dir_ / "out").string() +
          " --max-range 8 --relations " + relations.string() + " --tum " + tum.string());
  ASSERT_EQ(r.status, 0) << r.output;
  // One line each (on stderr, so in any order with stdout's JSON).
  for (const char* line : {"relations: 3 matched, 1 unmatched; translation ",
                           "odometry relations: 3 matched, 1 unmatched; translation "})
    EXPECT_TRUE(r.output.rfind(line, 0) == 0 ||
                r.output.find("\n" + std::string(line)) != std::string::npos)
        << line << " in " << r.output;
  const std::string metrics = slurp(dir_ / "out" / "metrics.json");
  for (const char* key : {"relations", "odometry_relations"}) {
    const std::string object = json_object(metrics, key);
    ASSERT_FALSE(object.empty()) << key << " in " << metrics;
    EXPECT_NE(object.find("\"matched\": 3,"), std::string::npos) << object;
    EXPECT_NE(object.find("\"unmatched\": 1"), std::string::npos) << object;
    for (const char* field :
         {"trans_mean", "trans_std", "rot_mean_deg", "rot_std_deg", "trans_sq_mean", "trans_sq_std",
          "rot_sq_mean", "rot_sq_std", "trans_median", "rot_median_deg", "off", "off_fraction"})
      EXPECT_NE(object.find("\"" + std::string(field) + "\": "), std::string::npos)
          << field << " in " << object;
  }
  EXPECT_NE(metrics.find("\"relations_file\": \"" + relations.string() + "\""), std::string::npos);
  EXPECT_NE(metrics.find("\"relation_stretches\": ["), std::string::npos) << metrics;
  // relations.csv: each relation in the file's order with the SLAM's and the odometry's errors,
  // empty where it matched no scan; its matched rows' mean is the metrics' trans_mean.
  std::istringstream csv(slurp(dir_ / "out" / "relations.csv"));
  std::vector<std::string> rows;
  for (std::string line; std::getline(csv, line);) rows.push_back(line);
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0],
            "t1,t2,trans_error_m,rot_error_deg,off,odometry_trans_error_m,odometry_rot_error_deg");
  EXPECT_EQ(rows[1].rfind("100,101,", 0), 0u) << rows[1];
  EXPECT_EQ(rows[2].rfind("101,102.005,", 0), 0u) << rows[2];
  EXPECT_EQ(rows[4], "100,103,,,0,,") << rows[4];
  double sum = 0.0;
  for (std::size_t i = 1; i <= 3; ++i) sum += std::stod(rows[i].substr(rows[i].find(',', 4) + 1));
  const std::string slam_object = json_object(metrics, "relations");
  const std::size_t at = slam_object.find("\"trans_mean\": ");
  ASSERT_NE(at, std::string::npos) << slam_object;
  EXPECT_NEAR(std::stod(slam_object.substr(at + 14)), sum / 3.0, 1e-12);
  EXPECT_NE(metrics.find("\"reordered_scans\": 0"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"peak_memory_bytes\": "), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"real_time_factor\": "), std::string::npos) << metrics;

  std::istringstream lines(slurp(tum));
  std::vector<std::string> poses;
  for (std::string line; std::getline(lines, line);) poses.push_back(line);
  ASSERT_EQ(poses.size(), 3u) << slurp(tum);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(poses[i].substr(0, 4), std::to_string(100 + i) + " ") << poses[i];
    std::istringstream fields(poses[i]);
    EXPECT_EQ(std::distance(std::istream_iterator<std::string>(fields),
                            std::istream_iterator<std::string>()),
              8)
        << poses[i];
  }
  // trajectory.txt keeps its format: a comment, then t x y theta.
  const std::string trajectory = slurp(dir_ / "out" / "trajectory.txt");
  EXPECT_EQ(trajectory.rfind("# t x y theta", 0), 0u) << trajectory;
}

TEST_F(Cli, SlamRefusesRelationsThatMatchNoScanOrDoNotParse) {
  const std::string log = " --log " + write("s.log", kSlamLog).string();
  const std::string out = " --out " + (dir_ / "out").string();
  fs::path relations = write("other.relations",
                             "# for another log\n"
                             "\n"
                             "976052905.167303 976052911.885496 -0.05 -0.12 0 0 0 -1.68\n"
                             "100.02 101 0.1 0 0 0 0 0\n");
  CliRun r = run("slam" + log + out + " --relations " + relations.string());
  EXPECT_EQ(r.status, 2);
  expect_error(r, relations.string() +
                      ":3: t1: none of its 2 relations matches a scan of the log " +
                      (dir_ / "s.log").string() + " within 0.01 s");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "metrics.json"));

  relations = write("bad.relations", "100 101 0.1 0 0 0 0 0\n101 102 0.1 nan 0 0 0 0\n");
  r = run("slam" + log + out + " --relations " + relations.string());
  EXPECT_EQ(r.status, 2);
  expect_error(r, relations.string() + ":2: y: must be a finite number");

  relations = write("short.relations", "100 101 0.1 0 0 0 0\n");
  r = run("slam" + log + out + " --relations " + relations.string());
  EXPECT_EQ(r.status, 2);
  expect_error(r, relations.string() + ":1: yaw: missing");

  relations = write("empty.relations", "# nothing\n");
  r = run("slam" + log + out + " --relations " + relations.string());
  EXPECT_EQ(r.status, 2);
  expect_error(r, relations.string() + ": relations: the file holds no relation");

  r = run("slam" + log + out + " --relations " + (dir_ / "missing.relations").string());
  EXPECT_EQ(r.status, 2);
  expect_error(r, (dir_ / "missing.relations").string() + ": file: cannot open");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "map.yaml"));
}

// On a terminal (a pseudo-terminal from util-linux's `script`) slam's progress line shows the
// time left.
TEST_F(Cli, SlamProgressOnATerminalShowsTheTimeLeft) {
  if (std::system("command -v script > /dev/null 2>&1") != 0) GTEST_SKIP() << "no `script`";
  const std::string slam = std::string(INTGRID_CLI) + " slam --log " +
                           write("s.log", kSlamLog).string() + " --out " + (dir_ / "out").string() +
                           " --max-range 8 > /dev/null";
  const auto [status, output] = intgrid::test::run_command("script -qec '" + slam + "' /dev/null");
  if (status != 0) GTEST_SKIP() << "script failed: " << output;
  EXPECT_NE(output.find("SLAM (integer): 1/3 (33%), ETA "), std::string::npos) << output;
  EXPECT_NE(output.find("SLAM (integer): 3/3 (100%) in "), std::string::npos) << output;
}

// `figure slam-sweeps --quick`: three CSVs of one row per SLAM run (both arithmetics at each
// point), finite numbers, E(d) >= 0, the pictures, and the plots, or a note when gnuplot is
// missing.
TEST_F(Cli, SlamSweepsWriteTheirCsvsAndPictures) {
  const std::string header =
      "lambda,xi,window_cells,window_headings,pose_cells,arith,scans,localizations,mappings,"
      "seconds,ms_per_scan,int_over_float_seconds,e_sigma_m,e_d_m,e_d_max_m,e_d_centres_m,"
      "map_occupied_cells,ate_rmse_m,ate_max_m,ate_heading_deg";
  const std::vector<std::string> columns = fields_of(header);
  const auto column = [&](const char* name) {
    return static_cast<std::size_t>(std::find(columns.begin(), columns.end(), name) -
                                    columns.begin());
  };
  CliRun r = run("figure slam-sweeps --quick --out " + (dir_ / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  // --quick: lambda 1 and 3, xi 1 and 3, windows 3 and 5, each in int and float.
  const std::vector<std::pair<std::string, std::pair<const char*, std::vector<int>>>> sweeps = {
      {"slam_lambda.csv", {"lambda", {1, 1, 3, 3}}},
      {"slam_xi.csv", {"xi", {1, 1, 3, 3}}},
      {"slam_depth.csv", {"window_cells", {3, 3, 5, 5}}}};
  for (const auto& [file, swept] : sweeps) {
    SCOPED_TRACE(file);
    std::ifstream in(dir_ / "out" / file);
    const std::vector<std::string> lines =
        lines_of({std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()});
    ASSERT_EQ(lines.size(), 5u);
    EXPECT_EQ(lines[0], header);
    for (std::size_t i = 1; i < lines.size(); ++i) {
      const std::vector<std::string> f = fields_of(lines[i]);
      ASSERT_EQ(f.size(), columns.size()) << lines[i];
      EXPECT_EQ(f[column("arith")], i % 2 == 1 ? "int" : "float") << lines[i];
      EXPECT_EQ(std::stoi(f[column(swept.first)]), swept.second[i - 1]) << lines[i];
      for (std::size_t c = 0; c < f.size(); ++c) {
        if (c == column("arith")) continue;
        std::size_t used = 0;
        const double value = std::stod(f[c], &used);
        EXPECT_EQ(used, f[c].size()) << columns[c] << " in " << lines[i];
        EXPECT_TRUE(std::isfinite(value)) << columns[c] << " in " << lines[i];
        EXPECT_GE(value, 0.0) << columns[c] << " in " << lines[i];
      }
      EXPECT_GT(std::stod(f[column("seconds")]), 0.0) << lines[i];
      EXPECT_GT(std::stoi(f[column("map_occupied_cells")]), 0) << lines[i];
      EXPECT_LE(std::stod(f[column("e_d_m")]), std::stod(f[column("e_d_centres_m")])) << lines[i];
      EXPECT_EQ(std::stoi(f[column("scans")]), 24) << lines[i];
    }
  }
  expect_png(dir_ / "out" / "slam_world.png");
  expect_png(dir_ / "out" / "slam_maps.png");
  if (r.output.find("plots skipped") == std::string::npos)
    for (const char* png : {"slam_lambda.png", "slam_xi.png", "slam_depth.png"})
      expect_png(dir_ / "out" / png);
  for (const auto& entry : fs::directory_iterator(dir_ / "out"))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();

  r = run("figure slam-sweeps --quick --scans 12 --gnuplot " + (dir_ / "no-gnuplot").string() +
          " --out " + (dir_ / "bare").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("plots skipped"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "bare" / "slam_xi.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "bare" / "slam_xi.png"));
}

// `intgrid globloc` and `figure globloc-sweeps`: a 4 x 3 m room at 10 cm with two blocks that
// break its symmetry.
fs::path write_globloc_room(const fs::path& dir) {
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

// The room against itself 100 m away: far past any small tolerance, within any huge one. The
// search window is cut to the grid (a tolerance of 10^9 cells once searched 10^18 cells, and
// 10^10 overflowed to a window of none).
TEST_F(Cli, CompareTakesAnyToleranceAndRefusesAnAbsurdResolution) {
  const fs::path room = write_globloc_room(dir_);
  std::ofstream(dir_ / "far.yaml") << "image: room.pgm\nresolution: 0.1\norigin: [100, 0, 0]\n"
                                      "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  const std::string base =
      "compare --map " + room.string() + " --reference " + (dir_ / "far.yaml").string();
  for (const char* tolerance : {"1e9", "1e10", "1e300"}) {
    const CliRun r = run(base + " --tolerance-cells " + tolerance);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("of the reference's: 100.0%"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("of ours: 100.0%"), std::string::npos) << r.output;
  }
  const CliRun near = run(base + " --tolerance-cells 2");
  ASSERT_EQ(near.status, 0) << near.output;
  EXPECT_NE(near.output.find("of the reference's: 0.0%"), std::string::npos) << near.output;
  expect_error(run(base + " --tolerance-cells nan"), "--tolerance-cells");
  std::ofstream(dir_ / "fine.yaml") << "image: room.pgm\nresolution: 1e-320\norigin: [0, 0, 0]\n"
                                       "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  expect_error(
      run("compare --map " + room.string() + " --reference " + (dir_ / "fine.yaml").string()),
      "resolution");
}

TEST_F(Cli, GlobLocWritesPosesPictureAndMetricsAndScoresAgainstAReference) {
  const fs::path room = write_globloc_room(dir_);
  const fs::path sim = dir_ / "sim";
  ASSERT_EQ(run("simulate --out " + sim.string() + " --world " + room.string() +
                " --scans 6 --seed 3 --noise 0.01")
                .status,
            0);
  const fs::path out = dir_ / "out";
  const CliRun r = run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() +
                       " --out " + out.string() + " --reference " + (sim / "truth.log").string() +
                       " --scans 1:4 --pose-cell 0.1 --headings 64 --beams 90");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"poses.txt", "pose_grid.png", "metrics.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  expect_png(out / "pose_grid.png");
  const std::vector<std::string> lines = lines_of(file_text(out / "poses.txt"));
  ASSERT_EQ(lines.size(), 5u) << file_text(out / "poses.txt");
  EXPECT_EQ(lines[0].rfind("# t x y theta score", 0), 0u) << lines[0];
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::istringstream fields(lines[i]);
    double t = 0, x = 0, y = 0, theta = 0, score = 0;
    ASSERT_TRUE(fields >> t >> x >> y >> theta >> score) << lines[i];
    EXPECT_NEAR(t, 1e9 + 0.2 * static_cast<double>(i), 1e-6) << lines[i];  // scans 1 to 4
    EXPECT_TRUE(x > 0 && x < 4 && y > 0 && y < 3) << lines[i];
  }
  // Every scan has a reference pose; in this room each is found.
  EXPECT_NE(r.output.find("\"matched\": 4"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"within\": 4"), std::string::npos) << r.output;
  EXPECT_NE(file_text(out / "metrics.json").find("\"share\": 1.0"), std::string::npos);
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();

  // --hypotheses 3: each line adds the two next hypotheses (x y theta score) after the ambiguity
  // flag, on any thread count the same file.
  for (const char* threads : {"1", "3"}) {
    const fs::path k3 = dir_ / (std::string("k3_") + threads);
    const CliRun h = run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() +
                         " --out " + k3.string() + " --scans 1:4 --pose-cell 0.1 --headings 64 " +
                         "--beams 20 --hypotheses 3 --threads " + threads);
    ASSERT_EQ(h.status, 0) << h.output;
    const std::vector<std::string> k3_lines = lines_of(file_text(k3 / "poses.txt"));
    ASSERT_EQ(k3_lines.size(), 5u);
    for (std::size_t i = 1; i < k3_lines.size(); ++i) {
      std::istringstream fields(k3_lines[i]);
      std::vector<double> v;
      for (double x = 0; fields >> x;) v.push_back(x);
      ASSERT_EQ(v.size(), 14u) << k3_lines[i];
      EXPECT_TRUE(v[5] == 0.0 || v[5] == 1.0) << k3_lines[i];
      EXPECT_GE(v[4], v[9]) << k3_lines[i];  // best first
      EXPECT_GE(v[9], v[13]) << k3_lines[i];
    }
  }
  EXPECT_EQ(file_text(dir_ / "k3_1" / "poses.txt"), file_text(dir_ / "k3_3" / "poses.txt"));
  // A trajectory as the reference (t x y theta, as slam writes it): the estimates themselves are
  // found, at any tolerance; shifted by 0.2 m, not within 0.1 m.
  std::string exact = "# t x y theta\n", shifted = exact;
  const auto number = [](double v) {
    std::ostringstream o;
    o.precision(17);
    o << v;
    return o.str();
  };
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::istringstream fields(lines[i]);
    double t = 0, x = 0, y = 0, theta = 0;
    fields >> t >> x >> y >> theta;
    exact += number(t) + ' ' + number(x) + ' ' + number(y) + ' ' + number(theta) + '\n';
    shifted += number(t) + ' ' + number(x + 0.2) + ' ' + number(y) + ' ' + number(theta) + '\n';
  }
  for (const auto& [name, text, within] :
       {std::tuple{"exact.txt", exact, 4}, std::tuple{"shifted.txt", shifted, 0}}) {
    const CliRun t =
        run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() + " --out " +
            (dir_ / "traj").string() + " --reference-trajectory " + write(name, text).string() +
            " --scans 1:4 --pose-cell 0.1 --headings 64 --beams 90 --tolerance 0.1 1");
    ASSERT_EQ(t.status, 0) << t.output;
    EXPECT_NE(t.output.find("\"within\": " + std::to_string(within)), std::string::npos)
        << name << t.output;
    // Each miss's endpoints fit the map better at the answer than at the shifted reference.
    if (within == 0) {
      EXPECT_NE(t.output.find("\"misses_where_the_endpoints_fit_the_reference_better\": 0"),
                std::string::npos)
          << t.output;
    }
  }
  // A pose grid above --max-memory is refused, naming the option, before it is built.
  const CliRun big =
      run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() + " --out " +
          (dir_ / "big").string() + " --pose-cell 0.1 --headings 4096 --max-memory 1");
  EXPECT_EQ(big.status, 2) << big.output;
  expect_error(big, "--max-memory: a pose grid of");

  // The baselines run too.
  for (const char* method : {"markov", "markov-mixture", "likelihood-field"}) {
    const CliRun b = run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() +
                         " --out " + (dir_ / method).string() + " --scans 2:2 --method " + method);
    ASSERT_EQ(b.status, 0) << method << b.output;
    EXPECT_NE(b.output.find(std::string("\"method\": \"") + method + "\""), std::string::npos);
  }
}

// --track: from each selected scan the scans after it are fused until the answer is
// unambiguous; poses.txt adds how many it took and when it started, the same on any thread count.
TEST_F(Cli, GlobLocTrackFusesScansAndSaysHowManyItTook) {
  const fs::path room = write_globloc_room(dir_);
  const fs::path sim = dir_ / "sim";
  ASSERT_EQ(run("simulate --out " + sim.string() + " --world " + room.string() +
                " --scans 12 --seed 3 --noise 0.01")
                .status,
            0);
  for (const char* threads : {"1", "3"}) {
    const fs::path out = dir_ / (std::string("track_") + threads);
    const CliRun r = run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() +
                         " --out " + out.string() + " --reference " + (sim / "truth.log").string() +
                         " --scans 0:5 --pose-cell 0.1 --headings 64 --beams 20 --track 4 " +
                         "--track-step 0.05 5 --ambiguity-levels 20 --threads " + threads);
    ASSERT_EQ(r.status, 0) << r.output;
    const std::vector<std::string> lines = lines_of(file_text(out / "poses.txt"));
    ASSERT_EQ(lines.size(), 7u) << file_text(out / "poses.txt");
    EXPECT_NE(lines[0].find("scans t_first"), std::string::npos) << lines[0];
    std::size_t fused_more = 0;
    for (std::size_t i = 1; i < lines.size(); ++i) {
      std::istringstream fields(lines[i]);
      double t = 0, x = 0, y = 0, theta = 0, score = 0, ambiguous = 0, scans = 0, t_first = 0;
      ASSERT_TRUE(fields >> t >> x >> y >> theta >> score >> ambiguous >> scans >> t_first)
          << lines[i];
      EXPECT_NEAR(t_first, 1e9 + 0.2 * static_cast<double>(i - 1), 1e-6) << lines[i];
      EXPECT_GE(scans, 1.0);
      EXPECT_LE(scans, 4.0);
      // A scan is fused after the first only while the answer is ambiguous; each fused scan
      // is a later one.
      EXPECT_TRUE(scans == 4.0 || ambiguous == 0.0) << lines[i];
      EXPECT_GE(t, t_first + 0.2 * (scans - 1) - 1e-6) << lines[i];
      fused_more += scans > 1.0 ? 1 : 0;
    }
    // --ambiguity-levels 20 calls nearly every answer ambiguous: sequences are fused.
    EXPECT_GT(fused_more, 0u);
    const std::string metrics = file_text(out / "metrics.json");
    EXPECT_NE(metrics.find("\"track\""), std::string::npos);
    EXPECT_NE(metrics.find("\"mean_scans\""), std::string::npos);
    EXPECT_NE(r.output.find("\"matched\": 6"), std::string::npos) << r.output;
  }
  EXPECT_EQ(file_text(dir_ / "track_1" / "poses.txt"), file_text(dir_ / "track_3" / "poses.txt"));
}

TEST_F(Cli, GlobLocRefusesBadInputsNamingFileAndField) {
  const fs::path room = write_globloc_room(dir_);
  const fs::path log = write("room.log", "RLASER 4 -0.5 0.3 10 1.0 1.2 1.1 1.3" + kScanTail +
                                             "RLASER 4 -0.5 0.3 10 1.0 1.2 1.1 1.3" + kScanTail);
  const fs::path out = dir_ / "out";
  const auto globloc = [&](const fs::path& map, const fs::path& scans, const std::string& more) {
    return run("globloc --map " + map.string() + " --log " + scans.string() + " --out " +
               out.string() + " " + more);
  };
  // A map without any free cell.
  write("dark.pgm", std::string("P5\n10 10\n255\n") + std::string(100, '\0'));
  const fs::path dark = write("dark.yaml",
                              "image: dark.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  CliRun r = globloc(dark, log, "");
  expect_error(r, dark.string() + ": image: the map has no free cell");
  EXPECT_EQ(r.status, 2);
  // A pose grid finer than the map.
  r = globloc(room, log, "--pose-cell 0.05");
  expect_error(r, room.string() + ": resolution: the pose-grid step --pose-cell 0.05 m is finer");
  EXPECT_EQ(r.status, 2);
  // A log without any valid reading.
  const fs::path dead = write("dead.log", "RLASER 4 -0.5 0.3 10 0 0 nan 11" + kScanTail);
  r = globloc(room, dead, "");
  expect_error(r, dead.string() + ": ranges: no selected scan holds a valid reading");
  EXPECT_EQ(r.status, 2);
  // Bad scan ranges.
  for (const char* scans : {"5:2", "0:2", "a:1", "1", "1:2:3"}) {
    SCOPED_TRACE(scans);
    r = globloc(room, log, std::string("--scans ") + scans);
    expect_error(r, log.string() + ": --scans: '" + scans + "'");
    EXPECT_EQ(r.status, 2);
  }
  // A log line that does not parse names its line and field.
  const fs::path bad = write("bad.log", "RLASER 4 -0.5 0.3 10 1.0 1.0 x1 1.0" + kScanTail);
  r = globloc(room, bad, "");
  expect_error(r, bad.string() + ":1: r_2");
  EXPECT_EQ(r.status, 2);
  EXPECT_FALSE(fs::exists(out / "poses.txt"));
}

// `figure globloc-sweeps --quick`: one CSV per sweep (two points, four methods each), the same for
// one and two threads, and the plots (or a note when gnuplot is missing).
TEST_F(Cli, GlobLocSweepsWriteTheirCsvsAndPlotsTheSameForAnyThreadCount) {
  const fs::path room = write_globloc_room(dir_);
  const std::string options =
      "figure globloc-sweeps --quick --trials 3 --pose-cell 0.1 --headings 32 --seed 4 --map " +
      room.string();
  const CliRun one = run(options + " --threads 1 --out " + (dir_ / "one").string());
  ASSERT_EQ(one.status, 0) << one.output;
  const CliRun two = run(options + " --threads 2 --out " + (dir_ / "two").string());
  ASSERT_EQ(two.status, 0) << two.output;
  EXPECT_NE(one.output.find("success: position error <= 0.2 m (2 pose cells) AND heading error "
                            "<= 22.5 deg (2 heading bins)"),
            std::string::npos)
      << one.output;
  const std::vector<std::pair<std::string, std::string>> sweeps = {
      {"readings", "readings"},
      {"noise", "noise_m"},
      {"contamination", "contamination"},
      {"obstacles", "obstacles"},
      {"large_obstacle", "distance_m"}};
  const char* methods[] = {"pog", "markov", "markov-mixture", "likelihood-field"};
  for (const auto& [sweep, variable] : sweeps) {
    SCOPED_TRACE(sweep);
    const std::string csv = file_text(dir_ / "one" / ("globloc_" + sweep + ".csv"));
    EXPECT_EQ(csv, file_text(dir_ / "two" / ("globloc_" + sweep + ".csv")));
    const std::vector<std::string> lines = lines_of(csv);
    ASSERT_EQ(lines.size(), 1u + 2 * 4) << csv;
    EXPECT_EQ(lines[0], variable +
                            ",method,trials,failed_setups,mean_readings,successes,success_rate,"
                            "mean_position_error_m,median_position_error_m,mean_heading_error_deg");
    for (std::size_t i = 1; i < lines.size(); ++i) {
      const std::vector<std::string> f = fields_of(lines[i]);
      ASSERT_EQ(f.size(), 10u) << lines[i];
      EXPECT_EQ(f[1], methods[(i - 1) % 4]) << lines[i];
      EXPECT_EQ(std::stoi(f[2]) + std::stoi(f[3]), 3) << lines[i];
      const double rate = std::stod(f[6]);
      EXPECT_TRUE(rate >= 0.0 && rate <= 1.0) << lines[i];
      for (std::size_t c = 7; c < 10; ++c) EXPECT_GE(std::stod(f[c]), 0.0) << lines[i];
    }
    if (one.output.find("plots skipped") == std::string::npos)
      expect_png(dir_ / "one" / ("globloc_" + sweep + ".png"));
  }
  EXPECT_TRUE(fs::exists(dir_ / "one" / "globloc_timing.csv"));
  // With 60 clean readings in this room every method finds nearly every pose.
  const std::vector<std::string> readings =
      lines_of(file_text(dir_ / "one" / "globloc_readings.csv"));
  for (std::size_t i = 5; i < readings.size(); ++i)
    EXPECT_GE(std::stod(fields_of(readings[i])[6]), 0.6) << readings[i];
  for (const auto& entry : fs::directory_iterator(dir_ / "one"))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
  // --sweeps runs only those: the same rows as in the full run, no other sweep's file.
  const CliRun only = run(options + " --sweeps contamination --out " + (dir_ / "only").string());
  ASSERT_EQ(only.status, 0) << only.output;
  EXPECT_EQ(file_text(dir_ / "only" / "globloc_contamination.csv"),
            file_text(dir_ / "one" / "globloc_contamination.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "only" / "globloc_readings.csv"));
  EXPECT_EQ(run(options + " --sweeps speed --out " + (dir_ / "bad").string()).status, 2);
}

// Every subcommand's bad inputs, one of each class of option at least (no number, NaN, negative,
// out of range, unknown name, unknown option, missing value, missing file): exit 2 and one line
// naming the flag, or the file; for a bad option, a hint to the subcommand's help. (slam's own
// options are left to the slam command's tests: only the generic errors here.)
TEST_F(Cli, EveryBadInputExitsTwoNamingTheFlagOrTheFile) {
  const fs::path log = write("room.log", "RLASER 4 -0.5 0.3 10 1.0 1.2 1.1 1.3" + kScanTail +
                                             "RLASER 4 -0.5 0.3 10 1.0 1.2 1.1 1.3" + kScanTail);
  const fs::path room = write_globloc_room(dir_);
  const std::string missing = (dir_ / "missing.file").string();
  const std::string out = (dir_ / "out").string();
  const std::string narrow = "ism --sigma 0.02 --cell 0.05 --z 1 --length 2";
  const std::string map = "map --log " + log.string() + " --out " + out;
  const std::string compare = "compare --map " + room.string() + " --reference " + room.string();
  const std::string sweeps =
      "figure globloc-sweeps --quick --out " + out + " --map " + room.string();
  const std::string simulate = "simulate --out " + out;
  const std::string globloc =
      "globloc --map " + room.string() + " --log " + log.string() + " --out " + out;
  const fs::path held = dir_ / "held";
  fs::create_directories(held / "inner");
  struct Case {
    std::string arguments;
    std::string named;  // the flag or the file the message names
    std::string help;   // the subcommand of the hint "run 'intgrid SUB --help'", if any
  };
  const std::vector<Case> cases = {
      // ism
      {"ism --sigma abc --cell 0.05 --z 1 --length 2", "--sigma", "ism"},
      {"ism --sigma nan --cell 0.05 --z 1 --length 2", "--sigma", "ism"},
      {"ism --sigma 0.02 --cell -0.05 --z 1 --length 2", "--cell", "ism"},
      {narrow + " --bits 17", "--bits", "ism"},
      {narrow + " --bits 2.5", "--bits", "ism"},
      {narrow + " --eps 0.5", "--eps", "ism"},
      {narrow + " --eps 1e-17", "--eps", "ism"},
      {"ism --sigma 0.02 --cell 0.05 --z -1 --length 2", "--z", "ism"},
      {narrow + " --k-d -1", "--k-d", "ism"},
      {"ism --sigma 0.02 --cell 0.05 --z 1 --length 0.01", "--length", "ism"},
      {"ism --sigma 0.02 --cell 0.05 --length 2", "--z", "ism"},
      {"ism --cell 0.05 --z 1 --length 2", "--sigma", "ism"},
      {"ism --fov 30 --z inf", "--z", "ism"},
      {"ism --fov 30 --arith int --z 1e12", "--z", "ism"},  // the kernel's "reading z", named
      {"ism --fov 30 --z 1 --arith fixed", "--arith", "ism"},
      {"ism --fov 30 --z 1 --sectors 5", "--sectors", "ism"},
      {"ism --fov 30 --z 1 --k-size -1", "--k-size", "ism"},
      {"ism --fov 30 --agreement -3", "--agreement", "ism"},
      {"ism --fov 30 --agreement 10 --seed x", "--seed", "ism"},
      {"ism --fov 30 --z", "--z", "ism"},
      {"ism --frob 1", "--frob", "ism"},
      // resolution
      {"resolution --sigma 0.02 --pmax 1.5", "--pmax", "resolution"},
      {"resolution --sigma 0.02 --pmax nan", "--pmax", "resolution"},
      {"resolution --sigma -1 --pmax 0.9", "--sigma", "resolution"},
      {"resolution --sigma 0.02", "--pmax", "resolution"},
      // values that crashed, hung, printed NaN or exited 1 unnamed (issue 21, item 10)
      {"resolution --sigma 1e307 --pmax 0.9", "--sigma", "resolution"},
      {"resolution --sigma 1e-315 --pmax 0.9", "--sigma", "resolution"},
      {"ism --sigma 1e-300 --cell 0.05 --z 1 --length 2", "--sigma", "ism"},
      {"ism --fov 30 --arith int --z 1 --sigma 0.5 --cell 0.05", "--sigma", "ism"},
      {"ism --fov 30 --arith int --z 1 --sigma 0.02 --cell 0.05 --rings 200000", "--rings", "ism"},
      {"hw-config --name t --out " + out + " --eps 1e-4", "--eps", "hw-config"},
      {map + " --cell 1e9", "--cell", "map"},
      {map + " --cell 0.003", "--cell", "map"},
      {"slam --log " + log.string() + " --out " + out + " --tracking-degrees 200",
       "--tracking-degrees", "slam"},
      {"slam --log " + log.string() + " --out " + out + " --cell 0.2 --sigma 0.001", "--cell",
       "slam"},
      {"slam --engine grid --log " + log.string() + " --out " + out + " --cell 1e-300", "--cell",
       "slam"},
      {"slam --engine grid --log " + log.string() + " --out " + out + " --sigma 1e18", "--sigma",
       "slam"},
      {globloc + " --sigma 1e9", "--sigma", "globloc"},
      {globloc + " --pose-cell 1e9", "--pose-cell", "globloc"},
      {"figure slam-sweeps --out " + out + " --cell 1e-300", "--cell", "figure slam-sweeps"},
      {sweeps + " --clearance 1e9", "--clearance", "figure globloc-sweeps"},
      {simulate + " --max-range 1e9", "--max-range", "simulate"},
      {simulate + " --odometry-noise 0,0,1e300,0", "--odometry-noise", "simulate"},
      {map + " --cell 0.05 --levels 200", "--levels", "map"},
      // map
      {map + " --cell abc", "--cell", "map"},
      {map + " --cell 0", "--cell", "map"},
      {map + " --res 0", "--cell", "map"},
      {map + " --cell 0.00001", "--cell", "map"},
      {map, "--cell", "map"},
      {map + " --cell 0.05 --sigma nan", "--sigma", "map"},
      {map + " --cell 0.05 --k-d -0.1", "--k-d", "map"},
      {map + " --cell 0.05 --bits 1", "--bits", "map"},
      {map + " --cell 0.05 --levels 0", "--levels", "map"},
      {map + " --cell 0.05 --eps 0.7", "--eps", "map"},
      {map + " --cell 0.05 --eps 1e-300", "--eps", "map"},  // 1/2 + eps rounds to 1/2
      {map + " --cell 0.05 --arith double", "--arith", "map"},
      {map + " --cell 0.05 --veto-bound maybe", "--veto-bound", "map"},
      {"map --log " + missing + " --out " + out + " --cell 0.05", missing, ""},
      // compare
      {compare + " --tolerance-cells -1", "--tolerance-cells", "compare"},
      {compare + " --tolerance-cells x", "--tolerance-cells", "compare"},
      {"compare --map " + room.string(), "--reference", "compare"},
      {"compare --map " + room.string() + " --reference " + missing, missing, ""},
      // figure
      {"figure", "subcommand", "figure"},
      {"figure bogus", "bogus", "figure"},
      {"figure ns-sweep --z nan --out " + out + ".png", "--z", "figure ns-sweep"},
      {"figure ns-sweep --z -1 --out " + out + ".png", "--z", "figure ns-sweep"},
      {"figure ns-sweep --out " + out + ".jpg", "--out", "figure ns-sweep"},
      {"figure fusion --out " + out + ".txt", "--out", "figure fusion"},
      {"figure fusion --frob", "--frob", "figure fusion"},
      {"figure slam-sweeps --frob", "--frob", "figure slam-sweeps"},
      {sweeps + " --trials 0", "--trials", "figure globloc-sweeps"},
      // A pose grid above the limit (was an error on the map's image).
      {sweeps + " --headings 4096 --max-memory 1", "--max-memory", "figure globloc-sweeps"},
      {map + " --cell 0.05 --max-memory 0.5", "--max-memory", "map"},
      {sweeps + " --threads -1", "--threads", "figure globloc-sweeps"},
      {sweeps + " --seed 1.5", "--seed", "figure globloc-sweeps"},
      {sweeps + " --sweeps speed", "--sweeps", "figure globloc-sweeps"},
      {sweeps + " --fov 400", "--fov", "figure globloc-sweeps"},
      {sweeps + " --noise -0.1", "--noise", "figure globloc-sweeps"},
      {sweeps + " --beams 0", "--beams", "figure globloc-sweeps"},
      {sweeps + " --sensor-range inf", "--sensor-range", "figure globloc-sweeps"},
      {sweeps + " --clearance nan", "--clearance", "figure globloc-sweeps"},
      {sweeps + " --headings 2", "--headings", "figure globloc-sweeps"},
      {sweeps + " --levels 10 --veto-levels 20", "--veto-levels", "figure globloc-sweeps"},
      {sweeps + " --pose-cell 0.05", "--pose-cell", ""},
      {"figure globloc-sweeps --quick --out " + out + " --map " + missing, missing, ""},
      // demo
      {"demo --sigma -1", "--sigma", "demo"},
      {"demo --bits 40", "--bits", "demo"},
      {"demo --veto-bound x", "--veto-bound", "demo"},
      {"demo --out " + out + " --data " + missing, missing, ""},
      // simulate
      {simulate + " --noise abc", "--noise", "simulate"},
      {simulate + " --dropout nan", "--dropout", "simulate"},
      {simulate + " --seed -1", "--seed", "simulate"},
      {simulate + " --scans 0", "--scans", "simulate"},
      {simulate + " --sensor radar", "--sensor", "simulate"},
      {simulate + " --fov 400", "--fov", "simulate"},
      {simulate + " --world " + missing, missing, ""},
      {simulate + " --trajectory " + missing, missing, ""},
      {"simulate --scans 5", "--out", "simulate"},
      {simulate + " --frob", "--frob", "simulate"},
      // slam: the generic errors only
      {"slam --log " + log.string() + " --out " + out + " --frob 1", "--frob", "slam"},
      // --out: a file, a folder holding folders (which a run could not replace as one)
      {"map --cell 0.1 --log " + log.string() + " --out " + log.string(), "--out", "map"},
      {"map --cell 0.1 --log " + log.string() + " --out " + held.string(), "--out", "map"},
      {"globloc --map " + room.string() + " --log " + log.string() + " --out " + room.string(),
       "--out", "globloc"},
      {"slam --log " + missing + " --out " + out, missing, ""},
      // globloc
      {globloc + " --pose-cell -1", "--pose-cell", "globloc"},
      {globloc + " --pose-res -1", "--pose-cell", "globloc"},
      {globloc + " --headings 3", "--headings", "globloc"},
      {globloc + " --headings x", "--headings", "globloc"},
      {globloc + " --sigma nan", "--sigma", "globloc"},
      {globloc + " --max-range 0", "--max-range", "globloc"},
      {globloc + " --levels 200", "--levels", "globloc"},
      {globloc + " --veto-levels 20", "--veto-levels", "globloc"},
      {globloc + " --method best", "--method", "globloc"},
      {globloc + " --every 0", "--every", "globloc"},
      {globloc + " --beams -1", "--beams", "globloc"},
      {globloc + " --track 2 --method markov", "--track", ""},
      {globloc + " --track 1001", "--track", "globloc"},
      {globloc + " --track 2 --track-step -1 5", "--track-step", "globloc"},
      {globloc + " --refine-levels 9", "--refine-levels", "globloc"},
      {globloc + " --headings 4096 --refine-levels 5", "--refine-levels", ""},
      {globloc + " --scans 5:2", "--scans", ""},
      {"globloc --map " + missing + " --log " + log.string() + " --out " + out, missing, ""},
      {globloc + " --reference " + missing, missing, ""},
      {globloc + " --frob", "--frob", "globloc"},
      // no subcommand, an unknown one
      {"", "subcommand", "intgrid"},
      {"bogus", "bogus", "intgrid"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.arguments);
    const CliRun r = run(c.arguments);
    EXPECT_EQ(r.status, 2) << r.output;
    expect_error(r, c.named);
    EXPECT_EQ(r.output.rfind("intgrid: error: ", 0), 0u) << r.output;
    if (!c.help.empty()) {
      const std::string sub = c.help == "intgrid" ? "intgrid" : "intgrid " + c.help;
      EXPECT_NE(r.output.find("run '" + sub + " --help'"), std::string::npos) << r.output;
    }
    EXPECT_FALSE(fs::exists(dir_ / "out" / "poses.txt"));
  }
}

// --help exits 0 with every subcommand's options and no CLI11 internals: no transformer map
// ("->", "OR {"), no range bound of more than 12 digits, and only the documented names.
TEST_F(Cli, HelpShowsNoLibraryInternals) {
  const std::vector<std::string> subcommands = {"",
                                                "ism",
                                                "resolution",
                                                "map",
                                                "compare",
                                                "figure",
                                                "figure ns-sweep",
                                                "figure fusion",
                                                "figure slam-sweeps",
                                                "figure globloc-sweeps",
                                                "demo",
                                                "simulate",
                                                "slam",
                                                "globloc",
                                                "hw-config"};
  for (const std::string& sub : subcommands) {
    SCOPED_TRACE(sub);
    const CliRun r = run(sub + " --help");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("Usage: intgrid " + sub), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("->"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("OR {"), std::string::npos) << r.output;
    std::size_t digits = 0, longest = 0;
    for (const char c : r.output) {
      digits = std::isdigit(static_cast<unsigned char>(c)) ? digits + 1 : 0;
      longest = std::max(longest, digits);
    }
    EXPECT_LE(longest, 12u) << r.output;
    // Old names work but are not documented.
    if (sub == "slam" || sub == "figure slam-sweeps") continue;  // the SLAM's options: elsewhere
    for (const char* old_name : {"--res ", "--pose-res", "--sigma0", "--readings"})
      EXPECT_EQ(r.output.find(old_name), std::string::npos) << old_name << "\n" << r.output;
  }
  EXPECT_NE(run("map --help").output.find("--cell FLOAT"), std::string::npos);
  EXPECT_NE(run("globloc --help").output.find("--pose-cell FLOAT"), std::string::npos);
  // The top level lists every subcommand on one line each, with a short description.
  const std::vector<std::string> lines = lines_of(run("--help").output);
  const auto at = std::find(lines.begin(), lines.end(), "Subcommands:");
  ASSERT_NE(at, lines.end());
  std::size_t listed = 0;
  for (auto line = at + 1; line != lines.end() && !line->empty(); ++line, ++listed)
    EXPECT_LE(line->size(), 110u) << *line;
  // One line per top-level subcommand in the list above (not "" and not "figure x").
  const auto top_level = std::count_if(subcommands.begin(), subcommands.end(), [](const auto& s) {
    return !s.empty() && s.find(' ') == std::string::npos;
  });
  EXPECT_EQ(listed, static_cast<std::size_t>(top_level));
}

// The old names of renamed options keep working: --res (map), --pose-res (globloc), --sigma0
// (ism --fov), --readings (figure globloc-sweeps).
TEST_F(Cli, OldOptionNamesStillWork) {
  const fs::path log = write("good.log", "RLASER 4 -0.5 0.3 10 1.0 1.0 1.0 1.0" + kScanTail);
  CliRun r = run("map --log " + log.string() + " --out " + (dir_ / "m").string() + " --res 0.05");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(run("ism --fov 30 --z 1 --sigma0 0.03").output,
            run("ism --fov 30 --z 1 --sigma 0.03").output);
  const fs::path room = write_globloc_room(dir_);
  ASSERT_EQ(run("simulate --out " + (dir_ / "sim").string() + " --world " + room.string() +
                " --scans 2 --seed 3")
                .status,
            0);
  r = run("globloc --map " + room.string() + " --log " + (dir_ / "sim" / "sim.log").string() +
          " --out " + (dir_ / "g").string() + " --scans 0:0 --pose-res 0.1 --headings 16");
  EXPECT_EQ(r.status, 0) << r.output;
  r =
      run("figure globloc-sweeps --quick --trials 1 --sweeps readings --readings 20 --headings 16 "
          "--gnuplot " +
          (dir_ / "no-gnuplot").string() + " --out " + (dir_ / "s").string() + " --map " +
          room.string());
  EXPECT_EQ(r.status, 0) << r.output;
}

}  // namespace

namespace {

// `intgrid hw-config`: a configuration folder of the sectoral ISM's RTL. That its bytes are
// golden's is the hw test sectoral_ism_config_* (the committed cone16 and cone12); here the
// folder's files, the ROM paths its parameter files give, and the errors.
TEST_F(Cli, HwConfigWritesTheRomsAndTheParametersNamingThem) {
  const fs::path out = dir_ / "config" / "my_sensor";
  const CliRun r = run("hw-config --name my_sensor --out " + out.string() +
                       " --fov 60 --rings 24 --bins 12 --sectors 2 --cell 0.1");
  ASSERT_EQ(r.status, 0) << r.output;
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(out))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  const std::vector<std::string> want = {"sectoral_ism_my_sensor.svh",
                                         "sectoral_ism_my_sensor.vc",
                                         "sectoral_ism_my_sensor.ys",
                                         "sectoral_ism_my_sensor_log_add.mem",
                                         "sectoral_ism_my_sensor_log_norm.mem",
                                         "sectoral_ism_my_sensor_log_weight.mem",
                                         "sectoral_ism_my_sensor_quad_coef.mem",
                                         "sectoral_ism_my_sensor_threshold_bucket.mem",
                                         "sectoral_ism_my_sensor_thresholds.mem"};
  EXPECT_EQ(names, want);
  std::ifstream vc(out / "sectoral_ism_my_sensor.vc");
  const std::string text((std::istreambuf_iterator<char>(vc)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("-GBINS=12\n"), std::string::npos) << text;
  EXPECT_NE(text.find("-GSECTORS=2\n"), std::string::npos) << text;
  EXPECT_NE(text.find("-GLOG_ADD_FILE=\\\"config/my_sensor/sectoral_ism_my_sensor_log_add.mem\\\""),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find(dir_.string()), std::string::npos) << "no absolute path: " << text;

  const CliRun moved =
      run("hw-config --name my_sensor --rom-dir roms --out " + (dir_ / "moved").string());
  ASSERT_EQ(moved.status, 0) << moved.output;
  std::ifstream ys(dir_ / "moved" / "sectoral_ism_my_sensor.ys");
  const std::string script((std::istreambuf_iterator<char>(ys)), std::istreambuf_iterator<char>());
  EXPECT_NE(script.find("chparam -set LOG_ADD_FILE \"roms/sectoral_ism_my_sensor_log_add.mem\""),
            std::string::npos)
      << script;
}

TEST_F(Cli, HwConfigRefusesWhatTheKernelCannotHoldNamingTheOption) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--bins 15 --sectors 4", "--bins: 15 is no multiple of --sectors 4"},
      {"--sectors 17", "--sectors"},
      {"--rings 300", "--rings"},  // reach (300 + window) << 8 passes the 16-bit reading port
      {"--sigma 50 --cell 0.01", "--sigma"},
      // the quadratic term's limit: led by --cell, and the --k-d that the user set is named too
      {"--k-d 10", "--k-d move it too"},
      {"--bits 1", "--bits"},
      {"--eps 0.5", "--eps"},
      {"--fov 0", "--fov"},
      {"--rom-dir /abs/roms", "--rom-dir"},
  };
  const fs::path out = dir_ / "bad";
  for (const auto& [options, keyword] : cases) {
    SCOPED_TRACE(options);
    const CliRun r = run("hw-config --name bad --out " + out.string() + " " + options);
    expect_error(r, keyword);
    EXPECT_EQ(r.status, 2);
    EXPECT_FALSE(fs::exists(out));
  }
  for (const char* name : {"Cone", "1st", "my-sensor", "a/b"}) {
    SCOPED_TRACE(name);
    const CliRun r = run(std::string("hw-config --name ") + name + " --out " + out.string());
    expect_error(r, "--name");
    EXPECT_EQ(r.status, 2);
  }
}

}  // namespace
