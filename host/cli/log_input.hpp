// Logs as the commands read them: the records the reader skipped (CARMEN messages the pipeline
// does not use, or a line whose keyword was damaged) are counted and shown, never lost unseen.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "intgrid/core/types.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/log_io.hpp"

namespace intgrid::cli {

struct LogInput {
  core::Log log;
  io::SkippedRecords skipped;  // record type -> lines skipped
};

// Reads `file` (either format); when records were skipped, says so on one stderr line
// ("intgrid: FILE: skipped records: FLXSER 1, PARAM 2").
LogInput read_log_input(const std::filesystem::path& file);

// {"FLXSER": 1, "PARAM": 2}, for the commands' JSON and metrics.json.
nlohmann::json skipped_records_json(const io::SkippedRecords& skipped);

}  // namespace intgrid::cli
