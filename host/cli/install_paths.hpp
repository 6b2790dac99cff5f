// Where the command finds its own files: <prefix>/share/intgrid beside <prefix>/bin/intgrid, the
// same in the build tree (CMake lays it out so) as once installed or moved. No path of the
// source tree is compiled in.
#pragma once

#include <filesystem>

namespace intgrid::cli {

// <folder of the running executable>/../share/intgrid.
std::filesystem::path share_dir();
// share_dir() / "data": the bundled real logs and maps.
std::filesystem::path bundled_data_dir();

}  // namespace intgrid::cli
