// What every subcommand shares: exit status 2 and one line naming the flag or the file for
// every bad input, help without library internals, the old option names.
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

// Every subcommand's bad inputs, one of each class of option at least (no number, NaN, negative,
// out of range, unknown name, unknown option, missing value, missing file): exit 2 and one line
// naming the flag, or the file; for a bad option, a hint to the subcommand's help. (slam's own
// options are left to the slam command's tests: only the generic errors here.)
TEST_F(Cli, EveryBadInputExitsTwoNamingTheFlagOrTheFile) {
  const fs::path log = write("room.log", "RLASER 4 -0.5 0.3 10 1.0 1.2 1.1 1.3" + kScanTail +
                                             "RLASER 4 -0.5 0.3 10 1.0 1.2 1.1 1.3" + kScanTail);
  const fs::path room = write_globloc_room(dir_);
  const std::string missing = (dir_ / "missing.file").string();
  const std::string out = (dir_ / "out").string();
  const std::string narrow = "ism --sigma 0.02 --cell 0.05 --z 1 --length 2";
  const std::string map = "map --log " + log.string() + " --out " + out;
  const std::string compare = "compare --map " + room.string() + " --reference " + room.string();
  const std::string sweeps =
      "figure globloc-sweeps --quick --out " + out + " --map " + room.string();
  const std::string simulate = "simulate --out " + out;
  const std::string globloc =
      "globloc --map " + room.string() + " --log " + log.string() + " --out " + out;
  const fs::path held = dir_ / "held";
  fs::create_directories(held / "inner");
  struct Case {
    std::string arguments;
    std::string named;  // the flag or the file the message names
    std::string help;   // the subcommand of the hint "run 'intgrid SUB --help'", if any
  };
  const std::vector<Case> cases = {
      // ism
      {"ism --sigma abc --cell 0.05 --z 1 --length 2", "--sigma", "ism"},
      {"ism --sigma nan --cell 0.05 --z 1 --length 2", "--sigma", "ism"},
      {"ism --sigma 0.02 --cell -0.05 --z 1 --length 2", "--cell", "ism"},
      {narrow + " --bits 17", "--bits", "ism"},
      {narrow + " --bits 2.5", "--bits", "ism"},
      {narrow + " --eps 0.5", "--eps", "ism"},
      {narrow + " --eps 1e-17", "--eps", "ism"},
      {"ism --sigma 0.02 --cell 0.05 --z -1 --length 2", "--z", "ism"},
      {narrow + " --k-d -1", "--k-d", "ism"},
      {"ism --sigma 0.02 --cell 0.05 --z 1 --length 0.01", "--length", "ism"},
      {"ism --sigma 0.02 --cell 0.05 --length 2", "--z", "ism"},
      {"ism --cell 0.05 --z 1 --length 2", "--sigma", "ism"},
      {"ism --fov 30 --z inf", "--z", "ism"},
      {"ism --fov 30 --arith int --z 1e12", "--z", "ism"},  // the kernel's "reading z", named
      {"ism --fov 30 --z 1 --arith fixed", "--arith", "ism"},
      {"ism --fov 30 --z 1 --sectors 5", "--sectors", "ism"},
      {"ism --fov 30 --z 1 --k-size -1", "--k-size", "ism"},
      {"ism --fov 30 --agreement -3", "--agreement", "ism"},
      {"ism --fov 30 --agreement 10 --seed x", "--seed", "ism"},
      {"ism --fov 30 --z", "--z", "ism"},
      {"ism --frob 1", "--frob", "ism"},
      // resolution
      {"resolution --sigma 0.02 --pmax 1.5", "--pmax", "resolution"},
      {"resolution --sigma 0.02 --pmax nan", "--pmax", "resolution"},
      {"resolution --sigma -1 --pmax 0.9", "--sigma", "resolution"},
      {"resolution --sigma 0.02", "--pmax", "resolution"},
      // values that crashed, hung, printed NaN or exited 1 unnamed (issue 21, item 10)
      {"resolution --sigma 1e307 --pmax 0.9", "--sigma", "resolution"},
      {"resolution --sigma 1e-315 --pmax 0.9", "--sigma", "resolution"},
      {"ism --sigma 1e-300 --cell 0.05 --z 1 --length 2", "--sigma", "ism"},
      {"ism --fov 30 --arith int --z 1 --sigma 0.5 --cell 0.05", "--sigma", "ism"},
      {"ism --fov 30 --arith int --z 1 --sigma 0.02 --cell 0.05 --rings 200000", "--rings", "ism"},
      {"hw-config --name t --out " + out + " --eps 1e-4", "--eps", "hw-config"},
      {map + " --cell 1e9", "--cell", "map"},
      {map + " --cell 0.003", "--cell", "map"},
      {"slam --log " + log.string() + " --out " + out + " --tracking-degrees 200",
       "--tracking-degrees", "slam"},
      {"slam --log " + log.string() + " --out " + out + " --cell 0.2 --sigma 0.001", "--cell",
       "slam"},
      {"slam --engine grid --log " + log.string() + " --out " + out + " --cell 1e-300", "--cell",
       "slam"},
      {"slam --engine grid --log " + log.string() + " --out " + out + " --sigma 1e18", "--sigma",
       "slam"},
      {globloc + " --sigma 1e9", "--sigma", "globloc"},
      {globloc + " --pose-cell 1e9", "--pose-cell", "globloc"},
      {"figure slam-sweeps --out " + out + " --cell 1e-300", "--cell", "figure slam-sweeps"},
      {sweeps + " --clearance 1e9", "--clearance", "figure globloc-sweeps"},
      {simulate + " --max-range 1e9", "--max-range", "simulate"},
      {simulate + " --odometry-noise 0,0,1e300,0", "--odometry-noise", "simulate"},
      {map + " --cell 0.05 --levels 200", "--levels", "map"},
      // map
      {map + " --cell abc", "--cell", "map"},
      {map + " --cell 0", "--cell", "map"},
      {map + " --res 0", "--cell", "map"},
      {map + " --cell 0.00001", "--cell", "map"},
      {map, "--cell", "map"},
      {map + " --cell 0.05 --sigma nan", "--sigma", "map"},
      {map + " --cell 0.05 --k-d -0.1", "--k-d", "map"},
      {map + " --cell 0.05 --bits 1", "--bits", "map"},
      {map + " --cell 0.05 --levels 0", "--levels", "map"},
      {map + " --cell 0.05 --eps 0.7", "--eps", "map"},
      {map + " --cell 0.05 --eps 1e-300", "--eps", "map"},  // 1/2 + eps rounds to 1/2
      {map + " --cell 0.05 --arith double", "--arith", "map"},
      {map + " --cell 0.05 --veto-bound maybe", "--veto-bound", "map"},
      {"map --log " + missing + " --out " + out + " --cell 0.05", missing, ""},
      // compare
      {compare + " --tolerance-cells -1", "--tolerance-cells", "compare"},
      {compare + " --tolerance-cells x", "--tolerance-cells", "compare"},
      {"compare --map " + room.string(), "--reference", "compare"},
      {"compare --map " + room.string() + " --reference " + missing, missing, ""},
      // figure
      {"figure", "subcommand", "figure"},
      {"figure bogus", "bogus", "figure"},
      {"figure ns-sweep --z nan --out " + out + ".png", "--z", "figure ns-sweep"},
      {"figure ns-sweep --z -1 --out " + out + ".png", "--z", "figure ns-sweep"},
      {"figure ns-sweep --out " + out + ".jpg", "--out", "figure ns-sweep"},
      {"figure fusion --out " + out + ".txt", "--out", "figure fusion"},
      {"figure fusion --frob", "--frob", "figure fusion"},
      {"figure slam-sweeps --frob", "--frob", "figure slam-sweeps"},
      {sweeps + " --trials 0", "--trials", "figure globloc-sweeps"},
      // A pose grid above the limit (was an error on the map's image).
      {sweeps + " --headings 4096 --max-memory 1", "--max-memory", "figure globloc-sweeps"},
      {map + " --cell 0.05 --max-memory 0.5", "--max-memory", "map"},
      {sweeps + " --threads -1", "--threads", "figure globloc-sweeps"},
      {sweeps + " --seed 1.5", "--seed", "figure globloc-sweeps"},
      {sweeps + " --sweeps speed", "--sweeps", "figure globloc-sweeps"},
      {sweeps + " --fov 400", "--fov", "figure globloc-sweeps"},
      {sweeps + " --noise -0.1", "--noise", "figure globloc-sweeps"},
      {sweeps + " --beams 0", "--beams", "figure globloc-sweeps"},
      {sweeps + " --sensor-range inf", "--sensor-range", "figure globloc-sweeps"},
      {sweeps + " --clearance nan", "--clearance", "figure globloc-sweeps"},
      {sweeps + " --headings 2", "--headings", "figure globloc-sweeps"},
      {sweeps + " --levels 10 --veto-levels 20", "--veto-levels", "figure globloc-sweeps"},
      {sweeps + " --pose-cell 0.05", "--pose-cell", ""},
      {"figure globloc-sweeps --quick --out " + out + " --map " + missing, missing, ""},
      // demo
      {"demo --sigma -1", "--sigma", "demo"},
      {"demo --bits 40", "--bits", "demo"},
      {"demo --veto-bound x", "--veto-bound", "demo"},
      {"demo --out " + out + " --data " + missing, missing, ""},
      // simulate
      {simulate + " --noise abc", "--noise", "simulate"},
      {simulate + " --dropout nan", "--dropout", "simulate"},
      {simulate + " --seed -1", "--seed", "simulate"},
      {simulate + " --scans 0", "--scans", "simulate"},
      {simulate + " --sensor radar", "--sensor", "simulate"},
      {simulate + " --fov 400", "--fov", "simulate"},
      {simulate + " --world " + missing, missing, ""},
      {simulate + " --trajectory " + missing, missing, ""},
      {"simulate --scans 5", "--out", "simulate"},
      {simulate + " --frob", "--frob", "simulate"},
      // slam: the generic errors only
      {"slam --log " + log.string() + " --out " + out + " --frob 1", "--frob", "slam"},
      // --out: a file, a folder holding folders (which a run could not replace as one)
      {"map --cell 0.1 --log " + log.string() + " --out " + log.string(), "--out", "map"},
      {"map --cell 0.1 --log " + log.string() + " --out " + held.string(), "--out", "map"},
      {"globloc --map " + room.string() + " --log " + log.string() + " --out " + room.string(),
       "--out", "globloc"},
      {"slam --log " + missing + " --out " + out, missing, ""},
      // globloc
      {globloc + " --pose-cell -1", "--pose-cell", "globloc"},
      {globloc + " --pose-res -1", "--pose-cell", "globloc"},
      {globloc + " --headings 3", "--headings", "globloc"},
      {globloc + " --headings x", "--headings", "globloc"},
      {globloc + " --sigma nan", "--sigma", "globloc"},
      {globloc + " --max-range 0", "--max-range", "globloc"},
      {globloc + " --levels 200", "--levels", "globloc"},
      {globloc + " --veto-levels 20", "--veto-levels", "globloc"},
      {globloc + " --method best", "--method", "globloc"},
      {globloc + " --every 0", "--every", "globloc"},
      {globloc + " --beams -1", "--beams", "globloc"},
      {globloc + " --track 2 --method markov", "--track", ""},
      {globloc + " --track 1001", "--track", "globloc"},
      {globloc + " --track 2 --track-step -1 5", "--track-step", "globloc"},
      {globloc + " --refine-levels 9", "--refine-levels", "globloc"},
      {globloc + " --headings 4096 --refine-levels 5", "--refine-levels", ""},
      {globloc + " --scans 5:2", "--scans", ""},
      {"globloc --map " + missing + " --log " + log.string() + " --out " + out, missing, ""},
      {globloc + " --reference " + missing, missing, ""},
      {globloc + " --frob", "--frob", "globloc"},
      // no subcommand, an unknown one
      {"", "subcommand", "intgrid"},
      {"bogus", "bogus", "intgrid"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.arguments);
    const CliRun r = run(c.arguments);
    EXPECT_EQ(r.status, 2) << r.output;
    expect_error(r, c.named);
    EXPECT_EQ(r.output.rfind("intgrid: error: ", 0), 0u) << r.output;
    if (!c.help.empty()) {
      const std::string sub = c.help == "intgrid" ? "intgrid" : "intgrid " + c.help;
      EXPECT_NE(r.output.find("run '" + sub + " --help'"), std::string::npos) << r.output;
    }
    EXPECT_FALSE(fs::exists(dir_ / "out" / "poses.txt"));
  }
}

// --help exits 0 with every subcommand's options and no CLI11 internals: no transformer map
// ("->", "OR {"), no range bound of more than 12 digits, and only the documented names.
TEST_F(Cli, HelpShowsNoLibraryInternals) {
  const std::vector<std::string> subcommands = {"",
                                                "ism",
                                                "resolution",
                                                "map",
                                                "compare",
                                                "figure",
                                                "figure ns-sweep",
                                                "figure fusion",
                                                "figure slam-sweeps",
                                                "figure globloc-sweeps",
                                                "demo",
                                                "simulate",
                                                "slam",
                                                "globloc",
                                                "localize",
                                                "hw-config"};
  for (const std::string& sub : subcommands) {
    SCOPED_TRACE(sub);
    const CliRun r = run(sub + " --help");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("Usage: intgrid " + sub), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("->"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("OR {"), std::string::npos) << r.output;
    std::size_t digits = 0, longest = 0;
    for (const char c : r.output) {
      digits = std::isdigit(static_cast<unsigned char>(c)) ? digits + 1 : 0;
      longest = std::max(longest, digits);
    }
    EXPECT_LE(longest, 12u) << r.output;
    // Old names work but are not documented.
    if (sub == "slam" || sub == "figure slam-sweeps") continue;  // the SLAM's options: elsewhere
    for (const char* old_name : {"--res ", "--pose-res", "--sigma0", "--readings"})
      EXPECT_EQ(r.output.find(old_name), std::string::npos) << old_name << "\n" << r.output;
  }
  EXPECT_NE(run("map --help").output.find("--cell FLOAT"), std::string::npos);
  EXPECT_NE(run("globloc --help").output.find("--pose-cell FLOAT"), std::string::npos);
  // The top level lists every subcommand on one line each, with a short description.
  const std::vector<std::string> lines = lines_of(run("--help").output);
  const auto at = std::find(lines.begin(), lines.end(), "Subcommands:");
  ASSERT_NE(at, lines.end());
  std::size_t listed = 0;
  for (auto line = at + 1; line != lines.end() && !line->empty(); ++line, ++listed)
    EXPECT_LE(line->size(), 110u) << *line;
  // One line per top-level subcommand in the list above (not "" and not "figure x").
  const auto top_level = std::count_if(subcommands.begin(), subcommands.end(), [](const auto& s) {
    return !s.empty() && s.find(' ') == std::string::npos;
  });
  EXPECT_EQ(listed, static_cast<std::size_t>(top_level));
}

// The old names of renamed options keep working: --res (map), --pose-res (globloc), --sigma0
// (ism --fov), --readings (figure globloc-sweeps).
TEST_F(Cli, OldOptionNamesStillWork) {
  const fs::path log = write("good.log", "RLASER 4 -0.5 0.3 10 1.0 1.0 1.0 1.0" + kScanTail);
  CliRun r = run("map --log " + log.string() + " --out " + (dir_ / "m").string() + " --res 0.05");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(run("ism --fov 30 --z 1 --sigma0 0.03").output,
            run("ism --fov 30 --z 1 --sigma 0.03").output);
  const fs::path room = write_globloc_room(dir_);
  ASSERT_EQ(run("simulate --out " + (dir_ / "sim").string() + " --world " + room.string() +
                " --scans 2 --seed 3")
                .status,
            0);
  r = run("globloc --map " + room.string() + " --log " + (dir_ / "sim" / "sim.log").string() +
          " --out " + (dir_ / "g").string() + " --scans 0:0 --pose-res 0.1 --headings 16");
  EXPECT_EQ(r.status, 0) << r.output;
  r =
      run("figure globloc-sweeps --quick --trials 1 --sweeps readings --readings 20 --headings 16 "
          "--gnuplot " +
          (dir_ / "no-gnuplot").string() + " --out " + (dir_ / "s").string() + " --map " +
          room.string());
  EXPECT_EQ(r.status, 0) << r.output;
}

}  // namespace
