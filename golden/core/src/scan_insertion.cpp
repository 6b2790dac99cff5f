#include "intgrid/core/scan_insertion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
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
  first_cell_sq_ = least_rho_sq_reaching(1, cell);
}

template <class Index>
const std::vector<Index>& IndexScanInserter<Index>::beam_indices(double z) {
  return ism(z).indices;
}

template <class Index>
const typename IndexScanInserter<Index>::BeamIsm& IndexScanInserter<Index>::ism(double z) {
  const long long bin = ism_range_bin(z, z_step_);
  BeamIsm& beam = beams_[bin];
  if (!beam.indices.empty()) return beam;
  std::vector<Index>& indices = beam.indices;
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
  // The constant core: cells 1..repeated take indices[0]; at least the last cell is left out, so
  // that the core ends a cell inside the footprint's reach.
  beam.constant = indices[0];
  std::size_t repeated = 1;
  while (repeated + 1 < indices.size() && indices[repeated] == indices[0]) ++repeated;
  if (repeated > 1) beam.core_sq = least_rho_sq_reaching(repeated + 1, cell_);
  return beam;
}

template <class Index>
std::size_t IndexScanInserter<Index>::insert_beam(Grid<Index>& grid, Vec2 sensor,
                                                  const ScanBeam& beam, RowBand rows,
                                                  double inner_sq) const {
  Index* const cells = grid.cells.data();
  const Index* const values = beam.ism->indices.data();
  const int max_index = codec_.max_index();
  std::size_t updated = 0;  // local: the cells' byte stores could alias a member
  for_each_footprint_cell(
      grid.geometry, sensor, beam.from, beam.to, cell_, beam.ism->indices.size(),
      [&](std::size_t index, std::size_t k) {
        cells[index] = fuse_indices(cells[index], values[k - 1], max_index);
        ++updated;
      },
      rows, inner_sq);
  return updated;
}

template <class Index>
void IndexScanInserter<Index>::insert(Grid<Index>& grid, const Scan& scan, InsertionStats& stats,
                                      RowBand rows) {
  if (grid.geometry.resolution != cell_)
    fail<std::invalid_argument>("the grid's resolution differs from the inserter's cell size");
  const Pose2 pose = scan.sensor_pose();
  const Vec2 sensor{pose.x, pose.y};
  scan_beams_.clear();
  for_each_valid_beam(scan, stats, [&](double z, Vec2 from, Vec2 to) {
    scan_beams_.push_back({from, to, &ism(z)});
  });
  std::size_t updated = 0;
  Index* const cells = grid.cells.data();
  const int max_index = codec_.max_index();
  const std::ptrdiff_t width = grid.geometry.width;
  const auto same = [](Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; };
  for (std::size_t g = 0; g < scan_beams_.size();) {
    const BeamIsm& first = *scan_beams_[g].ism;
    if (first.core_sq <= 0.0) {
      updated += insert_beam(grid, sensor, scan_beams_[g], rows, 0.0);
      ++g;
      continue;
    }
    // The group: beams g..end - 1, neighbours (sharing a boundary, in either turning sense) of
    // one constant, less than a quarter turn wide, whose cores end within kGroupDepth of the
    // nearest. The depth only trades the group's runs against its beams' own: any value gives
    // the same cells.
    constexpr double kGroupDepth = 0.5;  // metres
    Vec2 from = scan_beams_[g].from, to = scan_beams_[g].to;
    double nearest = first.core_sq, farthest = first.core_sq;
    std::size_t end = g + 1;
    for (; end < scan_beams_.size(); ++end) {
      const ScanBeam& beam = scan_beams_[end];
      if (beam.ism->core_sq <= 0.0 || beam.ism->constant != first.constant) break;
      const bool after = same(beam.from, to), before = same(beam.to, from);
      if (!after && !before) break;
      const Vec2 new_from = before ? beam.from : from, new_to = after ? beam.to : to;
      if (!(cross(new_from, new_to) > 0.0 && dot(new_from, new_to) > 0.0)) break;
      const double new_nearest = std::min(nearest, beam.ism->core_sq);
      const double new_farthest = std::max(farthest, beam.ism->core_sq);
      if (std::sqrt(new_farthest) - std::sqrt(new_nearest) > kGroupDepth) break;
      from = new_from;
      to = new_to;
      nearest = new_nearest;
      farthest = new_farthest;
    }
    for_each_sector_run(
        grid.geometry, sensor, from, to, first_cell_sq_, nearest,
        [&, constant = first.constant](const SectorRun& run) {
          // Copies, not references: the cells' byte stores could alias what a reference names,
          // which would reload it every cell and keep the row's loop from being vectorized.
          const int bound = max_index;
          const std::ptrdiff_t stride = run.along_rows ? 1 : width;
          const int n = run.last - run.first + 1;
          updated += static_cast<std::size_t>(n);
          Index* c = cells + run.index(grid.geometry, run.first);
          if (stride == 1) {
            for (int i = 0; i < n; ++i) c[i] = fuse_indices(c[i], constant, bound);
          } else {
            for (int i = 0; i < n; ++i, c += stride) *c = fuse_indices(*c, constant, bound);
          }
        },
        rows);
    for (; g < end; ++g) updated += insert_beam(grid, sensor, scan_beams_[g], rows, nearest);
  }
  stats.cells_updated += updated;
}

template class IndexScanInserter<std::int8_t>;
template class IndexScanInserter<std::int16_t>;

}  // namespace intgrid::core
