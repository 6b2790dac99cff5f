// The integer path's units, and the conversions into them from SI units, named in domain words:
// positions and ranges in millimetres, headings in angle units (2^16 a turn), times in
// milliseconds. Every module that quantizes a metre or a radian for the per-scan path does it
// here, with one rounding (to the nearest, halves away from zero).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace intgrid::core {

inline constexpr std::int32_t kAngleUnitsPerTurn = 65536;
inline constexpr double kRadiansPerAngleUnit = 2.0 * std::numbers::pi / kAngleUnitsPerTurn;

inline std::int64_t millimetres(double metres) {
  return std::llround(metres * 1000.0);
}
inline std::int64_t milliseconds(double seconds) {
  return std::llround(seconds * 1000.0);
}
inline std::int64_t angle_units(double radians) {
  return std::llround(radians / kRadiansPerAngleUnit);
}
constexpr double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

}  // namespace intgrid::core
