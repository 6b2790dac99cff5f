// Names of the temporary files and folders that outputs are written under before a rename puts
// them in place ("NAME.tmp.<pid>.<n>"), and the removal of those that killed writers left.
// Private to the io library: AtomicFile and OutputFolder share them.
#pragma once

#include <filesystem>

namespace intgrid::io {

// "TARGET.tmp.<pid>.<n>": unique per process and per call, so concurrent writers of one target
// never share a temporary.
std::filesystem::path temporary_path_for(const std::filesystem::path& target);

// Removes (with their contents) the temporaries of target left by writers that were killed
// before they could: "NAME.tmp.<pid>.<n>" whose process no longer exists. A live process's are
// kept (another run may be writing the same output); a dead writer's pid taken by a new process
// keeps its temporary until that process ends.
void remove_leftovers_of_dead_writers(const std::filesystem::path& target);

}  // namespace intgrid::io
