// The one sensor description (core::RangeSensor) and its check: every component that takes a
// range sensor accepts the same values and names the field the same way.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "intgrid/core/range_sensor.hpp"

namespace intgrid::core {
namespace {

// The message of check_range_sensor for s, or "" if it passes.
std::string refusal(const RangeSensor& s) {
  try {
    check_range_sensor(s, "sensor");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(RangeSensor, AcceptsTheBoundsAndNamesTheFieldPastThem) {
  EXPECT_EQ(refusal({0.03, 30.0}), "");
  EXPECT_EQ(refusal({0.001, 1000.0}), "");
  EXPECT_EQ(refusal({1.0, 0.001}), "");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double sigma : {0.0009, 1.0001, 0.0, -0.03, nan, inf})
    EXPECT_EQ(refusal({sigma, 30.0}).rfind("sensor.sigma ", 0), 0u) << sigma;
  for (const double range : {0.0, -1.0, 1000.1, nan, inf})
    EXPECT_EQ(refusal({0.03, range}).rfind("sensor.max_range ", 0), 0u) << range;
}

TEST(RangeSensor, NamesTheOwnersField) {
  try {
    check_range_sensor({0.0, 30.0}, "lidar");
    FAIL() << "a sigma of 0 passed";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("lidar.sigma ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace intgrid::core
