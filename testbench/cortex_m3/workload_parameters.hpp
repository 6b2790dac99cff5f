// The settings of the embedded workload that the input generator shares with it.
#pragma once

#include <cstdint>

#include "intgrid/core/resolution.hpp"
#include "intgrid/core/sensor_model.hpp"
#include "intgrid/core/seps.hpp"

namespace intgrid::embedded {

inline constexpr double kSigma = 0.03;  // m, the sensor's range noise
inline constexpr std::int32_t kMaxRangeMm = 8000;
inline constexpr std::int32_t kInsertionCellMm = 50;
inline constexpr double kInsertionCell = kInsertionCellMm / 1000.0;  // m
inline constexpr std::int32_t kInsertionZStepMm = kInsertionCellMm / 8;

inline core::GaussianBeamModel beam_model() {
  return {kSigma, 0.0};
}
// A reading's strongest occupied index is 16, on 8 bits.
inline core::SepsCodec insertion_codec() {
  return core::SepsCodec::for_levels(8, core::narrow_pmax(kInsertionCell, kSigma), 16);
}

}  // namespace intgrid::embedded
