// Mapping with known poses: every scan of a log inserted into one grid.
#pragma once

#include <cstdint>
#include <functional>
#include <span>

#include "intgrid/core/scan_insertion.hpp"

namespace intgrid::core {

// Told after each scan: scans done, scans in all.
using Progress = std::function<void(std::size_t, std::size_t)>;

// A grid of the given resolution covering every sensor position and every valid
// reading's end point of the scans, plus `margin` metres on each side.
// Throws std::invalid_argument if no scan has a valid reading.
GridGeometry geometry_covering(std::span<const Scan> scans, double resolution, double margin);

// Every scan, in the log's order, into the rows `rows` of grid: those rows' cells as the whole
// grid's insertion gives them, whatever other bands do meanwhile.
void insert_scans(ProbabilityGrid& grid, std::span<const Scan> scans,
                  const GaussianBeamModel& model, InsertionStats& stats, RowBand rows = {},
                  const Progress& progress = {});
template <class Index>
void insert_scans(Grid<Index>& grid, std::span<const Scan> scans,
                  IndexScanInserter<Index>& inserter, InsertionStats& stats, RowBand rows = {},
                  const Progress& progress = {}) {
  for (std::size_t i = 0; i < scans.size(); ++i) {
    inserter.insert(grid, scans[i], stats, rows);
    if (progress) progress(i + 1, scans.size());
  }
}

// The whole log in double precision (Bayesian fusion), every cell starting at 1/2.
ProbabilityGrid map_probabilities(std::span<const Scan> scans, const GaussianBeamModel& model,
                                  const GridGeometry& geometry, InsertionStats& stats,
                                  const Progress& progress = {});

// The whole log in S_eps indices (index addition), every cell starting at 0.
template <class Index>
Grid<Index> map_indices(std::span<const Scan> scans, IndexScanInserter<Index>& inserter,
                        const GridGeometry& geometry, InsertionStats& stats,
                        const Progress& progress = {}) {
  Grid<Index> grid(geometry, Index{0});
  insert_scans(grid, scans, inserter, stats, {}, progress);
  return grid;
}

// The probabilities p_n of an index grid.
template <class Index>
ProbabilityGrid to_probabilities(const Grid<Index>& grid, const SepsCodec& codec) {
  ProbabilityGrid out(grid.geometry, 0.5);
  for (std::size_t i = 0; i < grid.cells.size(); ++i)
    out.cells[i] = codec.probability(grid.cells[i]);
  return out;
}

}  // namespace intgrid::core
