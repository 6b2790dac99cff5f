// `intgrid simulate`, and `intgrid map` on a simulated log.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cli_fixture.hpp"
#include "data_dir.hpp"

namespace {

using namespace intgrid::cli_test;

std::size_t records(const std::string& log, const std::string& type) {
  std::size_t n = 0;
  for (const std::string& line : lines_of(log)) n += line.rfind(type + " ", 0) == 0 ? 1 : 0;
  return n;
}

TEST_F(Cli, SimulateWritesEveryFileAndTheRequestedScans) {
  const fs::path out = dir_ / "sim";
  const CliRun r = run("simulate --out " + out.string() + " --scans 25 --obstacles 3 --seed 5");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"sim.log", "truth.log", "world.yaml", "world.pgm", "world.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  expect_png(out / "world.png");
  EXPECT_NE(r.output.find("\"scans\": 25"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"seed\": 5"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find((out / "sim.log").string()), std::string::npos) << r.output;
  // sim.log: a scan and an odometry record per step; truth.log: the scans alone.
  const std::string sim = file_text(out / "sim.log"), truth = file_text(out / "truth.log");
  EXPECT_EQ(records(sim, "RLASER"), 25u);
  EXPECT_EQ(records(sim, "ODOM"), 25u);
  EXPECT_EQ(records(truth, "RLASER"), 25u);
  EXPECT_EQ(records(truth, "ODOM"), 0u);
  // The project's reader takes both back: mapping them sees 25 scans of 361 readings.
  for (const char* log : {"sim.log", "truth.log"}) {
    const CliRun m = run("map --log " + (out / log).string() + " --out " + (dir_ / "map").string() +
                         " --cell 0.1 --json");
    ASSERT_EQ(m.status, 0) << m.output;
    EXPECT_NE(m.output.find("\"scans\": 25,"), std::string::npos) << m.output;
    EXPECT_NE(m.output.find("\"readings\": 9025,"), std::string::npos) << m.output;
  }
  // The world map reads back, and the true path of the default floorplan is within it.
  const CliRun c = run("compare --map " + (out / "world.yaml").string() + " --reference " +
                       (out / "world.yaml").string() + " --json");
  ASSERT_EQ(c.status, 0) << c.output;
  EXPECT_NE(c.output.find("\"ours_near_reference\": 1.0"), std::string::npos) << c.output;
}

TEST_F(Cli, SimulateIsByteIdenticalForTheSameSeed) {
  const std::string options = " --scans 30 --obstacles 4 --dropout 0.1 --contamination 0.05";
  ASSERT_EQ(run("simulate --out " + (dir_ / "a").string() + options + " --seed 9").status, 0);
  ASSERT_EQ(run("simulate --out " + (dir_ / "b").string() + options + " --seed 9").status, 0);
  ASSERT_EQ(run("simulate --out " + (dir_ / "c").string() + options + " --seed 10").status, 0);
  for (const char* f : {"sim.log", "truth.log", "world.pgm", "world.png"})
    EXPECT_EQ(file_text(dir_ / "a" / f), file_text(dir_ / "b" / f)) << f;
  EXPECT_NE(file_text(dir_ / "a" / "sim.log"), file_text(dir_ / "c" / "sim.log"));
}

// The map is the same, bit for bit, for every thread count, in both arithmetics (each thread
// fills its own band of rows: every cell takes the same fusions in the same order).
TEST_F(Cli, MapIsByteIdenticalForEveryThreadCount) {
  const fs::path log = dir_ / "sim" / "sim.log";
  ASSERT_EQ(run("simulate --out " + (dir_ / "sim").string() + " --scans 40 --seed 3").status, 0);
  for (const char* arith : {"int", "float"}) {
    std::string first;
    for (const int threads : {1, 2, 3, 7}) {
      const fs::path out = dir_ / (std::string(arith) + std::to_string(threads));
      const CliRun m =
          run("map --log " + log.string() + " --out " + out.string() + " --cell 0.05 --arith " +
              arith + " --threads " + std::to_string(threads));
      ASSERT_EQ(m.status, 0) << m.output;
      const std::string pgm = file_text(out / "map.pgm");
      if (first.empty()) first = pgm;
      EXPECT_EQ(pgm, first) << arith << ", " << threads << " threads";
    }
  }
}

TEST_F(Cli, SimulateOnAMapAlongAReferenceTrajectory) {
  // A 4 m square room map, and a reference log of three poses inside it.
  std::string pgm = "P5\n40 40\n255\n";
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) pgm += (x == 0 || y == 0 || x == 39 || y == 39) ? '\0' : '\xfe';
  write("room.pgm", pgm);
  const fs::path yaml = write("room.yaml",
                              "image: room.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const fs::path reference = write("ref.log",
                                   "RLASER 2 0 0.1 10 1 1 1 0.5 0 0 0 0 5\n"
                                   "RLASER 2 0 0.1 10 1 1 1.5 0.5 0.1 0 0 0 6\n"
                                   "RLASER 2 0 0.1 10 1 1 2 0.6 0.2 0 0 0 7\n");
  const fs::path out = dir_ / "out";
  CliRun r = run("simulate --out " + out.string() + " --world " + yaml.string() + " --trajectory " +
                 reference.string() + " --sensor cone --beams 8 --fov 40");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string truth = file_text(out / "truth.log");
  const std::vector<std::string> lines = lines_of(truth);
  ASSERT_EQ(lines.size(), 3u) << truth;
  // RLASER 8 angle0 dangle maxrange r_0..r_7 x y theta ...: the reference's poses.
  EXPECT_NE(lines[1].find(" 1.5 0.5 0.1 0 0 0 "), std::string::npos) << lines[1];
  EXPECT_EQ(lines[0].rfind("RLASER 8 0 0.7853981633974483 5 ", 0), 0u) << lines[0];
  // More scans than the reference holds.
  expect_error(run("simulate --out " + out.string() + " --world " + yaml.string() +
                   " --trajectory " + reference.string() + " --scans 5"),
               "--scans");
  // Random waypoints in the room.
  r = run("simulate --out " + out.string() + " --world " + yaml.string() + " --scans 50");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(records(file_text(out / "sim.log"), "RLASER"), 50u);
}

TEST_F(Cli, SimulateRefusesBadOptionsNamingThem) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--noise -1", "--noise"},
      {"--noise nan", "--noise"},
      {"--dropout 1.5", "--dropout"},
      {"--contamination -0.1", "--contamination"},
      {"--beams 0", "--beams"},
      {"--sensor radar", "--sensor"},
      {"--fov 0", "--fov"},
      {"--sensor cone --fov 180", "--fov"},
      {"--max-range 0", "--max-range"},
      {"--max-range inf", "--max-range"},
      {"--scans 0", "--scans"},
      {"--obstacles -2", "--obstacles"},
      {"--odometry-noise 0.1,0.1,0.1", "--odometry-noise"},
      {"--odometry-noise 0.1,-1,0.1,0.1", "--odometry-noise"},
      {"--cell 0", "--cell"},
      {"--cell 0.6", "--cell"},
      {"--seed -1", "--seed"},
      {"--speed 0", "--speed"},
      {"--large-obstacle -1", "--large-obstacle"},
      {"--world w.yaml --floorplan", "--floorplan"},
  };
  const fs::path out = dir_ / "out";
  for (const auto& [options, keyword] : cases) {
    SCOPED_TRACE(options);
    const CliRun r = run("simulate --out " + out.string() + " " + options);
    expect_error(r, keyword);
    EXPECT_EQ(r.status, 2);
    EXPECT_FALSE(fs::exists(out / "sim.log"));
  }
}

TEST_F(Cli, SimulateRefusesAWorldWithoutFreeSpace) {
  write("dark.pgm", std::string("P5\n10 10\n255\n") + std::string(100, '\0'));
  const fs::path yaml = write("dark.yaml",
                              "image: dark.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const fs::path out = dir_ / "out";
  CliRun r = run("simulate --out " + out.string() + " --world " + yaml.string());
  expect_error(r, yaml.string() + ": image: the map has no free cell");
  EXPECT_EQ(r.status, 2);
  EXPECT_FALSE(fs::exists(out / "sim.log"));
  r = run("simulate --out " + out.string() + " --world " + (dir_ / "missing.yaml").string());
  expect_error(r, (dir_ / "missing.yaml").string());
  EXPECT_EQ(r.status, 2);
}

}  // namespace
