// ism_kernel_export NAME OUTDIR: writes sectoral_ism_NAME_config.hpp, the constexpr
// configuration struct of the C++ layers (hls/, systemc/) for the named sectoral ISM hardware
// configuration (golden/kernel/include/intgrid/kernel/hardware_configs.hpp), into OUTDIR, as
// golden's ism_table_files builds it (intgrid/kernel/table_export.hpp). The RTL's files of the
// same configuration are committed in rtl/config/NAME (written by `intgrid hw-config`). Output is
// deterministic; a file whose content is unchanged is not rewritten.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "intgrid/kernel/table_export.hpp"

namespace {

void write_if_changed(const std::filesystem::path& path, const std::string& text) {
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      const std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (old == text) return;
    }
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

int run(const std::string& name, const std::filesystem::path& dir) {
  const intgrid::kernel::IsmHwConfig& config = intgrid::kernel::ism_hw_config(name);
  std::filesystem::create_directories(dir);
  for (const intgrid::kernel::GeneratedFile& file : intgrid::kernel::ism_table_files(config, {}))
    if (file.name.ends_with("_config.hpp")) write_if_changed(dir / file.name, file.text);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: ism_kernel_export NAME OUTDIR   (NAME: cone16 | cone12)\n");
    return 2;
  }
  try {
    return run(argv[1], argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ism_kernel_export: %s\n", e.what());
    return 1;
  }
}
