// The intgrid command end to end: outputs, and one clear error line with a
// non-zero exit for every bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

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

TEST_F(Cli, LogWithoutAnyValidReadingIsAnError) {
  const fs::path log = write("dead.log", "RLASER 4 -0.5 0.3 10 0 0 nan 11" + kScanTail);
  expect_error(run("map --log " + log.string() + " --out " + (dir_ / "o").string() + " --res 0.05"),
               "no scan holds a valid reading");
}

}  // namespace
