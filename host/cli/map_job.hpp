// The `map` job: a log into one occupancy grid with the log's own poses, written
// as a ROS map (YAML + PGM) and a PNG with the sensor's path drawn on it.
#pragma once

#include <filesystem>
#include <optional>

#include "cli/memory_budget.hpp"
#include "intgrid/core/map_compare.hpp"
#include "intgrid/core/mapping.hpp"
#include "intgrid/io/log_io.hpp"

namespace intgrid::cli {

struct MapJobOptions {
  std::filesystem::path log;
  std::filesystem::path out;
  double resolution = 0.05;  // cell size (m): --cell
  core::Arithmetic arithmetic = core::Arithmetic::integer;
  core::GaussianBeamModel model{0.05, 0.0};
  int bits = 8;
  int levels = 16;            // eps from the ISM's Pmax: p_levels = Pmax
  std::optional<double> eps;  // overrides levels
  core::VetoBound veto = core::VetoBound::strongest_claim;
  // Threads inserting the log, each into its own band of the grid's rows (0: every core); the
  // same map for any count, bit for bit: every cell takes the same fusions in the same order.
  int threads = 0;
  double margin = 1.0;                                     // metres of grid around what the log saw
  double max_memory_bytes = default_memory_limit_bytes();  // --max-memory
};

struct MapJobResult {
  core::ProbabilityGrid map;
  core::InsertionStats stats;
  std::optional<core::SepsCodec> codec;  // the integer path's
  double seconds = 0.0;                  // insertion only, not I/O
  io::SkippedRecords skipped_records;    // the log's records the reader skipped, by type
};

MapJobResult run_map_job(const MapJobOptions& options);

}  // namespace intgrid::cli
