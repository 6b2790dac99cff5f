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
// origin: the reference starts where the odometry does): the ATE against the reference in
// metrics.json, every output written. The golden test (MapLocalizerData.*) measures 0.108 m.
TEST_F(Cli, LocalizeTracksTheBundledLogInItsMap) {
  const fs::path data = intgrid::test::data_dir();
  const CliRun r =
      run("localize --map " + (data / "malaga_telecom_map.yaml").string() + " --log " +
          (data / "malaga_telecom_loop.log").string() + " --initial 0 0 0 --reference " +
          (data / "malaga_telecom_loop_reference.log").string() + " --out " +
          (dir_ / "out").string() + " --threads 2");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"trajectory.txt", "fit.csv", "map.png", "metrics.json"})
    EXPECT_TRUE(fs::exists(dir_ / "out" / f)) << f;
  std::ifstream metrics(dir_ / "out" / "metrics.json");
  const std::string text((std::istreambuf_iterator<char>(metrics)), {});
  const auto number_after = [&](const std::string& key) {
    const std::size_t at = text.find("\"" + key + "\": ");
    EXPECT_NE(at, std::string::npos) << key;
    return std::stod(text.substr(at + key.size() + 4));
  };
  EXPECT_EQ(number_after("scans"), 225);
  EXPECT_EQ(number_after("matched_scans"), 225);
  EXPECT_LT(number_after("rmse_m"), 0.15);  // the localizer's, written before the odometry's
  std::ifstream fit(dir_ / "out" / "fit.csv");
  std::string line;
  std::size_t rows = 0;
  while (std::getline(fit, line)) ++rows;
  EXPECT_EQ(rows, 226u);  // the header and a row a scan
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
