// The demo's reader of docs/hardware_report.json: a report's rows become one line each, a
// missing report gives the hint line (never an error), a broken one a line naming the file.
#include "cli/hardware_summary.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "test_support.hpp"

using namespace intgrid::cli;

namespace intgrid {
namespace {

using test::TempDir;
using ::testing::HasSubstr;

// Two rows as scripts/hw_reports.sh writes them: one that meets its target, one that does not
// place (no Fmax) and says why.
const char* kReport = R"({
  "date": "2026-11-25",
  "tools": {"yosys": "Yosys 0.23"},
  "summary": [
    {"kernel": "index_fusion", "configuration": "B=8 LANES=1", "cycles_per_cell": 1.00001,
     "cycles_per_cell_backpressure": 1.99165, "latency_cycles": 1,
     "latency_cycles_backpressure": 2.9833, "lut4": 44, "dff": 20, "bram": 0,
     "fmax_mhz": 164.02, "target_mhz": 80, "target_met": true, "note": null},
    {"kernel": "index_fusion", "configuration": "B=8 LANES=16", "cycles_per_cell": 0.0625,
     "cycles_per_cell_backpressure": 0.12543, "latency_cycles": 1,
     "latency_cycles_backpressure": 3.0137, "lut4": 700, "dff": 260, "bram": 0,
     "fmax_mhz": null, "target_mhz": null, "target_met": null,
     "note": "does not fit the HX8K: 395 of 256 I/O"},
    {"kernel": "sectoral_ism", "configuration": "cone16", "cycles_per_cell": 1.2,
     "cycles_per_cell_backpressure": 2.1, "latency_cycles": 380.5,
     "latency_cycles_backpressure": 900, "lut4": 1842, "dff": 1273, "bram": 17,
     "fmax_mhz": 35.04, "target_mhz": 40, "target_met": false}
  ]
})";

TEST(HardwareSummary, ReportPathIsBesideTheDataFolder) {
  EXPECT_EQ(cli::hardware_report_path("/repo/data"),
            std::filesystem::path("/repo/hardware_report.json"));
  EXPECT_EQ(cli::hardware_report_path("/repo/data/"),
            std::filesystem::path("/repo/hardware_report.json"));
}

TEST(HardwareSummary, OneLinePerKernelConfiguration) {
  const TempDir dir;
  const auto file = dir.write("hardware_report.json", kReport);
  const HardwareSummary s = read_hardware_summary(file);
  ASSERT_TRUE(s.found);
  ASSERT_EQ(s.lines.size(), 4u);
  EXPECT_THAT(s.lines[0], HasSubstr("2026-11-25"));
  EXPECT_EQ(s.lines[1],
            "  index_fusion B=8 LANES=1: 1.000 cycles/cell, latency 1 cycles (with back-pressure: "
            "1.992, 2.98); 44 LUT4 / 20 DFF / 0 BRAM; Fmax 164.0 MHz vs 80 MHz target: met");
  EXPECT_EQ(s.lines[2],
            "  index_fusion B=8 LANES=16: 0.062 cycles/cell, latency 1 cycles (with back-pressure: "
            "0.125, 3.01); 700 LUT4 / 260 DFF / 0 BRAM; Fmax n/a; does not fit the HX8K: 395 of "
            "256 I/O");
  EXPECT_THAT(s.lines[3],
              HasSubstr("sectoral_ism cone16: 1.200 cycles/cell, latency 380.50 cycles"));
  EXPECT_THAT(s.lines[3], HasSubstr("1842 LUT4 / 1273 DFF / 17 BRAM; Fmax 35.0 MHz vs 40 MHz "
                                    "target: NOT met"));
  EXPECT_EQ(s.json["date"], "2026-11-25");
  ASSERT_EQ(s.json["kernels"].size(), 3u);
  EXPECT_EQ(s.json["kernels"][0]["lut4"], 44);
  EXPECT_EQ(s.json["tools"]["yosys"], "Yosys 0.23");
}

TEST(HardwareSummary, MissingReportGivesTheHintLineNotAnError) {
  const TempDir dir;
  const HardwareSummary s = read_hardware_summary(dir / "hardware_report.json");
  EXPECT_FALSE(s.found);
  ASSERT_EQ(s.lines.size(), 1u);
  EXPECT_THAT(s.lines[0], HasSubstr("bash scripts/hw_reports.sh"));
  EXPECT_TRUE(s.json["report"].is_null());
}

TEST(HardwareSummary, BrokenReportGivesOneLineNamingTheFile) {
  const TempDir dir;
  for (const char* content : {"{ not json", "[1, 2]", R"({"summary": 3})"}) {
    const auto file = dir.write("hardware_report.json", content);
    const HardwareSummary s = read_hardware_summary(file);
    EXPECT_FALSE(s.found) << content;
    ASSERT_EQ(s.lines.size(), 1u) << content;
    EXPECT_THAT(s.lines[0], HasSubstr(file.string())) << content;
    EXPECT_EQ(s.json["report"], file.string()) << content;
  }
}

TEST(HardwareSummary, AbsentFiguresPrintAsNotAvailable) {
  const std::string line = cli::hardware_summary_line(
      nlohmann::json{{"kernel", "sectoral_ism"}, {"configuration", "cone12"}});
  EXPECT_EQ(line,
            "sectoral_ism cone12: n/a cycles/cell, latency n/a cycles (with back-pressure: n/a, "
            "n/a); n/a LUT4 / n/a DFF / n/a BRAM; Fmax n/a");
}

}  // namespace
}  // namespace intgrid
