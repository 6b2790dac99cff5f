// Range readings in the sensor frame, as global localization takes them.
#pragma once

#include <vector>

#include "intgrid/core/types.hpp"

namespace intgrid::localization {

// One reading in the sensor frame.
struct RangeReading {
  double range = 0.0;    // m
  double bearing = 0.0;  // rad, from the sensor's heading
};

// The usable readings of a scan (valid for the scan and below max_range), `beams` of them spread
// evenly over the scan (all when beams <= 0 or beams >= the usable count): usable reading
// floor(i * usable / beams) for i = 0..beams-1.
std::vector<RangeReading> readings_of(const core::Scan& scan, int beams, double max_range);

}  // namespace intgrid::localization
