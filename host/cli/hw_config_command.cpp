// `intgrid hw-config`: a configuration folder of the sectoral ISM kernel's RTL (rtl/config/NAME)
// from a sensor's parameters. Golden builds the tables (make_ism_kernel) and narrows every word
// (derive_ism_hw); ism_table_files gives the text of the ROM files and of the parameters in
// three formats; this command only chooses the configuration and writes the files. The named
// configurations in rtl/config are this command's output (testbench/sectoral_ism.cmake checks
// that they still are).
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cli/commands.hpp"
#include "cli/kernel_options.hpp"
#include "intgrid/figures/polar_render.hpp"
#include "intgrid/io/atomic_file.hpp"
#include "intgrid/kernel/table_export.hpp"

namespace intgrid::cli {
namespace {

struct HwConfigArgs {
  std::string name;
  std::filesystem::path out;
  std::optional<std::filesystem::path> rom_dir;
  std::optional<double> fov_degrees;
  std::optional<double> fov_radians;
  core::SectoralGrid grid;
  core::ConeSensorModel model;
  int bits = 8;
  double eps = 0.05;
  kernel::IsmKernelFormat format;
};

// The golden checks' fields -> the options of `hw-config`.
const FieldFlags& hw_config_flags() {
  static const FieldFlags flags = {{"FOV", "--fov"},
                                   {"cell size", "--cell"},
                                   {"rings", "--rings"},
                                   {"bins", "--bins"},
                                   {"sectors", "--sectors"},
                                   {"sigma", "--sigma"},
                                   {"k_d", "--k-d"},
                                   {"k_theta", "--k-theta"},
                                   {"k_size", "--k-size"},
                                   {"eps", "--eps"},
                                   {"index width", "--bits"},
                                   {"reading_frac_bits", "--reading-frac"},
                                   {"log_frac_bits", "--log-frac"},
                                   {"quad_coef_frac_bits", "--quad-coef-frac"}};
  return flags;
}

// NAME becomes file names and the .svh's macro SECTORAL_ISM_<NAME>_PARAMS.
void check_name(const std::string& name) {
  const bool ok =
      !name.empty() && std::islower(static_cast<unsigned char>(name.front())) &&
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") == std::string::npos;
  if (!ok)
    bad_option("--name",
               "must be a lower-case letter then letters, digits or '_', got '" + name + "'");
}

void run_hw_config(const HwConfigArgs& a) {
  check_name(a.name);
  core::SectoralGrid grid = a.grid;
  if (a.fov_radians)
    grid.fov = *a.fov_radians;
  else if (a.fov_degrees)
    grid.fov = figures::radians(*a.fov_degrees);
  check_grid_options(grid, true);
  const kernel::IsmHwConfig config{a.name.c_str(), a.model, grid, a.bits, a.eps, a.format};
  // Tools resolve the ROM files from rtl/, where a configuration folder is rtl/config/NAME.
  const std::filesystem::path rom_dir =
      a.rom_dir.value_or(std::filesystem::path("config") / a.name);
  if (rom_dir.is_absolute())
    bad_option("--rom-dir",
               "must be relative (to the folder the tools run in), got " + rom_dir.string());
  std::vector<kernel::GeneratedFile> files;
  try {
    files = kernel::ism_table_files(config, rom_dir);
  } catch (const std::invalid_argument& e) {
    rethrow_naming_kernel_options(e, hw_config_flags());
  }
  std::filesystem::create_directories(a.out);
  std::size_t written = 0;
  for (const kernel::GeneratedFile& file : files) {
    if (file.name.ends_with("_config.hpp")) continue;  // the C++ layers' header: not the RTL's
    io::write_file_atomically(a.out / file.name, file.text);
    std::printf("%s\n", (a.out / file.name).string().c_str());
    ++written;
  }
  std::fprintf(stderr, "intgrid hw-config: %zu files of configuration %s in %s\n", written,
               a.name.c_str(), a.out.string().c_str());
}

}  // namespace

void add_hw_config_command(CLI::App& app) {
  auto a = std::make_shared<HwConfigArgs>();
  CLI::App* cmd = app.add_subcommand(
      "hw-config", "write a configuration folder of the sectoral ISM RTL (ROMs and parameters)");
  cmd->footer(
      "Writes into --out the six $readmemh ROM files of rtl/sectoral_ism.sv and its parameters "
      "as a Verilator -f file (.vc), a parameter macro (.svh) and a Yosys script (.ys), for the "
      "cone sensor model of docs/algorithms.md 3 with the given parameters (defaults: cone16). "
      "The parameter files name the ROMs as --rom-dir/FILE, relative to the folder the tools run "
      "in (rtl/). docs/hardware.md, 'Taking a kernel', shows how to lint, simulate and "
      "synthesize a configuration.");
  cmd->add_option("--name", a->name, "configuration name: file names and the .svh macro")
      ->required();
  cmd->add_option("--out", a->out, "folder to write (created if missing), e.g. rtl/config/NAME")
      ->required();
  cmd->add_option("--rom-dir", a->rom_dir,
                  "the ROM folder as the parameter files name it, relative to where the tools "
                  "run (default config/NAME)");
  CLI::Option* fov =
      cmd->add_option("--fov", a->fov_degrees, "field of view (degrees) (default 30)")
          ->check(real_range(0.0, 180.0, true, true));
  cmd->add_option("--fov-rad", a->fov_radians, "field of view (radians), instead of --fov")
      ->check(real_number("(0, pi)", "in (0, pi)",
                          [](double v) { return v > 0.0 && v < std::numbers::pi; }))
      ->excludes(fov);
  cmd->add_option("--rings", a->grid.rings, "range rings (R)")
      ->transform(whole_range(1, core::kMaxPolarCells))
      ->capture_default_str();
  cmd->add_option("--bins", a->grid.bins, "angular bins across the FOV (A)")
      ->transform(whole_range(1, core::kMaxBins))
      ->capture_default_str();
  cmd->add_option("--sectors", a->grid.sectors, "sectors (Ns), dividing the bins")
      ->transform(whole_range(1, kernel::kMaxKernelSectors))
      ->capture_default_str();
  cmd->add_option("--cell", a->grid.cell, "cell size (m)")
      ->check(positive())
      ->capture_default_str();
  cmd->add_option("--sigma,--sigma0", a->model.sigma0, "sensor standard deviation at 0 m (m)")
      ->check(positive())
      ->capture_default_str();
  cmd->add_option("--k-d", a->model.k_d, "relative growth of sigma per metre")
      ->check(non_negative())
      ->capture_default_str();
  cmd->add_option("--k-theta", a->model.k_theta, "relative growth of sigma at the FOV's edge")
      ->check(non_negative())
      ->capture_default_str();
  cmd->add_option("--k-size", a->model.k_size, "relative growth of sigma for a one-sector obstacle")
      ->check(non_negative())
      ->capture_default_str();
  cmd->add_option("--bits", a->bits, "S_eps index width (the output port)")
      ->transform(whole_range(2, 16))
      ->capture_default_str();
  cmd->add_option("--eps", a->eps, "eps of S_eps")
      ->check(real_range(0.0, 0.5, true, true))
      ->capture_default_str();
  cmd->add_option("--reading-frac", a->format.reading_frac_bits,
                  "fractional bits of the reading, in cells")
      ->transform(whole_range(0, 12))
      ->capture_default_str();
  cmd->add_option("--log-frac", a->format.log_frac_bits, "fractional bits of the log2 values")
      ->transform(whole_range(2, 12))
      ->capture_default_str();
  cmd->add_option("--quad-coef-frac", a->format.quad_coef_frac_bits,
                  "fractional bits of the density's quadratic coefficient")
      ->transform(whole_range(4, 24))
      ->capture_default_str();
  cmd->callback([a] { naming_flags(hw_config_flags(), [&] { run_hw_config(*a); }); });
}

}  // namespace intgrid::cli
