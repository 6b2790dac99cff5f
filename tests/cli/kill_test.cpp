// `intgrid map` and `intgrid slam` killed at each of their renames (strace's fault injection
// sends SIGKILL as the Nth call of a rename is entered, so calls 1..N-1 happened and N did not)
// leave their output folder as a reader may find it: every file of the previous run's set, or every
// file of this run's, never a mix (a new map.pgm under an old map.yaml, a new trajectory.txt
// beside an old metrics.json). The next complete run removes what the killed ones left.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "command_run.hpp"
#include "data_dir.hpp"

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

// Lines [first, last) of the bundled raw log: a few of its scans.
std::string bundled_scans(std::size_t first, std::size_t last) {
  std::ifstream in(fs::path(intgrid::test::data_dir()) / "malaga_telecom_loop.log");
  std::string line, text;
  for (std::size_t n = 0; n < last && std::getline(in, line); ++n)
    if (n >= first) text += line + "\n";
  return text;
}

// A folder's files by name. metrics.json holds times that differ from run to run: of it only
// the line naming the log is kept, which tells the runs apart.
std::map<std::string, std::string> contents(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    std::string text = bytes.str();
    if (entry.path().filename() == "metrics.json") {
      std::istringstream lines(text);
      std::string line;
      text.clear();
      while (std::getline(lines, line))
        if (line.find("\"log\"") != std::string::npos) text = line;
    }
    files[entry.path().filename().string()] = text;
  }
  return files;
}

// Runs `command --log old.log --out old`, then the same with new.log into new, then kills
// the new run writing over a copy of old at each of its renames; checks what a reader finds.
void expect_no_mix(const std::string& name, const std::string& command, const std::string& old_log,
                   const std::string& new_log) {
  const fs::path dir = fs::temp_directory_path() / ("intgrid_killed_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  write(dir / "old.log", old_log);
  write(dir / "new.log", new_log);
  const std::string prefix = std::string(INTGRID_CLI) + " " + command + " --log ";
  const std::string new_run = prefix + (dir / "new.log").string() + " --out ";
  ASSERT_EQ(run(prefix + (dir / "old.log").string() + " --out " + (dir / "old").string()), 0);
  ASSERT_EQ(run(new_run + (dir / "new").string()), 0);
  const auto old_set = contents(dir / "old"), new_set = contents(dir / "new");
  for (const auto& [file, bytes] : old_set)
    ASSERT_NE(bytes, new_set.at(file)) << file << " must tell the runs apart";

  // strace counts each system call apart: the files are renamed with rename, the folder is
  // exchanged with renameat2.
  const fs::path out = dir / "out";
  int killed = 0;
  for (const std::string call : {"rename", "renameat", "renameat2"})
    for (int n = 1; n < 40; ++n) {
      SCOPED_TRACE(name + " killed at " + call + " " + std::to_string(n));
      fs::remove_all(out);
      fs::copy(dir / "old", out);
      // LeakSanitizer cannot run under ptrace: in the sanitized build a complete run would end
      // in its fatal error instead of exit 0, so the traced runs do not check leaks.
      const int status =
          run("ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0\" "
              "strace -f -qq -o /dev/null -e trace=" +
              call + " -e inject=" + call + ":signal=KILL:when=" + std::to_string(n) + " " +
              new_run + out.string());
      if (status == 0) break;  // fewer calls than n: the run completed
      ++killed;
      const auto seen = contents(out);
      EXPECT_TRUE(seen == old_set || seen == new_set);
    }
  // Each output file is renamed in the staging folder, then the folder into place.
  EXPECT_EQ(killed, static_cast<int>(new_set.size()) + 1);
  // A complete run then leaves nothing of the killed ones.
  ASSERT_EQ(run(new_run + out.string()), 0);
  EXPECT_EQ(contents(out), new_set);
  for (const fs::path& folder : {dir, out})
    for (const fs::directory_entry& entry : fs::directory_iterator(folder))
      EXPECT_EQ(entry.path().filename().string().find(".tmp."), std::string::npos) << entry.path();
  fs::remove_all(dir);
}

TEST(KilledRun, AMapReaderSeesTheOldSetOrTheNewOneNeverAMix) {
  if (run("strace -V") != 0)
    GTEST_SKIP() << "strace is not installed (scripts/setup.sh installs it)";
  expect_no_mix("map", "map --cell 0.1", log_text(2.0), log_text(3.5));
}

TEST(KilledRun, ASlamReaderSeesTheOldSetOrTheNewOneNeverAMix) {
  if (run("strace -V") != 0)
    GTEST_SKIP() << "strace is not installed (scripts/setup.sh installs it)";
  expect_no_mix("slam", "slam --res 0.1", bundled_scans(0, 12), bundled_scans(12, 24));
}

}  // namespace
