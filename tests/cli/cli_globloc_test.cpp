// `intgrid globloc`, `figure globloc-sweeps` and `compare`, in the room of write_globloc_room.
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

// The room against itself 100 m away: far past any small tolerance, within any huge one. The
// search window is cut to the grid (a tolerance of 10^9 cells once searched 10^18 cells, and
// 10^10 overflowed to a window of none).
TEST_F(Cli, CompareTakesAnyToleranceAndRefusesAnAbsurdResolution) {
  const fs::path room = write_globloc_room(dir_);
  std::ofstream(dir_ / "far.yaml") << "image: room.pgm\nresolution: 0.1\norigin: [100, 0, 0]\n"
                                      "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  const std::string base =
      "compare --map " + room.string() + " --reference " + (dir_ / "far.yaml").string();
  for (const char* tolerance : {"1e9", "1e10", "1e300"}) {
    const CliRun r = run(base + " --tolerance-cells " + tolerance);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("of the reference's: 100.0%"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("of ours: 100.0%"), std::string::npos) << r.output;
  }
  const CliRun near = run(base + " --tolerance-cells 2");
  ASSERT_EQ(near.status, 0) << near.output;
  EXPECT_NE(near.output.find("of the reference's: 0.0%"), std::string::npos) << near.output;
  expect_error(run(base + " --tolerance-cells nan"), "--tolerance-cells");
  std::ofstream(dir_ / "fine.yaml") << "image: room.pgm\nresolution: 1e-320\norigin: [0, 0, 0]\n"
                                       "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  expect_error(
      run("compare --map " + room.string() + " --reference " + (dir_ / "fine.yaml").string()),
      "resolution");
}

TEST_F(Cli, GlobLocWritesPosesPictureAndMetricsAndScoresAgainstAReference) {
  const fs::path room = write_globloc_room(dir_);
  const fs::path sim = dir_ / "sim";
  ASSERT_EQ(run("simulate --out " + sim.string() + " --world " + room.string() +
                " --scans 6 --seed 3 --noise 0.01")
                .status,
            0);
  const fs::path out = dir_ / "out";
  const CliRun r = run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() +
                       " --out " + out.string() + " --reference " + (sim / "truth.log").string() +
                       " --scans 1:4 --pose-cell 0.1 --headings 64 --beams 90");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"poses.txt", "pose_grid.png", "metrics.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  expect_png(out / "pose_grid.png");
  const std::vector<std::string> lines = lines_of(file_text(out / "poses.txt"));
  ASSERT_EQ(lines.size(), 5u) << file_text(out / "poses.txt");
  EXPECT_EQ(lines[0].rfind("# t x y theta score", 0), 0u) << lines[0];
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::istringstream fields(lines[i]);
    double t = 0, x = 0, y = 0, theta = 0, score = 0;
    ASSERT_TRUE(fields >> t >> x >> y >> theta >> score) << lines[i];
    EXPECT_NEAR(t, 1e9 + 0.2 * static_cast<double>(i), 1e-6) << lines[i];  // scans 1 to 4
    EXPECT_TRUE(x > 0 && x < 4 && y > 0 && y < 3) << lines[i];
  }
  // Every scan has a reference pose; in this room each is found.
  EXPECT_NE(r.output.find("\"matched\": 4"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"within\": 4"), std::string::npos) << r.output;
  EXPECT_NE(file_text(out / "metrics.json").find("\"share\": 1.0"), std::string::npos);
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();

  // --hypotheses 3: each line adds the two next hypotheses (x y theta score) after the ambiguity
  // flag, on any thread count the same file.
  for (const char* threads : {"1", "3"}) {
    const fs::path k3 = dir_ / (std::string("k3_") + threads);
    const CliRun h = run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() +
                         " --out " + k3.string() + " --scans 1:4 --pose-cell 0.1 --headings 64 " +
                         "--beams 20 --hypotheses 3 --threads " + threads);
    ASSERT_EQ(h.status, 0) << h.output;
    const std::vector<std::string> k3_lines = lines_of(file_text(k3 / "poses.txt"));
    ASSERT_EQ(k3_lines.size(), 5u);
    for (std::size_t i = 1; i < k3_lines.size(); ++i) {
      std::istringstream fields(k3_lines[i]);
      std::vector<double> v;
      for (double x = 0; fields >> x;) v.push_back(x);
      ASSERT_EQ(v.size(), 14u) << k3_lines[i];
      EXPECT_TRUE(v[5] == 0.0 || v[5] == 1.0) << k3_lines[i];
      EXPECT_GE(v[4], v[9]) << k3_lines[i];  // best first
      EXPECT_GE(v[9], v[13]) << k3_lines[i];
    }
  }
  EXPECT_EQ(file_text(dir_ / "k3_1" / "poses.txt"), file_text(dir_ / "k3_3" / "poses.txt"));
  // A trajectory as the reference (t x y theta, as slam writes it): the estimates themselves are
  // found, at any tolerance; shifted by 0.2 m, not within 0.1 m.
  std::string exact = "# t x y theta\n", shifted = exact;
  const auto number = [](double v) {
    std::ostringstream o;
    o.precision(17);
    o << v;
    return o.str();
  };
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::istringstream fields(lines[i]);
    double t = 0, x = 0, y = 0, theta = 0;
    fields >> t >> x >> y >> theta;
    exact += number(t) + ' ' + number(x) + ' ' + number(y) + ' ' + number(theta) + '\n';
    shifted += number(t) + ' ' + number(x + 0.2) + ' ' + number(y) + ' ' + number(theta) + '\n';
  }
  for (const auto& [name, text, within] :
       {std::tuple{"exact.txt", exact, 4}, std::tuple{"shifted.txt", shifted, 0}}) {
    const CliRun t =
        run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() + " --out " +
            (dir_ / "traj").string() + " --reference-trajectory " + write(name, text).string() +
            " --scans 1:4 --pose-cell 0.1 --headings 64 --beams 90 --tolerance 0.1 1");
    ASSERT_EQ(t.status, 0) << t.output;
    EXPECT_NE(t.output.find("\"within\": " + std::to_string(within)), std::string::npos)
        << name << t.output;
    // Each miss's endpoints fit the map better at the answer than at the shifted reference.
    if (within == 0) {
      EXPECT_NE(t.output.find("\"misses_where_the_endpoints_fit_the_reference_better\": 0"),
                std::string::npos)
          << t.output;
    }
  }
  // A pose grid above --max-memory is refused, naming the option, before it is built.
  const CliRun big =
      run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() + " --out " +
          (dir_ / "big").string() + " --pose-cell 0.1 --headings 4096 --max-memory 1");
  EXPECT_EQ(big.status, 2) << big.output;
  expect_error(big, "--max-memory: a pose grid of");

  // The baselines run too.
  for (const char* method : {"markov", "markov-mixture", "likelihood-field"}) {
    const CliRun b = run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() +
                         " --out " + (dir_ / method).string() + " --scans 2:2 --method " + method);
    ASSERT_EQ(b.status, 0) << method << b.output;
    EXPECT_NE(b.output.find(std::string("\"method\": \"") + method + "\""), std::string::npos);
  }
}

// --track: from each selected scan the scans after it are fused until the answer is
// unambiguous; poses.txt adds how many it took and when it started, the same on any thread count.
TEST_F(Cli, GlobLocTrackFusesScansAndSaysHowManyItTook) {
  const fs::path room = write_globloc_room(dir_);
  const fs::path sim = dir_ / "sim";
  ASSERT_EQ(run("simulate --out " + sim.string() + " --world " + room.string() +
                " --scans 12 --seed 3 --noise 0.01")
                .status,
            0);
  for (const char* threads : {"1", "3"}) {
    const fs::path out = dir_ / (std::string("track_") + threads);
    const CliRun r = run("globloc --map " + room.string() + " --log " + (sim / "sim.log").string() +
                         " --out " + out.string() + " --reference " + (sim / "truth.log").string() +
                         " --scans 0:5 --pose-cell 0.1 --headings 64 --beams 20 --track 4 " +
                         "--track-step 0.05 5 --ambiguity-levels 20 --threads " + threads);
    ASSERT_EQ(r.status, 0) << r.output;
    const std::vector<std::string> lines = lines_of(file_text(out / "poses.txt"));
    ASSERT_EQ(lines.size(), 7u) << file_text(out / "poses.txt");
    EXPECT_NE(lines[0].find("scans t_first"), std::string::npos) << lines[0];
    std::size_t fused_more = 0;
    for (std::size_t i = 1; i < lines.size(); ++i) {
      std::istringstream fields(lines[i]);
      double t = 0, x = 0, y = 0, theta = 0, score = 0, ambiguous = 0, scans = 0, t_first = 0;
      ASSERT_TRUE(fields >> t >> x >> y >> theta >> score >> ambiguous >> scans >> t_first)
          << lines[i];
      EXPECT_NEAR(t_first, 1e9 + 0.2 * static_cast<double>(i - 1), 1e-6) << lines[i];
      EXPECT_GE(scans, 1.0);
      EXPECT_LE(scans, 4.0);
      // A scan is fused after the first only while the answer is ambiguous; each fused scan
      // is a later one.
      EXPECT_TRUE(scans == 4.0 || ambiguous == 0.0) << lines[i];
      EXPECT_GE(t, t_first + 0.2 * (scans - 1) - 1e-6) << lines[i];
      fused_more += scans > 1.0 ? 1 : 0;
    }
    // --ambiguity-levels 20 calls nearly every answer ambiguous: sequences are fused.
    EXPECT_GT(fused_more, 0u);
    const std::string metrics = file_text(out / "metrics.json");
    EXPECT_NE(metrics.find("\"track\""), std::string::npos);
    EXPECT_NE(metrics.find("\"mean_scans\""), std::string::npos);
    EXPECT_NE(r.output.find("\"matched\": 6"), std::string::npos) << r.output;
  }
  EXPECT_EQ(file_text(dir_ / "track_1" / "poses.txt"), file_text(dir_ / "track_3" / "poses.txt"));
}

TEST_F(Cli, GlobLocRefusesBadInputsNamingFileAndField) {
  const fs::path room = write_globloc_room(dir_);
  const fs::path log = write("room.log", "RLASER 4 -0.5 0.3 10 1.0 1.2 1.1 1.3" + kScanTail +
                                             "RLASER 4 -0.5 0.3 10 1.0 1.2 1.1 1.3" + kScanTail);
  const fs::path out = dir_ / "out";
  const auto globloc = [&](const fs::path& map, const fs::path& scans, const std::string& more) {
    return run("globloc --map " + map.string() + " --log " + scans.string() + " --out " +
               out.string() + " " + more);
  };
  // A map without any free cell.
  write("dark.pgm", std::string("P5\n10 10\n255\n") + std::string(100, '\0'));
  const fs::path dark = write("dark.yaml",
                              "image: dark.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  CliRun r = globloc(dark, log, "");
  expect_error(r, dark.string() + ": image: the map has no free cell");
  EXPECT_EQ(r.status, 2);
  // A pose grid finer than the map.
  r = globloc(room, log, "--pose-cell 0.05");
  expect_error(r, room.string() + ": resolution: the pose-grid step --pose-cell 0.05 m is finer");
  EXPECT_EQ(r.status, 2);
  // A log without any valid reading.
  const fs::path dead = write("dead.log", "RLASER 4 -0.5 0.3 10 0 0 nan 11" + kScanTail);
  r = globloc(room, dead, "");
  expect_error(r, dead.string() + ": ranges: no selected scan holds a valid reading");
  EXPECT_EQ(r.status, 2);
  // Bad scan ranges.
  for (const char* scans : {"5:2", "0:2", "a:1", "1", "1:2:3"}) {
    SCOPED_TRACE(scans);
    r = globloc(room, log, std::string("--scans ") + scans);
    expect_error(r, log.string() + ": --scans: '" + scans + "'");
    EXPECT_EQ(r.status, 2);
  }
  // A log line that does not parse names its line and field.
  const fs::path bad = write("bad.log", "RLASER 4 -0.5 0.3 10 1.0 1.0 x1 1.0" + kScanTail);
  r = globloc(room, bad, "");
  expect_error(r, bad.string() + ":1: r_2");
  EXPECT_EQ(r.status, 2);
  EXPECT_FALSE(fs::exists(out / "poses.txt"));
}

// `figure globloc-sweeps --quick`: one CSV per sweep (two points, four methods each), the same for
// one and two threads, and the plots (or a note when gnuplot is missing).
TEST_F(Cli, GlobLocSweepsWriteTheirCsvsAndPlotsTheSameForAnyThreadCount) {
  const fs::path room = write_globloc_room(dir_);
  const std::string options =
      "figure globloc-sweeps --quick --trials 3 --pose-cell 0.1 --headings 32 --seed 4 --map " +
      room.string();
  const CliRun one = run(options + " --threads 1 --out " + (dir_ / "one").string());
  ASSERT_EQ(one.status, 0) << one.output;
  const CliRun two = run(options + " --threads 2 --out " + (dir_ / "two").string());
  ASSERT_EQ(two.status, 0) << two.output;
  EXPECT_NE(one.output.find("success: position error <= 0.2 m (2 pose cells) AND heading error "
                            "<= 22.5 deg (2 heading bins)"),
            std::string::npos)
      << one.output;
  const std::vector<std::pair<std::string, std::string>> sweeps = {
      {"readings", "readings"},
      {"noise", "noise_m"},
      {"contamination", "contamination"},
      {"obstacles", "obstacles"},
      {"large_obstacle", "distance_m"}};
  const char* methods[] = {"pog", "markov", "markov-mixture", "likelihood-field"};
  for (const auto& [sweep, variable] : sweeps) {
    SCOPED_TRACE(sweep);
    const std::string csv = file_text(dir_ / "one" / ("globloc_" + sweep + ".csv"));
    EXPECT_EQ(csv, file_text(dir_ / "two" / ("globloc_" + sweep + ".csv")));
    const std::vector<std::string> lines = lines_of(csv);
    ASSERT_EQ(lines.size(), 1u + 2 * 4) << csv;
    EXPECT_EQ(lines[0], variable +
                            ",method,trials,failed_setups,mean_readings,successes,success_rate,"
                            "mean_position_error_m,median_position_error_m,mean_heading_error_deg");
    for (std::size_t i = 1; i < lines.size(); ++i) {
      const std::vector<std::string> f = fields_of(lines[i]);
      ASSERT_EQ(f.size(), 10u) << lines[i];
      EXPECT_EQ(f[1], methods[(i - 1) % 4]) << lines[i];
      EXPECT_EQ(std::stoi(f[2]) + std::stoi(f[3]), 3) << lines[i];
      const double rate = std::stod(f[6]);
      EXPECT_TRUE(rate >= 0.0 && rate <= 1.0) << lines[i];
      for (std::size_t c = 7; c < 10; ++c) EXPECT_GE(std::stod(f[c]), 0.0) << lines[i];
    }
    if (one.output.find("plots skipped") == std::string::npos)
      expect_png(dir_ / "one" / ("globloc_" + sweep + ".png"));
  }
  EXPECT_TRUE(fs::exists(dir_ / "one" / "globloc_timing.csv"));
  // With 60 clean readings in this room every method finds nearly every pose.
  const std::vector<std::string> readings =
      lines_of(file_text(dir_ / "one" / "globloc_readings.csv"));
  for (std::size_t i = 5; i < readings.size(); ++i)
    EXPECT_GE(std::stod(fields_of(readings[i])[6]), 0.6) << readings[i];
  for (const auto& entry : fs::directory_iterator(dir_ / "one"))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
  // --sweeps runs only those: the same rows as in the full run, no other sweep's file.
  const CliRun only = run(options + " --sweeps contamination --out " + (dir_ / "only").string());
  ASSERT_EQ(only.status, 0) << only.output;
  EXPECT_EQ(file_text(dir_ / "only" / "globloc_contamination.csv"),
            file_text(dir_ / "one" / "globloc_contamination.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "only" / "globloc_readings.csv"));
  EXPECT_EQ(run(options + " --sweeps speed --out " + (dir_ / "bad").string()).status, 2);
}

}  // namespace
