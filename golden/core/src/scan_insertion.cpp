#include "intgrid/core/scan_insertion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/narrow_ism.hpp"

namespace intgrid::core {

RangeClass classify_range(double range, double max_range) {
  if (!std::isfinite(range)) return RangeClass::not_finite;
  if (range == 0.0) return RangeClass::zero;
  if (range < 0.0) return RangeClass::negative;
  if (range >= max_range) return RangeClass::at_or_over_max;
  return RangeClass::valid;
}

std::size_t ism_cells_for_reading(const GaussianBeamModel& model, double z, double cell) {
  return static_cast<std::size_t>(std::ceil((z + 8.0 * model.sigma(z)) / cell)) + 1;
}

void insert_scan(ProbabilityGrid& grid, const Scan& scan, const GaussianBeamModel& model,
                 InsertionStats& stats, RowBand rows) {
  const double cell = grid.geometry.resolution;
  const Pose2 pose = scan.sensor_pose();
  std::vector<double> ism;
  double* const cells = grid.cells.data();
  std::size_t updated = 0;
  for_each_valid_beam(scan, stats, [&](double z, Vec2 from, Vec2 to) {
    ism.resize(ism_cells_for_reading(model, z, cell));
    narrow_ism(model, z, cell, ism);
    const double* const beam = ism.data();
    for_each_footprint_cell(
        grid.geometry, {pose.x, pose.y}, from, to, cell, ism.size(),
        [&](std::size_t index, std::size_t k) {
          cells[index] = fuse_probabilities(cells[index], beam[k - 1]);
          ++updated;
        },
        rows);
  });
  stats.cells_updated += updated;
}

template <class Index>
IndexScanInserter<Index>::IndexScanInserter(const GaussianBeamModel& model, double cell,
                                            const SepsCodec& codec, VetoBound veto, double z_step)
    : model_(model), cell_(cell), codec_(codec), veto_(veto), z_step_(z_step) {
  check_model(model);
  if (!(cell > 0.0) || !std::isfinite(cell))
    fail<std::invalid_argument>("cell size must be positive");
  if (!(z_step > 0.0) || !std::isfinite(z_step))
    fail<std::invalid_argument>("z step must be positive");
  if (codec.max_index() > std::numeric_limits<Index>::max())
    fail<std::invalid_argument>("the S_eps index width does not fit the grid's cell type");
}

template <class Index>
const std::vector<Index>& IndexScanInserter<Index>::beam_indices(double z) {
  const long long bin = ism_range_bin(z, z_step_);
  std::vector<Index>& indices = beams_[bin];
  if (!indices.empty()) return indices;
  const double zq = static_cast<double>(bin) * z_step_;
  // The exact ISM, extended until it quantizes to 0 (no information) at its end.
  std::vector<double> ism;
  for (std::size_t cells = ism_cells_for_reading(model_, zq, cell_);; cells *= 2) {
    if (cells > (std::size_t{1} << 26))
      fail<std::invalid_argument>("eps is too small: the ISM never quantizes to index 0");
    ism.resize(cells);
    narrow_ism(model_, zq, cell_, ism);
    if (codec_.quantize_conservative(ism.back()) == 0) break;
  }
  // Quantize once, then drop the trailing cells that say nothing (index 0).
  indices.resize(ism.size());
  int strongest_claim = 0;
  for (std::size_t k = 0; k < ism.size(); ++k) {
    const int n = codec_.quantize_conservative(ism[k]);
    indices[k] = static_cast<Index>(n);
    strongest_claim = std::max(strongest_claim, n);
  }
  std::size_t last = indices.size();
  while (last > 1 && indices[last - 1] == 0) --last;
  indices.resize(last);
  if (veto_ == VetoBound::strongest_claim)
    for (Index& n : indices) n = static_cast<Index>(std::max<int>(n, -strongest_claim));
  return indices;
}

template <class Index>
void IndexScanInserter<Index>::insert(Grid<Index>& grid, const Scan& scan, InsertionStats& stats,
                                      RowBand rows) {
  if (grid.geometry.resolution != cell_)
    fail<std::invalid_argument>("the grid's resolution differs from the inserter's cell size");
  const Pose2 pose = scan.sensor_pose();
  const int max_index = codec_.max_index();
  Index* const cells = grid.cells.data();
  std::size_t updated = 0;  // local: the cells' byte stores could alias a member
  for_each_valid_beam(scan, stats, [&](double z, Vec2 from, Vec2 to) {
    const std::vector<Index>& indices = beam_indices(z);
    const Index* const ism = indices.data();
    for_each_footprint_cell(
        grid.geometry, {pose.x, pose.y}, from, to, cell_, indices.size(),
        [&](std::size_t index, std::size_t k) {
          cells[index] = fuse_indices(cells[index], ism[k - 1], max_index);
          ++updated;
        },
        rows);
  });
  stats.cells_updated += updated;
}

template class IndexScanInserter<std::int8_t>;
template class IndexScanInserter<std::int16_t>;

}  // namespace intgrid::core
