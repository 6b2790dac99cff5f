// `intgrid demo`.
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

}  // namespace
