// The hardware kernels' figures for `intgrid demo`: read from the report that
// scripts/hw_reports.sh writes (docs/hardware_report.json, installed as
// share/intgrid/hardware_report.json) (simulation, Yosys and nextpnr-ice40 measurements). The demo
// only reads the report; it never runs the tools.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace intgrid::cli {

// <data>/../hardware_report.json: the report is installed beside the bundled data.
std::filesystem::path hardware_report_path(const std::filesystem::path& data_dir);

struct HardwareSummary {
  bool found = false;              // the report exists and was read
  std::vector<std::string> lines;  // for people: a heading, then one line per kernel configuration
  nlohmann::json json;             // for summary.json under "hardware"
};

// Never throws for a missing or unreadable report: a missing file gives one line saying how to
// generate it; a file that is not the report's JSON gives one line naming the file and the
// reason.
HardwareSummary read_hardware_summary(const std::filesystem::path& report);

// One line for a row of the report's "summary" array, e.g.
//   index_fusion B=8 LANES=1: 1.000 cycles/cell, latency 1 cycles (with back-pressure: 1.992,
//   2.98); 44 LUT4 / 20 DFF / 0 BRAM; Fmax 164.0 MHz vs 80 MHz target: met
// Absent or null figures print as n/a; the row's "note", if any, is appended.
std::string hardware_summary_line(const nlohmann::json& row);

}  // namespace intgrid::cli
