#include "cli/install_paths.hpp"

#include <system_error>

namespace intgrid::cli {

std::filesystem::path share_dir() {
  std::error_code error;
  // Linux names the running executable here; without it, the working folder's layout is tried.
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::filesystem::path bin = error ? std::filesystem::path("bin") : exe.parent_path();
  return (bin / ".." / "share" / "intgrid").lexically_normal();
}

std::filesystem::path bundled_data_dir() {
  return share_dir() / "data";
}

}  // namespace intgrid::cli
