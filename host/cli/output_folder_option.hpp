// `--out FOLDER` of the commands that write a set of files (map, slam, globloc, simulate): the
// folder that changes as one when the run commits (io::OutputFolder), opened before the run's
// work so that an unusable folder is an option error at once, not after minutes.
#pragma once

#include <filesystem>

#include "cli/options.hpp"
#include "intgrid/io/output_folder.hpp"

namespace intgrid::cli {

inline io::OutputFolder open_output_folder(const std::filesystem::path& folder) {
  try {
    return io::OutputFolder(folder);
  } catch (const io::OutputFolderError& e) {
    bad_option("--out", e.what());
  }
}

}  // namespace intgrid::cli
