// Output folders that change as one: a reader finds the previous run's files or this run's.
#include "intgrid/io/output_folder.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

#include "intgrid/io/atomic_file.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace intgrid::io {
namespace {

using test::TempDir;
using ::testing::HasSubstr;

TEST(OutputFolder, NothingIsVisibleBeforeTheCommitAndTheSetAfterIt) {
  const TempDir dir;
  OutputFolder out(dir / "run");
  write_file_atomically(out.file("a.txt"), "a\n");
  write_file_atomically(out.file("b.txt"), "b\n");
  EXPECT_FALSE(fs::exists(dir / "run"));
  out.commit();
  EXPECT_EQ(test::read_bytes(dir / "run" / "a.txt"), "a\n");
  EXPECT_EQ(test::read_bytes(dir / "run" / "b.txt"), "b\n");
  EXPECT_EQ(dir.entry_count(), 1u) << "no staging folder left";
}

TEST(OutputFolder, ReplacesThePreviousSetAndKeepsTheUsersOtherFiles) {
  const TempDir dir;
  fs::create_directories(dir / "run");
  dir.write("run/a.txt", "old a\n");
  dir.write("run/relations.csv", "old, not written by the new run\n");
  dir.write("run/notes.txt", "the user's\n");
  {
    OutputFolder out(dir / "run");
    write_file_atomically(out.file("a.txt"), "new a\n");
    write_file_atomically(out.file("relations.csv"), "new\n");
    write_file_atomically(out.file("b.txt"), "new b\n");
    EXPECT_EQ(test::read_bytes(dir / "run" / "a.txt"), "old a\n") << "old set until the commit";
    out.commit();
  }
  EXPECT_EQ(test::read_bytes(dir / "run" / "a.txt"), "new a\n");
  EXPECT_EQ(test::read_bytes(dir / "run" / "b.txt"), "new b\n");
  EXPECT_EQ(test::read_bytes(dir / "run" / "relations.csv"), "new\n");
  EXPECT_EQ(test::read_bytes(dir / "run" / "notes.txt"), "the user's\n");
  EXPECT_EQ(dir.entry_count(), 1u) << "the old folder is removed";
}

TEST(OutputFolder, ARunThatStopsBeforeItsCommitLeavesTheOldSet) {
  const TempDir dir;
  fs::create_directories(dir / "run");
  dir.write("run/a.txt", "old a\n");
  {
    OutputFolder out(dir / "run");
    write_file_atomically(out.file("a.txt"), "new a\n");
  }
  EXPECT_EQ(test::read_bytes(dir / "run" / "a.txt"), "old a\n");
  EXPECT_EQ(dir.entry_count(), 1u) << "the staging folder is removed";
}

TEST(OutputFolder, TheNextRunRemovesTheStagingFoldersOfKilledOnes) {
  const TempDir dir;
  const std::string dead = std::to_string(test::dead_pid()), live = std::to_string(::getppid());
  fs::create_directories(dir / ("run.tmp." + dead + ".3"));
  dir.write("run.tmp." + dead + ".3/a.txt", "half");
  fs::create_directories(dir / ("run.tmp." + live + ".0"));
  OutputFolder out(dir / "run");
  out.commit();
  EXPECT_FALSE(fs::exists(dir / ("run.tmp." + dead + ".3")));
  EXPECT_TRUE(fs::exists(dir / ("run.tmp." + live + ".0"))) << "a live run's is kept";
}

TEST(OutputFolder, RefusesAFileAFolderWithSubfoldersAndTheWorkingFolder) {
  const TempDir dir;
  dir.write("file", "");
  EXPECT_THROW(OutputFolder(dir / "file"), OutputFolderError);
  fs::create_directories(dir / "tree" / "inner");
  try {
    OutputFolder out(dir / "tree");
    ADD_FAILURE() << "a folder holding a folder is refused";
  } catch (const OutputFolderError& e) {
    EXPECT_THAT(e.what(), HasSubstr("inner"));
    EXPECT_THAT(e.what(), HasSubstr((dir / "tree").string()));
  }
  const fs::path before = fs::current_path();
  fs::create_directories(dir / "here");
  fs::current_path(dir / "here");
  EXPECT_THROW(OutputFolder("."), OutputFolderError);
  EXPECT_THROW(OutputFolder(".."), OutputFolderError);
  fs::current_path(before);
  EXPECT_TRUE(fs::exists(dir / "tree" / "inner"));
}

TEST(OutputFolder, ATrailingSlashNamesTheSameFolder) {
  const TempDir dir;
  OutputFolder out((dir / "run").string() + "/");
  EXPECT_EQ(out.folder(), dir / "run");
  out.commit();
  EXPECT_TRUE(fs::is_directory(dir / "run"));
}

}  // namespace
}  // namespace intgrid::io
