#include "intgrid/io/output_folder.hpp"

#include <fcntl.h>
#include <stdio.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "staging_names.hpp"

namespace fs = std::filesystem;

namespace intgrid::io {

namespace {

[[noreturn]] void fail(const fs::path& folder, const std::string& what, int error) {
  throw std::runtime_error("cannot " + what + " " + folder.string() + ": " + std::strerror(error));
}

// Whether inner is outer or lies inside it (both existing).
bool holds(const fs::path& outer, const fs::path& inner) {
  std::error_code error;
  const fs::path a = fs::canonical(outer, error), b = fs::canonical(inner, error);
  if (error) return false;
  auto i = a.begin(), j = b.begin();
  for (; i != a.end(); ++i, ++j)
    if (j == b.end() || *i != *j) return false;
  return true;
}

// The first folder (not a link to one) inside folder, or an empty path.
fs::path first_subfolder(const fs::path& folder) {
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    if (entry.is_directory() && !entry.is_symlink()) return entry.path();
  return {};
}

}  // namespace

OutputFolder::OutputFolder(const fs::path& folder)
    : folder_(fs::absolute(folder).lexically_normal()) {
  if (!folder_.has_filename()) folder_ = folder_.parent_path();  // "out/" names "out"
  if (fs::exists(folder_)) {
    if (!fs::is_directory(folder_)) throw OutputFolderError(folder.string() + ": is not a folder");
    if (holds(folder_, fs::current_path()))
      throw OutputFolderError(folder.string() +
                              ": holds the working folder, which a run cannot replace; name a "
                              "folder of the outputs' own");
    if (const fs::path inner = first_subfolder(folder_); !inner.empty())
      throw OutputFolderError(folder.string() + ": holds the folder " + inner.filename().string() +
                              ", which the run does not write; name a folder of the outputs' own");
  }
  fs::create_directories(folder_.parent_path());
  remove_leftovers_of_dead_writers(folder_);
  staging_ = temporary_path_for(folder_);
  std::error_code error;
  fs::create_directory(staging_, error);
  if (error) fail(staging_, "create the folder", error.value());
}

OutputFolder::~OutputFolder() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

void OutputFolder::commit() {
  std::error_code error;
  if (!fs::exists(folder_)) {
    fs::rename(staging_, folder_, error);
    if (error) fail(folder_, "create", error.value());
    committed_ = true;
    return;
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(folder_)) {
    const fs::path kept = staging_ / entry.path().filename();
    if (fs::exists(fs::symlink_status(kept))) continue;  // the run wrote it
    if (entry.is_symlink())
      fs::copy_symlink(entry.path(), kept, error);
    else if (entry.is_directory())
      throw OutputFolderError(folder_.string() + ": holds the folder " +
                              entry.path().filename().string() + ", which the run does not write");
    else if (fs::create_hard_link(entry.path(), kept, error); error)
      fs::copy_file(entry.path(), kept, error);  // a file system without hard links
    if (error) fail(entry.path(), "keep", error.value());
  }
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, folder_.c_str(), RENAME_EXCHANGE) != 0) {
    if (errno != EINVAL && errno != ENOSYS) fail(folder_, "replace", errno);
    // No exchange on this file system: the old folder moves aside first, so that for a moment
    // a reader finds no folder, and never a mix.
    const fs::path aside = temporary_path_for(folder_);
    fs::rename(folder_, aside, error);
    if (error) fail(folder_, "replace", error.value());
    fs::rename(staging_, folder_, error);
    if (error) {
      std::error_code ignored;
      fs::rename(aside, folder_, ignored);
      fail(folder_, "replace", error.value());
    }
    staging_ = aside;
  }
  committed_ = true;
  fs::remove_all(staging_, error);  // the old set; a leftover is removed by the next run
}

}  // namespace intgrid::io
