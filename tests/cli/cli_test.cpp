// The intgrid command end to end: outputs, and one clear error line with a
// non-zero exit for every bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct CliRun {
  int status;
  std::string output;  // stdout and stderr
};

CliRun run(const std::string& arguments) {
  const std::string command = std::string(INTGRID_CLI) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  std::array<char, 4096> buffer;
  while (std::fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
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
  const CliRun r =
      run("map --log " + log.string() + " --out " + (dir_ / "out").string() + " --res 0.05 --json");
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
      run("map --log " + log.string() + " --out " + (dir_ / "out").string() + " --res 0.05"),
      log.string() + ":2: r_2");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "map.pgm"));
}

TEST_F(Cli, UnparsableNumberNamesFileLineAndField) {
  const fs::path log = write("bad.log", "RLASER 4 -0.5 0.3 10 1.0 1.0 x1 1.0" + kScanTail);
  expect_error(
      run("map --log " + log.string() + " --out " + (dir_ / "out").string() + " --res 0.05"),
      log.string() + ":1: r_2");
}

TEST_F(Cli, MissingFileIsNamed) {
  expect_error(run("map --log " + (dir_ / "nope.log").string() + " --out " + (dir_ / "o").string() +
                   " --res 0.05"),
               (dir_ / "nope.log").string());
}

TEST_F(Cli, PgmSizeDisagreeingWithHeaderIsNamed) {
  write("m.pgm", std::string("P5\n4 4\n255\n") + std::string(10, '\xff'));
  const fs::path yaml = write("m.yaml",
                              "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  expect_error(run("compare --map " + yaml.string() + " --reference " + yaml.string()), "pixels");
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
  CliRun r = run(base + " --res -0.05");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--res"), std::string::npos) << r.output;
  r = run(base + " --res 0.05 --sigma -1");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--sigma"), std::string::npos) << r.output;
  r = run("ism --sigma -0.02 --cell 0.05 --z 1 --length 2");
  EXPECT_NE(r.status, 0);
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
      {"--bins 16 --sectors 5", "multiple of sectors"},
      {"--bins 16 --sectors 32", "exceed bins"},
      {"--bins 128 --sectors 128", "exceed 64"},
      {"--bins 64 --sectors 32 --arith int", "kernel"},
      {"--rings 0", "rings"},
      {"--rings -3", "rings"},
      {"--bins 0", "bins"},
      {"--sectors 0", "sectors"},
      {"--cell 0", "cell"},
      {"--cell -0.05", "cell"},
      {"--sigma0 0", "sigma"},
      {"--k-theta -1", "k_theta"},
  };
  const fs::path png = dir_ / "bad.png";
  for (const auto& [options, keyword] : cases) {
    SCOPED_TRACE(options);
    expect_error(run("ism --fov 30 --z 1 " + options + " --png " + png.string()), keyword);
    EXPECT_FALSE(fs::exists(png));
  }
  for (const char* fov : {"0", "180", "-10", "200"}) {
    SCOPED_TRACE(fov);
    expect_error(run(std::string("ism --z 1 --fov ") + fov + " --png " + png.string()), "FOV");
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
  expect_error(run("map --log " + log.string() + " --out " + (dir_ / "o").string() + " --res 0.05"),
               "no scan holds a valid reading");
}

// The demo prints the hardware kernels' summary from <data>/../docs/hardware_report.json and
// puts it in summary.json under "hardware"; without the report it prints how to make one.
class CliDemo : public Cli {
 protected:
  // A copy of the bundled data (links) in dir_/data, so that dir_/docs can hold a report.
  fs::path data() {
    const fs::path d = dir_ / "data";
    fs::create_directories(d);
    for (const char* f :
         {"malaga_telecom_map.yaml", "malaga_telecom_map.pgm", "malaga_telecom_loop_reference.log"})
      fs::create_symlink(fs::path(INTGRID_DATA_DIR) / f, d / f);
    return d;
  }
  std::string summary_json() {
    std::ifstream in(dir_ / "out" / "summary.json");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
};

TEST_F(CliDemo, PrintsTheKernelsSummaryFromTheHardwareReport) {
  const fs::path d = data();
  fs::create_directories(dir_ / "docs");
  std::ofstream(dir_ / "docs" / "hardware_report.json") << R"({"date": "2026-11-25", "summary": [
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

TEST_F(CliDemo, WithoutTheHardwareReportSaysHowToMakeIt) {
  const CliRun r = run("demo --data " + data().string() + " --out " + (dir_ / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("hardware kernels: no report yet"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bash scripts/hw_reports.sh"), std::string::npos) << r.output;
  EXPECT_NE(summary_json().find("\"hardware\""), std::string::npos);
}

}  // namespace
