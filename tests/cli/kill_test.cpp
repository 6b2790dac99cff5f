// `intgrid map` killed at each of its output renames (strace's fault injection sends SIGKILL as
// the Nth rename is entered, so renames 1..N-1 happened and N did not) leaves its output folder
// as a reader may find it: the map pair reads as the previous run's map or as this run's, or is
// refused naming image_crc32; never a mix read as a map. The next complete run removes the
// temporary files the killed ones left.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "command_run.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/map_io.hpp"

namespace fs = std::filesystem;

namespace {

// The exit status, or -1 when killed by a signal.
int run(const std::string& command) {
  return intgrid::test::run_command(command).status;
}

void write(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

std::string log_text(double range) {
  std::string text;
  for (int i = 0; i < 3; ++i) {
    const std::string r = std::to_string(range + 0.1 * i);
    text += "RLASER 4 -0.5 0.3 10 " + r + " " + r + " " + r + " " + r + " " +
            std::to_string(0.2 * i) + " 0 0 0 0 0 " + std::to_string(100 + i) + "\n";
  }
  return text;
}

// The same map: geometry, thresholds and every cell.
bool same(const intgrid::io::RosMap& a, const intgrid::io::RosMap& b) {
  const intgrid::core::GridGeometry &g = a.grid.geometry, &h = b.grid.geometry;
  return g.width == h.width && g.height == h.height && g.resolution == h.resolution &&
         g.origin_x == h.origin_x && g.origin_y == h.origin_y && a.negate == b.negate &&
         a.occupied_thresh == b.occupied_thresh && a.free_thresh == b.free_thresh &&
         a.grid.cells == b.grid.cells;
}

TEST(KilledRun, AReaderSeesTheOldMapTheNewOneOrARefusalNeverAMix) {
  if (run("strace -V") != 0)
    GTEST_SKIP() << "strace is not installed (scripts/setup.sh installs it)";
  const fs::path dir = fs::temp_directory_path() / "intgrid_killed_run";
  fs::remove_all(dir);
  fs::create_directories(dir);
  write(dir / "old.log", log_text(2.0));
  write(dir / "new.log", log_text(3.5));
  const std::string map = std::string(INTGRID_CLI) + " map --cell 0.1 --log ";
  ASSERT_EQ(run(map + (dir / "old.log").string() + " --out " + (dir / "old").string()), 0);
  ASSERT_EQ(run(map + (dir / "new.log").string() + " --out " + (dir / "new").string()), 0);
  const intgrid::io::RosMap old_map = intgrid::io::read_ros_map(dir / "old" / "map.yaml");
  const intgrid::io::RosMap new_map = intgrid::io::read_ros_map(dir / "new" / "map.yaml");
  ASSERT_FALSE(same(old_map, new_map));

  const fs::path out = dir / "out";
  int killed = 0, refused = 0;
  for (int n = 1; n < 20; ++n) {
    SCOPED_TRACE("killed at rename " + std::to_string(n));
    fs::remove_all(out);
    fs::copy(dir / "old", out);
    const int status =
        run("strace -f -qq -o /dev/null -e trace=rename,renameat,renameat2 -e "
            "inject=rename,renameat,renameat2:signal=KILL:when=" +
            std::to_string(n) + " " + map + (dir / "new.log").string() + " --out " + out.string());
    if (status == 0) break;  // fewer renames than n: the run completed
    ++killed;
    try {
      const intgrid::io::RosMap seen = intgrid::io::read_ros_map(out / "map.yaml");
      EXPECT_TRUE(same(seen, old_map) || same(seen, new_map));
    } catch (const intgrid::io::InputError& e) {
      EXPECT_EQ(e.field(), "image_crc32") << e.what();
      ++refused;
    }
  }
  // map.pgm, map.yaml and map.png are each renamed into place: three places to be killed, and
  // the one between the image and its YAML is refused.
  EXPECT_GE(killed, 3);
  EXPECT_EQ(refused, 1);
  // A complete run then leaves no temporary file of the killed ones.
  ASSERT_EQ(run(map + (dir / "new.log").string() + " --out " + out.string()), 0);
  for (const fs::directory_entry& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().filename().string().find(".tmp."), std::string::npos) << entry.path();
  fs::remove_all(dir);
}

}  // namespace
