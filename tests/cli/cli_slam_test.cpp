// `intgrid slam` and `figure slam-sweeps`.
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

// SLAM: a small log that moves, with one scan whose readings are all invalid.
const char* kSlamLog =
    "RLASER 5 -1 0.5 10 2 2.1 2.2 2.1 2 0 0 0 0 0 0 100\n"
    "ODOM 0.1 0 0 100.5\n"
    "RLASER 5 -1 0.5 10 0 nan -1 10 inf 0.1 0 0 0 0 0 101\n"
    "RLASER 5 -1 0.5 10 1.8 1.9 2 1.9 1.8 0.2 0 0 0 0 0 102\n";

TEST_F(Cli, SlamWritesTrajectoryMapAndMetricsAndCountsSkippedScans) {
  const CliRun r = run("slam --engine grid --log " + write("s.log", kSlamLog).string() + " --out " +
                       (dir_ / "out").string() + " --max-range 8");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"trajectory.txt", "map.yaml", "map.pgm", "map.png", "metrics.json"})
    EXPECT_TRUE(fs::exists(dir_ / "out" / f)) << f;
  std::ifstream trajectory(dir_ / "out" / "trajectory.txt");
  std::string line;
  std::vector<std::string> poses;
  while (std::getline(trajectory, line))
    if (!line.empty() && line[0] != '#') poses.push_back(line);
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(poses[1].substr(0, 4), "101 ");  // the log's timestamps
  EXPECT_NE(r.output.find("\"skipped_scans\": 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"unusable_readings\": 5"), std::string::npos) << r.output;
  for (const fs::directory_entry& e : fs::directory_iterator(dir_ / "out"))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

// Logs of a few bytes whose odometry wanders kilometres in steps under the 1 km a step may
// take: each engine's map is estimated from the odometry before SLAM runs and refused over
// --max-memory naming --cell (the submaps engine's 1.1e9-cell map and the grid engine's
// 3e9-cell square ask for about 29 and 116 GB); a square past the grid engine's 65535 cells a
// side names --cell too (it was an internal error, exit 1).
TEST_F(Cli, SlamMapOverTheMemoryLimitIsRefusedNamingTheOption) {
  const auto log_through = [&](const std::string& name, std::initializer_list<const char*> xy) {
    std::string text;
    int t = 0;
    for (const char* p : xy)
      text += "RLASER 4 -0.5 0.3 10 1.0 1.0 1.0 1.0 " + std::string(p) + " 0 0 0 0 " +
              std::to_string(++t) + "\n";
    return write(name, text);
  };
  const fs::path wander =
      log_through("wander.log", {"0 0", "900 0", "1800 0", "2700 0", "2700 900"});
  const std::string out = " --out " + (dir_ / "o").string();
  for (const char* engine : {"submaps", "grid"}) {
    const CliRun r =
        run("slam --log " + wander.string() + out + " --engine " + engine + " --max-memory 16000");
    expect_error(r, "--cell: a map of ");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("more than the memory limit of 16.0 GB (--max-memory)"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "o" / "trajectory.txt"));
  }
  const fs::path far = log_through("far.log", {"0 0", "900 0", "1800 0", "2700 0", "3600 0"});
  const CliRun r = run("slam --log " + far.string() + out + " --engine grid");
  expect_error(r, "--cell: a map of 0.1 m cells around the first pose of " + far.string());
  EXPECT_EQ(r.status, 2);
}

TEST_F(Cli, SlamRejectsEmptyMalformedAndOdometryFreeLogs) {
  const std::string out = " --out " + (dir_ / "out").string();
  CliRun r = run("slam --log " + write("empty.log", "").string() + out);
  EXPECT_EQ(r.status, 2);
  expect_error(r, "no scans");
  r = run("slam --log " + write("bad.log", "RLASER 2 0 1 10 1 x 0 0 0 0 0 0 5\n").string() + out);
  EXPECT_EQ(r.status, 2);
  expect_error(r, "bad.log:1: r_1");
  r = run(
      "slam --log " +
      write("still.log", "RLASER 2 0 1 10 1 1 0 0 0 0 0 0 5\nRLASER 2 0 1 10 1 1 0 0 0 0 0 0 6\n")
          .string() +
      out);
  EXPECT_EQ(r.status, 2);
  expect_error(r, "no odometry");
  r = run("slam --log " + write("s.log", kSlamLog).string() + out + " --cell 0.0125");
  EXPECT_EQ(r.status, 2);
  expect_error(r, "--cell: must be a whole number of millimetres");
  r = run("slam --engine grid --log " + write("s.log", kSlamLog).string() + out +
          " --window-cells 10");
  EXPECT_EQ(r.status, 2);
  expect_error(r, "--window-cells: must be odd");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "map.yaml"));
}

// The default engine is the submap SLAM: the same files, metrics.json with its counts and no
// E(sigma), and a summary line on stderr with its nodes and loop closures; --engine grid is the
// event-driven grid SLAM, as before.
TEST_F(Cli, SlamRunsTheSubmapEngineByDefaultAndTheGridEngineOnRequest) {
  const std::string log = " --log " + write("s.log", kSlamLog).string() + " --max-range 8";
  CliRun r = run("slam" + log + " --out " + (dir_ / "submaps").string());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"trajectory.txt", "map.yaml", "map.pgm", "map.png", "metrics.json"})
    EXPECT_TRUE(fs::exists(dir_ / "submaps" / f)) << f;
  std::string metrics = file_text(dir_ / "submaps" / "metrics.json");
  EXPECT_NE(metrics.find("\"engine\": \"submaps\""), std::string::npos) << metrics;
  for (const char* field :
       {"nodes", "submaps", "wide_searches", "unmatched_scans", "loop_searches", "loop_closures",
        "optimizations", "peak_pyramid_bytes", "scans", "readings", "unusable_readings",
        "reordered_scans", "seconds", "real_time_factor", "peak_memory_bytes"})
    EXPECT_NE(metrics.find("\"" + std::string(field) + "\": "), std::string::npos)
        << field << " in " << metrics;
  EXPECT_NE(metrics.find("\"scans\": 3,"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"unusable_readings\": 5,"), std::string::npos) << metrics;
  for (const char* field : {"e_sigma_m", "skipped_scans", "lambda"})
    EXPECT_EQ(metrics.find("\"" + std::string(field) + "\""), std::string::npos)
        << field << " in " << metrics;
  EXPECT_NE(r.output.find("slam (submaps): "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" node"), std::string::npos) << r.output;  // "2 nodes in 1 submap"
  EXPECT_NE(r.output.find(" loop closure"), std::string::npos) << r.output;
  std::istringstream lines(file_text(dir_ / "submaps" / "trajectory.txt"));
  std::size_t poses = 0;
  for (std::string line; std::getline(lines, line);) poses += !line.empty() && line[0] != '#';
  EXPECT_EQ(poses, 3u);

  r = run("slam" + log + " --engine grid --out " + (dir_ / "grid").string());
  ASSERT_EQ(r.status, 0) << r.output;
  metrics = file_text(dir_ / "grid" / "metrics.json");
  EXPECT_NE(metrics.find("\"engine\": \"grid\""), std::string::npos) << metrics;
  for (const char* field : {"e_sigma_m", "skipped_scans", "localizations", "mappings"})
    EXPECT_NE(metrics.find("\"" + std::string(field) + "\": "), std::string::npos)
        << field << " in " << metrics;
  EXPECT_EQ(metrics.find("\"loop_closures\""), std::string::npos) << metrics;
  EXPECT_NE(r.output.find("slam (grid): E(sigma) "), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "grid" / "map.png"));
}

// The options both engines have set the engine that runs: --cell 0.08 with either.
TEST_F(Cli, SlamSharedOptionsSetTheEngineThatRuns) {
  const std::string log = " --log " + write("s.log", kSlamLog).string() + " --max-range 8";
  CliRun r = run("slam" + log + " --cell 0.08 --sigma 0.07 --out " + (dir_ / "s").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::string metrics = file_text(dir_ / "s" / "metrics.json");
  EXPECT_NE(metrics.find("\"cell\": 0.08"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"sigma\": 0.07"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"max_range\": 8.0"), std::string::npos) << metrics;
  r = run("slam" + log + " --engine grid --cell 0.08 --out " + (dir_ / "g").string());
  ASSERT_EQ(r.status, 0) << r.output;
  metrics = file_text(dir_ / "g" / "metrics.json");
  EXPECT_NE(metrics.find("\"res\": 0.08"), std::string::npos) << metrics;
}

// A setting of the other engine, a bad submaps value, a value check_submap_slam_config refuses:
// exit 2, one line naming the flag (and, for another engine's setting, that engine), no output.
TEST_F(Cli, SlamRefusesTheOtherEnginesOptionsAndBadSubmapValues) {
  const std::string slam =
      "slam --log " + write("s.log", kSlamLog).string() + " --out " + (dir_ / "out").string() + " ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--lambda 2", "--lambda: a setting of --engine grid, not of --engine submaps"},
      {"--engine submaps --window-cells 11",
       "--window-cells: a setting of --engine grid, not of --engine submaps"},
      {"--motion-noise 0,0,0,0,0,0", "--motion-noise: a setting of --engine grid"},
      {"--engine grid --loop-window 1",
       "--loop-window: a setting of --engine submaps, not of --engine grid"},
      {"--engine grid --huber 2", "--huber: a setting of --engine submaps"},
      {"--engine grid --bits 8", "--bits: a setting of --engine submaps"},
      {"--engine gird", "--engine"},
      {"--loop-window -1", "--loop-window: must be >= 0, got -1"},
      {"--loop-min-score 0", "--loop-min-score"},
      {"--wide-below 1.5", "--wide-below"},
      {"--submap-scans 0", "--submap-scans"},
      {"--submap-rematch maybe", "--submap-rematch"},
      {"--submap-handover -1", "--submap-handover"},
      {"--submap-scans 8 --submap-handover 11",
       "--submap-handover: must be from 0 to --submap-scans"},
      {"--threads 300", "--threads"},
      {"--engine grid --threads 2", "--threads: a setting of --engine submaps"},
      {"--engine grid --submap-rematch false", "--submap-rematch: a setting of --engine submaps"},
      {"--huber nan", "--huber"},
      {"--graph-iterations 2.5", "--graph-iterations"},
      {"--filter-degrees 200", "--filter-degrees: must be in [0, 180]"},
      {"--graph-iterations 5000", "--graph-iterations: must be 1..1000"},
      {"--headings 32", "--headings: must be a power of two"},
      {"--bits 9", "--bits: must be 2..8"},
      {"--cell 0.0125", "--cell: must be a whole number of millimetres"},
      {"--tracking-window 5", "--tracking-window: "},
  };
  for (const auto& [options, message] : cases) {
    SCOPED_TRACE(options);
    const CliRun r = run(slam + options);
    EXPECT_EQ(r.status, 2) << r.output;
    expect_error(r, message);
    EXPECT_NE(r.output.find("run 'intgrid slam --help'"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "metrics.json"));
  }
}

// --help: --engine, both defaults of a shared option, the submaps engine's options.
TEST_F(Cli, SlamHelpShowsBothEngines) {
  const CliRun r = run("slam --help");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* text : {"--engine submaps|grid=submaps", "(default: submaps ", ", grid ",
                           "--loop-window", "--tracking-window", "--graph-iterations", "--lambda"})
    EXPECT_NE(r.output.find(text), std::string::npos) << text << " in " << r.output;
}

// --relations: relations between pairs of kSlamLog's scan times (100, 101, 102 s), one 5 ms off
// (within the benchmark's 0.01 s) and one to a time no scan has, scored for the SLAM and the
// raw odometry, each relation's error in relations.csv; --tum: one line a scan.
TEST_F(Cli, SlamScoresBenchmarkRelationsAndWritesATumTrajectory) {
  const fs::path relations = write("s.relations",
                                   "# t1 t2 x y z roll pitch yaw\n"
                                   "100 101 0.1 0 0 0 0 0\n"
                                   "101 102.005 0.1 0 0 0 0 0\n"
                                   "\n"
                                   "100 102 0.2 0 0 0 0 0.01\n"
                                   "100 103 0.3 0 0 0 0 0\n");
  const fs::path tum = dir_ / "trajectory.tum";
  const CliRun r =
      run("slam --log " + write("s.log", kSlamLog).string() + " --out " + (dir_ / "out").string() +
          " --max-range 8 --relations " + relations.string() + " --tum " + tum.string());
  ASSERT_EQ(r.status, 0) << r.output;
  // One line each (on stderr, so in any order with stdout's JSON).
  for (const char* line : {"relations: 3 matched, 1 unmatched; translation ",
                           "odometry relations: 3 matched, 1 unmatched; translation "})
    EXPECT_TRUE(r.output.rfind(line, 0) == 0 ||
                r.output.find("\n" + std::string(line)) != std::string::npos)
        << line << " in " << r.output;
  const std::string metrics = file_text(dir_ / "out" / "metrics.json");
  for (const char* key : {"relations", "odometry_relations"}) {
    const std::string object = json_object(metrics, key);
    ASSERT_FALSE(object.empty()) << key << " in " << metrics;
    EXPECT_NE(object.find("\"matched\": 3,"), std::string::npos) << object;
    EXPECT_NE(object.find("\"unmatched\": 1"), std::string::npos) << object;
    for (const char* field :
         {"trans_mean", "trans_std", "rot_mean_deg", "rot_std_deg", "trans_sq_mean", "trans_sq_std",
          "rot_sq_mean", "rot_sq_std", "trans_median", "rot_median_deg", "off", "off_fraction"})
      EXPECT_NE(object.find("\"" + std::string(field) + "\": "), std::string::npos)
          << field << " in " << object;
  }
  EXPECT_NE(metrics.find("\"relations_file\": \"" + relations.string() + "\""), std::string::npos);
  EXPECT_NE(metrics.find("\"relation_stretches\": ["), std::string::npos) << metrics;
  // relations.csv: each relation in the file's order with the SLAM's and the odometry's errors,
  // empty where it matched no scan; its matched rows' mean is the metrics' trans_mean.
  std::istringstream csv(file_text(dir_ / "out" / "relations.csv"));
  std::vector<std::string> rows;
  for (std::string line; std::getline(csv, line);) rows.push_back(line);
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0],
            "t1,t2,trans_error_m,rot_error_deg,off,odometry_trans_error_m,odometry_rot_error_deg");
  EXPECT_EQ(rows[1].rfind("100,101,", 0), 0u) << rows[1];
  EXPECT_EQ(rows[2].rfind("101,102.005,", 0), 0u) << rows[2];
  EXPECT_EQ(rows[4], "100,103,,,0,,") << rows[4];
  double sum = 0.0;
  for (std::size_t i = 1; i <= 3; ++i) sum += std::stod(rows[i].substr(rows[i].find(',', 4) + 1));
  const std::string slam_object = json_object(metrics, "relations");
  const std::size_t at = slam_object.find("\"trans_mean\": ");
  ASSERT_NE(at, std::string::npos) << slam_object;
  EXPECT_NEAR(std::stod(slam_object.substr(at + 14)), sum / 3.0, 1e-12);
  EXPECT_NE(metrics.find("\"reordered_scans\": 0"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"peak_memory_bytes\": "), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("\"real_time_factor\": "), std::string::npos) << metrics;

  std::istringstream lines(file_text(tum));
  std::vector<std::string> poses;
  for (std::string line; std::getline(lines, line);) poses.push_back(line);
  ASSERT_EQ(poses.size(), 3u) << file_text(tum);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(poses[i].substr(0, 4), std::to_string(100 + i) + " ") << poses[i];
    std::istringstream fields(poses[i]);
    EXPECT_EQ(std::distance(std::istream_iterator<std::string>(fields),
                            std::istream_iterator<std::string>()),
              8)
        << poses[i];
  }
  // trajectory.txt keeps its format: a comment, then t x y theta.
  const std::string trajectory = file_text(dir_ / "out" / "trajectory.txt");
  EXPECT_EQ(trajectory.rfind("# t x y theta", 0), 0u) << trajectory;
}

TEST_F(Cli, SlamRefusesRelationsThatMatchNoScanOrDoNotParse) {
  const std::string log = " --log " + write("s.log", kSlamLog).string();
  const std::string out = " --out " + (dir_ / "out").string();
  fs::path relations = write("other.relations",
                             "# for another log\n"
                             "\n"
                             "976052905.167303 976052911.885496 -0.05 -0.12 0 0 0 -1.68\n"
                             "100.02 101 0.1 0 0 0 0 0\n");
  CliRun r = run("slam" + log + out + " --relations " + relations.string());
  EXPECT_EQ(r.status, 2);
  expect_error(r, relations.string() +
                      ":3: t1: none of its 2 relations matches a scan of the log " +
                      (dir_ / "s.log").string() + " within 0.01 s");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "metrics.json"));

  relations = write("bad.relations", "100 101 0.1 0 0 0 0 0\n101 102 0.1 nan 0 0 0 0\n");
  r = run("slam" + log + out + " --relations " + relations.string());
  EXPECT_EQ(r.status, 2);
  expect_error(r, relations.string() + ":2: y: must be a finite number");

  relations = write("short.relations", "100 101 0.1 0 0 0 0\n");
  r = run("slam" + log + out + " --relations " + relations.string());
  EXPECT_EQ(r.status, 2);
  expect_error(r, relations.string() + ":1: yaw: missing");

  relations = write("empty.relations", "# nothing\n");
  r = run("slam" + log + out + " --relations " + relations.string());
  EXPECT_EQ(r.status, 2);
  expect_error(r, relations.string() + ": relations: the file holds no relation");

  r = run("slam" + log + out + " --relations " + (dir_ / "missing.relations").string());
  EXPECT_EQ(r.status, 2);
  expect_error(r, (dir_ / "missing.relations").string() + ": file: cannot open");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "map.yaml"));
}

// On a terminal (a pseudo-terminal from util-linux's `script`) slam's progress line shows the
// time left.
TEST_F(Cli, SlamProgressOnATerminalShowsTheTimeLeft) {
  if (std::system("command -v script > /dev/null 2>&1") != 0) GTEST_SKIP() << "no `script`";
  const std::string slam = std::string(INTGRID_CLI) + " slam --log " +
                           write("s.log", kSlamLog).string() + " --out " + (dir_ / "out").string() +
                           " --max-range 8 > /dev/null";
  const auto [status, output] = intgrid::test::run_command("script -qec '" + slam + "' /dev/null");
  if (status != 0) GTEST_SKIP() << "script failed: " << output;
  EXPECT_NE(output.find("SLAM (integer): 1/3 (33%), ETA "), std::string::npos) << output;
  EXPECT_NE(output.find("SLAM (integer): 3/3 (100%) in "), std::string::npos) << output;
}

// `figure slam-sweeps --quick`: three CSVs of one row per SLAM run (both arithmetics at each
// point), finite numbers, E(d) >= 0, the pictures, and the plots, or a note when gnuplot is
// missing.
TEST_F(Cli, SlamSweepsWriteTheirCsvsAndPictures) {
  const std::string header =
      "lambda,xi,window_cells,window_headings,pose_cells,arith,scans,localizations,mappings,"
      "seconds,ms_per_scan,int_over_float_seconds,e_sigma_m,e_d_m,e_d_max_m,e_d_centres_m,"
      "map_occupied_cells,ate_rmse_m,ate_max_m,ate_heading_deg";
  const std::vector<std::string> columns = fields_of(header);
  const auto column = [&](const char* name) {
    return static_cast<std::size_t>(std::find(columns.begin(), columns.end(), name) -
                                    columns.begin());
  };
  CliRun r = run("figure slam-sweeps --quick --out " + (dir_ / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  // --quick: lambda 1 and 3, xi 1 and 3, windows 3 and 5, each in int and float.
  const std::vector<std::pair<std::string, std::pair<const char*, std::vector<int>>>> sweeps = {
      {"slam_lambda.csv", {"lambda", {1, 1, 3, 3}}},
      {"slam_xi.csv", {"xi", {1, 1, 3, 3}}},
      {"slam_depth.csv", {"window_cells", {3, 3, 5, 5}}}};
  for (const auto& [file, swept] : sweeps) {
    SCOPED_TRACE(file);
    std::ifstream in(dir_ / "out" / file);
    const std::vector<std::string> lines =
        lines_of({std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()});
    ASSERT_EQ(lines.size(), 5u);
    EXPECT_EQ(lines[0], header);
    for (std::size_t i = 1; i < lines.size(); ++i) {
      const std::vector<std::string> f = fields_of(lines[i]);
      ASSERT_EQ(f.size(), columns.size()) << lines[i];
      EXPECT_EQ(f[column("arith")], i % 2 == 1 ? "int" : "float") << lines[i];
      EXPECT_EQ(std::stoi(f[column(swept.first)]), swept.second[i - 1]) << lines[i];
      for (std::size_t c = 0; c < f.size(); ++c) {
        if (c == column("arith")) continue;
        std::size_t used = 0;
        const double value = std::stod(f[c], &used);
        EXPECT_EQ(used, f[c].size()) << columns[c] << " in " << lines[i];
        EXPECT_TRUE(std::isfinite(value)) << columns[c] << " in " << lines[i];
        EXPECT_GE(value, 0.0) << columns[c] << " in " << lines[i];
      }
      EXPECT_GT(std::stod(f[column("seconds")]), 0.0) << lines[i];
      EXPECT_GT(std::stoi(f[column("map_occupied_cells")]), 0) << lines[i];
      EXPECT_LE(std::stod(f[column("e_d_m")]), std::stod(f[column("e_d_centres_m")])) << lines[i];
      EXPECT_EQ(std::stoi(f[column("scans")]), 24) << lines[i];
    }
  }
  expect_png(dir_ / "out" / "slam_world.png");
  expect_png(dir_ / "out" / "slam_maps.png");
  if (r.output.find("plots skipped") == std::string::npos)
    for (const char* png : {"slam_lambda.png", "slam_xi.png", "slam_depth.png"})
      expect_png(dir_ / "out" / png);
  for (const auto& entry : fs::directory_iterator(dir_ / "out"))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();

  r = run("figure slam-sweeps --quick --scans 12 --gnuplot " + (dir_ / "no-gnuplot").string() +
          " --out " + (dir_ / "bare").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("plots skipped"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "bare" / "slam_xi.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "bare" / "slam_xi.png"));
}

}  // namespace
