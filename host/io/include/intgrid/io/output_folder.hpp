// A command's output folder that changes as one: a run writes its files into a staging folder
// beside the output folder and commit() puts the staging folder in its place in one rename, so
// that a reader finds the previous run's set of files or this run's, never a mix (a new
// trajectory.txt beside an old metrics.json, a new map.yaml beside an old map.png).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace intgrid::io {

// The output folder cannot be used: it is not a folder, it holds the working folder (it could
// not be replaced), or it holds a folder that the run does not write. what() names the folder.
class OutputFolderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class OutputFolder {
 public:
  // Checks folder (see OutputFolderError) and creates the staging folder
  // "NAME.tmp.<pid>.<n>" beside it, after removing those that killed runs left (their process
  // no longer exists). Throws std::runtime_error if the staging folder cannot be created.
  explicit OutputFolder(const std::filesystem::path& folder);
  // Removes the staging folder unless commit() succeeded.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // Where the run writes its file `name`: inside the staging folder.
  std::filesystem::path file(const std::string& name) const { return staging_ / name; }
  const std::filesystem::path& folder() const { return folder_; }

  // Puts the staging folder in the output folder's place: a rename if there was none; else
  // the files of the old folder that the run did not write are linked into the staging folder
  // (a user's notes stay; a previous run's outputs that this run does not write go with the
  // old set), the two folders are exchanged in one renameat2(RENAME_EXCHANGE), and the old one
  // is removed. Throws std::runtime_error naming the folder if a step fails; the output folder
  // is then the old one, complete.
  void commit();

 private:
  std::filesystem::path folder_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

}  // namespace intgrid::io
