#include "cli/log_input.hpp"

#include <cstdio>
#include <string>

namespace intgrid::cli {

LogInput read_log_input(const std::filesystem::path& file) {
  LogInput input;
  input.log = io::read_log(file, &input.skipped);
  if (!input.skipped.empty()) {
    std::string counts;
    for (const auto& [type, lines] : input.skipped)
      counts += (counts.empty() ? "" : ", ") + io::quote_input(type) + " " + std::to_string(lines);
    std::fprintf(stderr, "intgrid: %s: skipped records: %s\n", file.string().c_str(),
                 counts.c_str());
  }
  return input;
}

nlohmann::json skipped_records_json(const io::SkippedRecords& skipped) {
  nlohmann::json counts = nlohmann::json::object();
  for (const auto& [type, lines] : skipped) counts[type] = lines;
  return counts;
}

}  // namespace intgrid::cli
