// Scan insertion: one exact narrow ISM per beam of a 2D range scan, range-mapped
// onto a world grid over the beam's footprint and fused into it, either as
// probabilities (Bayesian fusion, double) or as S_eps indices (integer addition).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "intgrid/core/footprint.hpp"
#include "intgrid/core/grid.hpp"
#include "intgrid/core/sensor_model.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/types.hpp"

namespace intgrid::core {

// Why a reading was or was not inserted.
enum class RangeClass { valid, zero, not_finite, negative, at_or_over_max };
RangeClass classify_range(double range, double max_range);

// Counts over every scan inserted so far.
struct InsertionStats {
  std::size_t scans = 0;
  std::size_t readings = 0;
  std::size_t inserted = 0;
  std::size_t zero = 0;
  std::size_t not_finite = 0;
  std::size_t negative = 0;
  std::size_t at_or_over_max = 0;
  std::size_t cells_updated = 0;
  std::size_t skipped() const { return zero + not_finite + negative + at_or_over_max; }
};

// How many line-of-sight cells a reading's ISM is computed over: past z + 8
// sigma(z) the ISM is 1/2 to 1e-14 and carries no information.
std::size_t ism_cells_for_reading(const GaussianBeamModel& model, double z, double cell);

// Calls beam(z, from, to) for every valid reading of the scan, with the world
// boundary vectors of its angular footprint, and counts the invalid ones.
template <class Beam>
void for_each_valid_beam(const Scan& scan, InsertionStats& stats, Beam&& beam) {
  const Pose2 sensor = scan.sensor_pose();
  ++stats.scans;
  // Boundary j lies between beams j - 1 and j; adjacent beams share it exactly.
  const bool counter_clockwise = scan.dangle >= 0.0;
  const auto boundary = [&](std::size_t j) {
    return unit_vector(sensor.theta + scan.angle0 + (static_cast<double>(j) - 0.5) * scan.dangle);
  };
  Vec2 previous = boundary(0);
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const Vec2 next = boundary(i + 1);
    const double z = scan.ranges[i];
    ++stats.readings;
    switch (classify_range(z, scan.max_range)) {
      case RangeClass::valid:
        ++stats.inserted;
        if (counter_clockwise)
          beam(z, previous, next);
        else
          beam(z, next, previous);
        break;
      case RangeClass::zero:
        ++stats.zero;
        break;
      case RangeClass::not_finite:
        ++stats.not_finite;
        break;
      case RangeClass::negative:
        ++stats.negative;
        break;
      case RangeClass::at_or_over_max:
        ++stats.at_or_over_max;
        break;
    }
    previous = next;
  }
}

// Double-precision insertion: the exact ISM of each reading, fused by Bayes' rule, into the
// cells of the rows `rows`.
void insert_scan(ProbabilityGrid& grid, const Scan& scan, const GaussianBeamModel& model,
                 InsertionStats& stats, RowBand rows = {});

// How far one reading may push a cell toward empty. The exact ISM calls the
// cells before z empty with near certainty, so one grazing or misaligned beam
// would erase a wall that many beams saw; bounding each reading's empty indices
// by its own strongest occupied index (docs/algorithms.md 7, rule 2) weighs a pass
// through a cell like one hit on it.
enum class VetoBound { none, strongest_claim };

// The step of the reading values an integer inserter keeps one quantized ISM for: 1 mm, the
// resolution of the logs.
inline constexpr double kIsmRangeStep = 0.001;

// The bin a reading of z metres falls in, for ISMs kept every z_step metres: round(z / z_step).
// The inserter and any estimate of how many ISMs it will keep count bins alike.
inline long long ism_range_bin(double z, double z_step) {
  return std::llround(z / z_step);
}

// Integer insertion. The exact ISM of each reading is quantized (conservatively)
// to S_eps indices once per reading value, on a grid of z_step metres, and then applied by
// saturating index addition.
//
// A quantized ISM is one constant from the sensor to near the reading (a 20 m reading at 5 cm:
// 398 of its 401 cells are the veto's bound), so a scan is inserted in two parts that together
// visit each beam's footprint cells as `for_each_footprint_cell` names them, once each with the
// same index: neighbouring beams of one constant form a group, whose sector is filled with it in
// runs out to the nearest distance where one of its beams' constant ends; each beam's cells
// beyond that take their own indices. Fewer, longer runs: the set-up of a beam's many short lines
// was the cost. Groups are inserted in the scan's order and are less than a quarter turn wide, so
// where a scan of more than a turn overlaps itself, a cell's two fusions still come in the
// scan's order (saturation makes the order matter).
template <class Index>
class IndexScanInserter {
 public:
  IndexScanInserter(const GaussianBeamModel& model, double cell, const SepsCodec& codec,
                    VetoBound veto = VetoBound::none, double z_step = kIsmRangeStep);

  // Into the cells of the rows `rows`. Requires grid resolution == cell.
  void insert(Grid<Index>& grid, const Scan& scan, InsertionStats& stats, RowBand rows = {});
  // The indices of line-of-sight cells 1..n for the reading z (rounded to z_step).
  const std::vector<Index>& beam_indices(double z);
  const SepsCodec& codec() const { return codec_; }

 private:
  // One reading's quantized ISM: the indices of line-of-sight cells 1..n, and the cells closer
  // than core_sq (squared metres, a cell centre's |v|^2 as the footprint computes it), whose
  // indices are all `constant`; core_sq 0 when the first index is not repeated.
  struct BeamIsm {
    std::vector<Index> indices;
    Index constant = 0;
    double core_sq = 0.0;
  };
  // A valid reading of the scan being inserted: its footprint and its ISM.
  struct ScanBeam {
    Vec2 from, to;
    const BeamIsm* ism;
  };
  const BeamIsm& ism(double z);
  // The footprint cells of one beam at squared distances >= inner_sq, fused; returns how many.
  std::size_t insert_beam(Grid<Index>& grid, Vec2 sensor, const ScanBeam& beam, RowBand rows,
                          double inner_sq) const;

  GaussianBeamModel model_;
  double cell_;
  SepsCodec codec_;
  VetoBound veto_;
  double z_step_;
  double first_cell_sq_;                          // the least |v|^2 whose line-of-sight cell is 1
  std::unordered_map<long long, BeamIsm> beams_;  // by round(z / z_step); nodes do not move
  std::vector<ScanBeam> scan_beams_;
};

extern template class IndexScanInserter<std::int8_t>;
extern template class IndexScanInserter<std::int16_t>;

}  // namespace intgrid::core
