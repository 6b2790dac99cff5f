#include "cli/hardware_summary.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <system_error>

namespace intgrid::cli {
namespace {

const char* kHint =
    "hardware kernels: no report yet (docs/hardware_report.json); generate it with `bash "
    "scripts/hw_reports.sh`";

// A number of the report, or null when the field is absent, null or not a number.
const nlohmann::json* number_field(const nlohmann::json& row, const char* key) {
  const auto it = row.find(key);
  return it != row.end() && it->is_number() ? &*it : nullptr;
}

std::string fixed(const nlohmann::json& row, const char* key, int decimals) {
  const nlohmann::json* v = number_field(row, key);
  if (!v) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v->get<double>());
  return buf;
}

// Whole numbers as integers, others with two decimals.
std::string compact(const nlohmann::json& row, const char* key) {
  const nlohmann::json* v = number_field(row, key);
  if (!v) return "n/a";
  const double x = v->get<double>();
  char buf[64];
  if (std::nearbyint(x) == x)
    std::snprintf(buf, sizeof buf, "%.0f", x);
  else
    std::snprintf(buf, sizeof buf, "%.2f", x);
  return buf;
}

std::string text(const nlohmann::json& row, const char* key) {
  const auto it = row.find(key);
  return it != row.end() && it->is_string() ? it->get<std::string>() : std::string();
}

}  // namespace

std::filesystem::path hardware_report_path(const std::filesystem::path& data_dir) {
  return (data_dir / ".." / "hardware_report.json").lexically_normal();
}

std::string hardware_summary_line(const nlohmann::json& row) {
  std::string line = text(row, "kernel") + " " + text(row, "configuration") + ": ";
  line += fixed(row, "cycles_per_cell", 3) + " cycles/cell, latency " +
          compact(row, "latency_cycles") +
          " cycles (with back-pressure: " + fixed(row, "cycles_per_cell_backpressure", 3) + ", " +
          compact(row, "latency_cycles_backpressure") + "); ";
  line += compact(row, "lut4") + " LUT4 / " + compact(row, "dff") + " DFF / " +
          compact(row, "bram") + " BRAM; Fmax ";
  if (number_field(row, "fmax_mhz")) {
    line += fixed(row, "fmax_mhz", 1) + " MHz";
    if (number_field(row, "target_mhz")) {
      line += " vs " + compact(row, "target_mhz") + " MHz target: ";
      const auto met = row.find("target_met");
      line += met != row.end() && met->is_boolean() && met->get<bool>() ? "met" : "NOT met";
    }
  } else {
    line += "n/a";
  }
  if (const std::string note = text(row, "note"); !note.empty()) line += "; " + note;
  return line;
}

HardwareSummary read_hardware_summary(const std::filesystem::path& report) {
  HardwareSummary s;
  std::error_code ec;
  if (!std::filesystem::exists(report, ec)) {
    s.lines.emplace_back(kHint);
    s.json = {{"report", nullptr}, {"hint", "bash scripts/hw_reports.sh"}};
    return s;
  }
  const auto unreadable = [&](const std::string& why) {
    s.lines.push_back("hardware kernels: " + report.string() + ": " + why +
                      " (regenerate it with `bash scripts/hw_reports.sh`)");
    s.json = {{"report", report.string()}, {"error", why}};
    return s;
  };
  std::ifstream in(report, std::ios::binary);
  if (!in) return unreadable("cannot be opened");
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return unreadable("not valid JSON");
  const auto rows = j.find("summary");
  if (!j.is_object() || rows == j.end() || !rows->is_array())
    return unreadable("no \"summary\" array");

  s.found = true;
  const std::string date = j.contains("date") && j["date"].is_string()
                               ? j["date"].get<std::string>()
                               : std::string("undated");
  s.lines.push_back("hardware kernels (" + report.string() + ", " + date +
                    "; cycles and latency from Verilator, resources from Yosys synth_ice40, Fmax "
                    "from nextpnr-ice40 on an HX8K):");
  nlohmann::json kernels = nlohmann::json::array();
  for (const nlohmann::json& row : *rows) {
    if (!row.is_object()) continue;
    s.lines.push_back("  " + hardware_summary_line(row));
    kernels.push_back(row);
  }
  s.json = {{"report", report.string()}, {"date", date}, {"kernels", kernels}};
  if (j.contains("tools")) s.json["tools"] = j["tools"];
  if (j.contains("part")) s.json["part"] = j["part"];
  return s;
}

}  // namespace intgrid::cli
