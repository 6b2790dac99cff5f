// `intgrid localize`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_fixture.hpp"
#include "data_dir.hpp"

namespace {

using namespace intgrid::cli_test;

// The bundled log in the bundled map of its courtyard, from the reference's first pose (the
// origin: the reference starts where the odometry does) and with no initial pose (found by global
// localization): the ATE against the reference in metrics.json, every scan tracked, every output
// written. The golden tests (MapLocalizerData.*, KnownMapLocalizerData.*) measure 0.108 m and
// 0.105 m.
void localizes_the_bundled_log(const fs::path& dir, const std::string& initial) {
  const fs::path data = intgrid::test::data_dir();
  const CliRun r = run("localize --map " + (data / "malaga_telecom_map.yaml").string() + " --log " +
                       (data / "malaga_telecom_loop.log").string() + initial + " --reference " +
                       (data / "malaga_telecom_loop_reference.log").string() + " --out " +
                       (dir / "out").string() + " --threads 2");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"trajectory.txt", "fit.csv", "map.png", "metrics.json"})
    EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
  std::ifstream metrics(dir / "out" / "metrics.json");
  const std::string text((std::istreambuf_iterator<char>(metrics)), {});
  const auto number_after = [&](const std::string& key) {
    const std::size_t at = text.find("\"" + key + "\": ");
    EXPECT_NE(at, std::string::npos) << key;
    return std::stod(text.substr(at + key.size() + 4));
  };
  EXPECT_EQ(number_after("scans"), 225);
  EXPECT_EQ(number_after("tracked_scans"), 225);
  EXPECT_EQ(number_after("matched_scans"), 225);
  EXPECT_EQ(number_after("lost"), 0);
  EXPECT_EQ(number_after("first_pose_scan"), 0);
  EXPECT_LT(number_after("rmse_m"), 0.15);  // the localizer's, written before the odometry's
  std::ifstream fit(dir / "out" / "fit.csv");
  std::string line, header;
  std::getline(fit, header);
  EXPECT_EQ(header, "t,state,evidence,matched,wide,hits,fit,fused_scans");
  std::size_t rows = 0, tracking = 0;
  while (std::getline(fit, line)) {
    ++rows;
    tracking += line.find(",tracking,") != std::string::npos;
  }
  EXPECT_EQ(rows, 225u);  // a row a scan
  EXPECT_EQ(tracking, 225u);
}

TEST_F(Cli, LocalizeTracksTheBundledLogInItsMap) {
  localizes_the_bundled_log(dir_, " --initial 0 0 0");
}

TEST_F(Cli, LocalizeFindsTheBundledLogInItsMapWithNoInitialPose) {
  localizes_the_bundled_log(dir_, "");
}

TEST_F(Cli, LocalizeNeedsAWholeInitialPose) {
  const fs::path data = intgrid::test::data_dir();
  const CliRun r = run("localize --map " + (data / "malaga_telecom_map.yaml").string() + " --log " +
                       (data / "malaga_telecom_loop.log").string() + " --initial 0 0 --out " +
                       (dir_ / "out").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--initial"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

}  // namespace
