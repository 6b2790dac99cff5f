// `intgrid ism`: the exact ISM of one reading as CSV or JSON. Without --fov the narrow-FOV
// ISM along a line of sight (eq. 2.12); with --fov the large-FOV ISM over a sensor's polar
// grid (docs/algorithms.md 3), in double precision or as the integer kernel's indices, or the
// kernel's agreement with the double model over many readings.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/kernel_agreement.hpp"
#include "intgrid/core/narrow_ism.hpp"
#include "intgrid/figures/polar_render.hpp"
#include "intgrid/kernel/ism_kernel.hpp"

namespace intgrid::cli {
namespace {

// The height of an --png picture, whatever the polar grid's size.
constexpr double kPolarPictureHeightPx = 600.0;

struct IsmArgs {
  // Both modes.
  std::optional<double> k_d;
  std::optional<double> cell;
  std::optional<double> z;
  std::optional<int> bits;
  std::optional<double> eps;
  bool json = false;
  // Narrow FOV.
  std::optional<double> sigma;
  std::optional<double> length;
  // Large FOV: the options fill grid and model, apart from the FOV (in degrees here), the
  // cell size and k_d, whose defaults depend on the mode.
  std::optional<double> fov_degrees;
  core::SectoralGrid grid;
  core::ConeSensorModel model;
  core::Arithmetic arithmetic = core::Arithmetic::floating;
  std::optional<std::filesystem::path> png;
  std::optional<std::size_t> agreement;
  std::uint64_t seed = 1;
};

template <class T>
T required(const std::optional<T>& value, const char* message) {
  if (!value) throw std::invalid_argument(message);
  return *value;
}

void run_narrow_ism(const IsmArgs& a) {
  const core::GaussianBeamModel model{required(a.sigma, "--sigma is required without --fov"),
                                      a.k_d.value_or(0.0)};
  const double cell = required(a.cell, "--cell is required without --fov");
  const double length = required(a.length, "--length is required without --fov");
  const double z = required(a.z, "--z is required");
  core::check_model(model);
  if (!(cell > 0.0) || !std::isfinite(cell))
    throw std::invalid_argument("--cell must be a positive number of metres");
  const auto cells = static_cast<std::size_t>(std::llround(length / cell));
  if (cells == 0) throw std::invalid_argument("--length must hold at least one cell");
  if (cells > 100'000'000) throw std::invalid_argument("--length / --cell exceeds 10^8 cells");
  if (!std::isfinite(z)) throw std::invalid_argument("--z must be finite");
  std::optional<core::SepsCodec> codec;
  if (a.bits || a.eps) codec.emplace(a.bits.value_or(8), a.eps.value_or(0.05));
  const std::vector<double> ism = core::narrow_ism(model, z, cell, cells);
  if (a.json) {
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t k = 1; k <= cells; ++k) {
      nlohmann::json row = {{"k", k}, {"d", static_cast<double>(k) * cell}, {"p", ism[k - 1]}};
      if (codec) row["index"] = codec->quantize_conservative(ism[k - 1]);
      rows.push_back(row);
    }
    print_json({{"sigma", model.sigma0},
                {"k_d", model.k_d},
                {"cell", cell},
                {"z", z},
                {"argmax_cell", core::predicted_argmax_cell(model, z, cell, cells)},
                {"cells", rows}});
    return;
  }
  std::printf(codec ? "k,d,p,index\n" : "k,d,p\n");
  for (std::size_t k = 1; k <= cells; ++k) {
    std::printf("%zu,%.6f,%.17g", k, static_cast<double>(k) * cell, ism[k - 1]);
    if (codec) std::printf(",%d", codec->quantize_conservative(ism[k - 1]));
    std::printf("\n");
  }
}

void print_polar_json(const core::SectoralGrid& grid, const core::ConeSensorModel& model, double z,
                      const std::vector<double>& ism, const std::vector<std::int16_t>& indices) {
  nlohmann::json rows = nlohmann::json::array();
  const auto bins = static_cast<std::size_t>(grid.bins);
  for (std::size_t i = 0; i < ism.size(); ++i) {
    nlohmann::json row = {{"ring", i / bins + 1}, {"bin", i % bins + 1}, {"p", ism[i]}};
    if (!indices.empty()) row["index"] = indices[i];
    rows.push_back(row);
  }
  print_json({{"grid", figures::polar_grid_json(grid)},
              {"sigma0", model.sigma0},
              {"k_d", model.k_d},
              {"k_theta", model.k_theta},
              {"k_size", model.k_size},
              {"z", z},
              {"cells", rows}});
}

void run_sectoral_ism(const IsmArgs& a) {
  core::SectoralGrid grid = a.grid;
  grid.fov = figures::radians(*a.fov_degrees);
  grid.cell = a.cell.value_or(grid.cell);
  core::ConeSensorModel model = a.model;
  model.k_d = a.k_d.value_or(model.k_d);
  core::check_sectoral_grid(grid);
  core::check_model(model);
  if ((a.bits || a.eps) && a.arithmetic == core::Arithmetic::floating && !a.agreement)
    throw std::invalid_argument("with --fov, --bits and --eps need --arith int or --agreement");
  const core::SepsCodec codec(a.bits.value_or(8), a.eps.value_or(0.05));
  if (a.agreement) {
    const KernelAgreementReport report =
        kernel_agreement_report(model, grid, codec, *a.agreement, a.seed);
    if (a.json) return print_json(kernel_agreement_json(report));
    return print_kernel_agreement(report);
  }
  double z = required(a.z, "--z is required (unless --agreement)");
  check_reading_option(z);
  std::vector<std::int16_t> indices;
  if (a.arithmetic == core::Arithmetic::integer) {
    // p then comes from the same fixed-point reading as the indices.
    const kernel::IsmKernelTables kernel = kernel::make_ism_kernel(model, grid, codec);
    const std::uint32_t reading = kernel::quantize_reading(kernel, z);
    z = kernel::reading_metres(kernel, reading);
    indices = kernel::ism_kernel_indices(kernel, reading);
  }
  const std::vector<double> ism = core::sectoral_ism(model, grid, z);
  if (a.png) {
    const double reach = (grid.rings + 0.5) * grid.cell;
    io::write_png(*a.png,
                  figures::render_polar(figures::polar_frame(grid, reach / kPolarPictureHeightPx),
                                        grid, ism, io::ProbabilityScale::grey));
  }
  if (a.json) return print_polar_json(grid, model, z, ism, indices);
  std::printf(indices.empty() ? "ring,bin,p\n" : "ring,bin,p,index\n");
  figures::write_polar_csv_rows(std::cout, "", grid, ism, indices);
  std::cout.flush();
}

}  // namespace

void add_ism_command(CLI::App& app) {
  auto a = std::make_shared<IsmArgs>();
  CLI::App* cmd = app.add_subcommand(
      "ism",
      "print the exact ISM of a reading: narrow FOV (eq. 2.12) as CSV k,d,p; with --fov the "
      "large-FOV ISM over the sensor's polar grid as CSV ring,bin,p");
  cmd->footer(
      "Narrow FOV needs --sigma, --cell, --z and --length. --fov selects the large FOV, with "
      "the cone model of docs/algorithms.md 3: sigma = sigma0 (1 + k_d d) (1 + k_theta theta) "
      "(1 + k_size / |S|) / (1 + k_size). With --arith int, the index column is the integer "
      "kernel's at the fixed-point reading nearest z, and p the double ISM at that same reading.");
  CLI::Option* fov = cmd->add_option("--fov", a->fov_degrees,
                                     "large-FOV mode: the sensor's field of view (degrees)");
  // Both modes.
  cmd->add_option("--k-d", a->k_d,
                  "relative growth of sigma per metre (default 0; with --fov 0.05)");
  cmd->add_option("--cell", a->cell, "cell size (m) (with --fov: default 0.05)");
  CLI::Option* z = cmd->add_option("--z", a->z, "the reading (m)");
  cmd->add_option("--bits", a->bits,
                  "S_eps index width (default 8); without --fov, adds the index column")
      ->check(CLI::Range(2, 16));
  cmd->add_option("--eps", a->eps, "eps of S_eps (default 0.05)")->check(CLI::Range(0.0, 0.5));
  cmd->add_flag("--json", a->json, "print JSON instead of CSV");
  // Narrow FOV.
  cmd->add_option("--sigma", a->sigma, "sensor standard deviation (m)")
      ->check(CLI::PositiveNumber)
      ->excludes(fov);
  cmd->add_option("--length", a->length, "length of the line of sight (m)")
      ->check(CLI::PositiveNumber)
      ->excludes(fov);
  // Large FOV.
  cmd->add_option("--bins", a->grid.bins, "angular bins across the FOV (A)")
      ->capture_default_str()
      ->needs(fov);
  cmd->add_option("--rings", a->grid.rings, "range rings (R)")->capture_default_str()->needs(fov);
  cmd->add_option("--sectors", a->grid.sectors, "sectors (Ns), dividing the bins")
      ->capture_default_str()
      ->needs(fov);
  cmd->add_option("--sigma0", a->model.sigma0, "standard deviation at distance 0 (m)")
      ->capture_default_str()
      ->needs(fov);
  cmd->add_option("--k-theta", a->model.k_theta, "relative growth of sigma at the FOV's edge")
      ->capture_default_str()
      ->needs(fov);
  cmd->add_option("--k-size", a->model.k_size, "relative growth of sigma for a one-sector obstacle")
      ->capture_default_str()
      ->needs(fov);
  CLI::Option* agreement =
      cmd->add_option("--agreement", a->agreement,
                      "instead of the ISM, print the integer kernel's agreement with the "
                      "quantized double ISM over this many random readings and the edge readings")
          ->check(CLI::Range(0.0, 1e7))
          ->needs(fov)
          ->excludes(z);
  cmd->add_option("--seed", a->seed, "seed of the random readings of --agreement")
      ->capture_default_str()
      ->needs(agreement);
  add_arithmetic_option(*cmd, a->arithmetic,
                        "float: the double ISM; int: adds the integer kernel's S_eps index, and "
                        "p is the double ISM at the kernel's fixed-point reading")
      ->default_str("float")
      ->needs(fov)
      ->excludes(agreement);
  cmd->add_option("--png", a->png, "also write the ISM (the p column) as a picture of the FOV")
      ->needs(fov)
      ->excludes(agreement);
  cmd->callback([a] { a->fov_degrees ? run_sectoral_ism(*a) : run_narrow_ism(*a); });
}

}  // namespace intgrid::cli
