// KnownMapLocalizer's settings: each bad one refused, named by its field.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "intgrid/navigation/known_map_localizer.hpp"

namespace intgrid::navigation {
namespace {

TEST(KnownMapLocalizer, RefusesABadSettingNamingItsField) {
  EXPECT_NO_THROW(check_known_map_localizer_config(KnownMapLocalizerConfig{}));
  const std::vector<std::pair<std::string, std::function<void(KnownMapLocalizerConfig&)>>> bad = {
      {"lost.fit_share", [](KnownMapLocalizerConfig& c) { c.lost.fit_share = 0.0; }},
      {"lost.fit_share", [](KnownMapLocalizerConfig& c) { c.lost.fit_share = std::nan(""); }},
      {"lost.scans", [](KnownMapLocalizerConfig& c) { c.lost.scans = 0; }},
      {"lost.recent", [](KnownMapLocalizerConfig& c) { c.lost.recent = 0; }},
      {"verify_every", [](KnownMapLocalizerConfig& c) { c.verify_every = 0.0; }},
      {"contest_scans", [](KnownMapLocalizerConfig& c) { c.contest_scans = 0; }},
      {"step_position", [](KnownMapLocalizerConfig& c) { c.sequence.step_position = -1.0; }},
      {"sensor.sigma", [](KnownMapLocalizerConfig& c) { c.tracking.sensor.sigma = 0.0; }},
      {"pose_res", [](KnownMapLocalizerConfig& c) { c.global.pose_res = -0.2; }},
  };
  for (const auto& [field, spoil] : bad) {
    KnownMapLocalizerConfig c;
    spoil(c);
    try {
      check_known_map_localizer_config(c);
      ADD_FAILURE() << field << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
}

TEST(KnownMapLocalizer, NamesTheStates) {
  EXPECT_STREQ(state_name(LocalizerState::locating), "locating");
  EXPECT_STREQ(state_name(LocalizerState::tracking), "tracking");
  EXPECT_STREQ(state_name(LocalizerState::lost), "lost");
  EXPECT_STREQ(state_name(LocalizerState::recovering), "recovering");
}

}  // namespace
}  // namespace intgrid::navigation
