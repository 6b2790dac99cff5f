// Inserting every scan of the bundled reference log (99 scans at their reference poses) into a
// fresh 5 cm grid, in intgrid's integer and double arithmetics: the benchmarks that
// intgrid_bench runs and that intgrid_peer_bench runs beside MRPT and OctoMap. Items are scans.
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/mapping.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/core/scan_insertion.hpp"
#include "intgrid/core/sensor_model.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/io/log_io.hpp"

namespace intgrid::bench {

inline constexpr double kMapCell = 0.05;
inline constexpr double kMapMargin = 1.0;
inline const core::GaussianBeamModel kMapModel{0.05, 0.0};

// The log and the grid covering it, read once.
struct LogFixture {
  core::Log log;
  core::GridGeometry geometry;
};
inline const LogFixture& reference_log() {
  static const LogFixture fixture = [] {
    LogFixture f;
    f.log = io::read_log(INTGRID_DATA_DIR "/malaga_telecom_loop_reference.log");
    f.geometry = core::geometry_covering(f.log.scans, kMapCell, kMapMargin);
    return f;
  }();
  return fixture;
}

inline void report_insertion(benchmark::State& state, const core::InsertionStats& stats) {
  state.SetItemsProcessed(static_cast<std::int64_t>(stats.scans));
  state.counters["cells_per_scan"] =
      stats.scans > 0 ? static_cast<double>(stats.cells_updated) / static_cast<double>(stats.scans)
                      : 0.0;
}

inline void BM_ScanInsertion_Int8(benchmark::State& state) {
  const LogFixture& fixture = reference_log();
  const std::span<const core::Scan> scans = fixture.log.scans;
  const core::SepsCodec codec =
      core::SepsCodec::for_levels(8, core::narrow_pmax(kMapCell, 0.05), 16);
  core::IndexScanInserter<std::int8_t> inserter(kMapModel, kMapCell, codec,
                                                core::VetoBound::strongest_claim);
  core::Grid<std::int8_t> grid(fixture.geometry, std::int8_t{0});
  // Warm-up: the inserter caches one quantized ISM per distinct reading.
  core::InsertionStats warm;
  for (const core::Scan& scan : scans) inserter.insert(grid, scan, warm);

  core::InsertionStats stats;
  for (auto _ : state) {
    state.PauseTiming();
    std::fill(grid.cells.begin(), grid.cells.end(), std::int8_t{0});
    state.ResumeTiming();
    for (const core::Scan& scan : scans) inserter.insert(grid, scan, stats);
    benchmark::DoNotOptimize(grid.cells.data());
    benchmark::ClobberMemory();
  }
  report_insertion(state, stats);
  // Cells the log moved off index 0 (probability 1/2): what the map learnt.
  state.counters["cells_known"] =
      static_cast<double>(grid.cells.size() - static_cast<std::size_t>(std::count(
                                                  grid.cells.begin(), grid.cells.end(), 0)));
}

inline void BM_ScanInsertion_DoubleBayes(benchmark::State& state) {
  const LogFixture& fixture = reference_log();
  const std::span<const core::Scan> scans = fixture.log.scans;
  core::ProbabilityGrid grid(fixture.geometry, 0.5);

  core::InsertionStats stats;
  for (auto _ : state) {
    state.PauseTiming();
    std::fill(grid.cells.begin(), grid.cells.end(), 0.5);
    state.ResumeTiming();
    for (const core::Scan& scan : scans) core::insert_scan(grid, scan, kMapModel, stats);
    benchmark::DoNotOptimize(grid.cells.data());
    benchmark::ClobberMemory();
  }
  report_insertion(state, stats);
}

}  // namespace intgrid::bench
