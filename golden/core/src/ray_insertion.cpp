#include "intgrid/core/ray_insertion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "intgrid/core/narrow_ism.hpp"
#include "intgrid/core/scan_insertion.hpp"

namespace intgrid::core {

std::vector<std::int32_t> make_sine_table_q16() {
  std::vector<std::int32_t> table(kAngleUnitsPerTurn);
  for (std::int32_t a = 0; a < kAngleUnitsPerTurn; ++a)
    table[static_cast<std::size_t>(a)] = static_cast<std::int32_t>(
        std::lround(std::sin(2.0 * std::numbers::pi * a / kAngleUnitsPerTurn) * 65536.0));
  return table;
}

namespace {

// Bins 0..max_range_mm / z_step_mm + 1, bin 0 empty; beam(z) gives the values of bin z.
template <class T, class Beam>
IsmTable<T> make_table(std::int32_t z_step_mm, std::int32_t max_range_mm, Beam&& beam) {
  std::vector<std::uint32_t> begin{0};
  std::vector<T> values;
  const std::int32_t bins = max_range_mm / z_step_mm + 2;
  for (std::int32_t b = 0; b < bins; ++b) {
    if (b > 0) beam(b * z_step_mm / 1000.0, values);
    begin.push_back(static_cast<std::uint32_t>(values.size()));
  }
  return make_ism_table(z_step_mm, std::move(begin), std::move(values));
}

}  // namespace

NarrowIsmTable make_index_ism_table(const GaussianBeamModel& model, double cell,
                                    const SepsCodec& codec, std::int32_t z_step_mm,
                                    std::int32_t max_range_mm, int empty_divisor) {
  IndexScanInserter<std::int8_t> inserter(model, cell, codec, VetoBound::strongest_claim,
                                          z_step_mm / 1000.0);
  return make_table<std::int8_t>(
      z_step_mm, max_range_mm, [&](double z, std::vector<std::int8_t>& out) {
        for (const std::int8_t n : inserter.beam_indices(z))
          out.push_back(
              n >= 0 ? n : static_cast<std::int8_t>(-((-n + empty_divisor - 1) / empty_divisor)));
      });
}

IsmTable<double> make_probability_ism_table(const GaussianBeamModel& model, double cell,
                                            std::int32_t z_step_mm, std::int32_t max_range_mm) {
  return make_table<double>(z_step_mm, max_range_mm, [&](double z, std::vector<double>& out) {
    const std::vector<double> ism =
        narrow_ism(model, z, cell, ism_cells_for_reading(model, z, cell));
    out.insert(out.end(), ism.begin(), ism.end());
  });
}

}  // namespace intgrid::core
