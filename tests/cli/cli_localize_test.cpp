// `intgrid localize`.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

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
  EXPECT_EQ(header, "t,state,verified,refixed,evidence,matched,wide,hits,fit,fused_scans");
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

// --relations: relations between the reference's poses 20 scans apart, scored on the localized
// trajectory and on the raw odometry: metrics.json's two summaries, relations.csv a line each.
// A file whose relations match no scan of the log is an input error naming it. --tum: the
// tracked scans' poses in the TUM format.
TEST_F(Cli, LocalizeScoresTheRelationsOfTheLog) {
  const fs::path data = intgrid::test::data_dir();
  std::ifstream reference(data / "malaga_telecom_loop_reference.log");
  struct Stamped {
    double t, x, y, theta;
  };
  std::vector<Stamped> poses;
  for (std::string line; std::getline(reference, line);) {
    std::istringstream in(line);
    std::vector<std::string> fields{std::istream_iterator<std::string>(in), {}};
    if (fields.empty() || fields[0] != "RLASER") continue;
    const std::size_t n = fields.size();
    poses.push_back({std::stod(fields[n - 1]), std::stod(fields[n - 7]), std::stod(fields[n - 6]),
                     std::stod(fields[n - 5])});
  }
  ASSERT_GT(poses.size(), 90u);
  std::ostringstream relations;
  relations.precision(17);
  std::size_t written = 0;
  for (std::size_t i = 0; i + 20 < poses.size(); i += 2, ++written) {
    const Stamped &a = poses[i], &b = poses[i + 20];
    const double c = std::cos(a.theta), s = std::sin(a.theta), dx = b.x - a.x, dy = b.y - a.y;
    relations << a.t << ' ' << b.t << ' ' << c * dx + s * dy << ' ' << -s * dx + c * dy << " 0 0 0 "
              << std::remainder(b.theta - a.theta, 2.0 * M_PI) << '\n';
  }
  const fs::path file = write("telecom.relations", relations.str());
  const std::string common = "localize --map " + (data / "malaga_telecom_map.yaml").string() +
                             " --log " + (data / "malaga_telecom_loop.log").string() +
                             " --threads 2 --out " + (dir_ / "out").string();
  const fs::path tum = dir_ / "poses.tum";
  const CliRun r = run(common + " --relations " + file.string() + " --tum " + tum.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(lines_of(file_text(tum)).size(), 225u);  // --tum: a line a tracked scan
  const std::string metrics = file_text(dir_ / "out" / "metrics.json");
  const auto mean_of = [&](const std::string& key) {
    const std::string object = json_object(metrics, key);
    const std::size_t at = object.find("\"trans_mean\": ");
    EXPECT_NE(at, std::string::npos) << key;
    return std::stod(object.substr(at + 14));
  };
  // Localized, a relation's error is the map's and the match's (the trajectory is 0.105 m from
  // the reference); the odometry drifts over 20 scans.
  EXPECT_LT(mean_of("relations"), 0.15);
  EXPECT_GT(mean_of("odometry_relations"), 2.0 * mean_of("relations"));
  EXPECT_EQ(lines_of(file_text(dir_ / "out" / "relations.csv")).size(), written + 1);

  const fs::path other = write("other.relations", "5 6 0.1 0 0 0 0 0\n");
  fs::remove_all(dir_ / "out");
  const CliRun refused = run(common + " --relations " + other.string());
  expect_error(refused, other.string() + ":1: t1: none of its 1 relations matches a scan");
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// The same trajectory and fits, byte for byte, on one thread and on two (the global
// localization's pose grid and each scan's match split over them).
TEST_F(Cli, LocalizeIsTheSameForAnyThreadCount) {
  const fs::path data = intgrid::test::data_dir();
  for (const char* threads : {"1", "2"}) {
    const CliRun r = run("localize --map " + (data / "malaga_telecom_map.yaml").string() +
                         " --log " + (data / "malaga_telecom_loop.log").string() + " --threads " +
                         threads + " --out " + (dir_ / threads).string());
    ASSERT_EQ(r.status, 0) << r.output;
  }
  for (const char* file : {"trajectory.txt", "fit.csv"})
    EXPECT_EQ(file_text(dir_ / "1" / file), file_text(dir_ / "2" / file)) << file;
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
