// A range sensor as the ISMs, the matchers and the localization model it: the noise of one
// reading and the range past which readings say nothing. One description for both SLAM engines,
// global localization and the command (--sigma, --max-range); each component that uses it owns
// its default, and checks it with check_range_sensor. The beam layout (start angle, spacing,
// count) is not here: it comes with each scan (core::Scan).
#pragma once

#include <cmath>
#include <string>

#include "intgrid/core/failure.hpp"

namespace intgrid::core {

struct RangeSensor {
  double sigma = 0.03;      // range noise of a reading: the beam model's standard deviation (m)
  double max_range = 30.0;  // readings at or past this are not used (m)
};

// The ranges every component accepts: sigma from 1 mm (the integer path's unit) to 1 m (wider
// says nothing a cell could hold), max_range positive up to 1 km (a 2D laser's range, and the
// millimetres of the integer path fit 32 bits). Throws std::invalid_argument naming the field
// as `<owner>.sigma` or `<owner>.max_range`.
inline void check_range_sensor(const RangeSensor& s, const std::string& owner) {
  require_field(std::isfinite(s.sigma) && s.sigma >= 0.001 && s.sigma <= 1.0, owner + ".sigma",
                "must be in [0.001, 1] metres");
  require_field(std::isfinite(s.max_range) && s.max_range > 0.0 && s.max_range <= 1000.0,
                owner + ".max_range", "must be in (0, 1000] metres");
}

}  // namespace intgrid::core
