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
#include "cli/kernel_options.hpp"
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
  std::optional<double> sigma;  // narrow: sigma0 of the Gaussian beam; large: the cone's sigma0
  // Narrow FOV.
  std::optional<double> length;
  // Large FOV: the options fill grid and model, apart from the FOV (in degrees here), the
  // cell size, sigma and k_d, whose defaults depend on the mode.
  std::optional<double> fov_degrees;
  core::SectoralGrid grid;
  core::ConeSensorModel model;
  core::Arithmetic arithmetic = core::Arithmetic::floating;
  std::optional<std::filesystem::path> png;
  std::optional<std::size_t> agreement;
  std::uint64_t seed = 1;
};

// The golden model's fields -> the options of `ism`.
const FieldFlags& ism_flags() {
  static const FieldFlags flags = {
      {"sigma", "--sigma"},   {"k_d", "--k-d"},         {"k_theta", "--k-theta"},
      {"k_size", "--k-size"}, {"cell size", "--cell"},  {"index width", "--bits"},
      {"eps", "--eps"},       {"reading z", "--z"},     {"rings", "--rings"},
      {"bins", "--bins"},     {"sectors", "--sectors"}, {"FOV", "--fov"}};
  return flags;
}

template <class T>
T required(const std::optional<T>& value, const char* flag, const char* when) {
  if (!value) throw OptionError(std::string(flag) + " is required " + when);
  return *value;
}

void run_narrow_ism(const IsmArgs& a) {
  const core::GaussianBeamModel model{required(a.sigma, "--sigma", "without --fov"),
                                      a.k_d.value_or(0.0)};
  const double cell = required(a.cell, "--cell", "without --fov");
  const double length = required(a.length, "--length", "without --fov");
  const double z = required(a.z, "--z", "(unless --fov with --agreement)");
  check_reading_option(z);
  const auto cells = static_cast<std::size_t>(std::llround(length / cell));
  if (cells == 0) bad_option("--length", "must hold at least one cell of --cell");
  if (cells > 100'000'000) bad_option("--length", "holds more than 10^8 cells of --cell");
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
  model.sigma0 = a.sigma.value_or(model.sigma0);
  model.k_d = a.k_d.value_or(model.k_d);
  check_grid_options(grid, a.arithmetic == core::Arithmetic::integer || a.agreement);
  if ((a.bits || a.eps) && a.arithmetic == core::Arithmetic::floating && !a.agreement)
    throw OptionError("with --fov, --bits and --eps need --arith int or --agreement");
  const core::SepsCodec codec(a.bits.value_or(8), a.eps.value_or(0.05));
  if (a.agreement) {
    const KernelAgreementReport report =
        kernel_agreement_report(model, grid, codec, *a.agreement, a.seed);
    if (a.json) return print_json(kernel_agreement_json(report));
    return print_kernel_agreement(report);
  }
  double z = required(a.z, "--z", "(unless --agreement)");
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

void check_grid_options(const core::SectoralGrid& g, bool kernel) {
  if (g.sectors > g.bins)
    bad_option("--sectors",
               std::to_string(g.sectors) + " exceeds --bins " + std::to_string(g.bins) + " (A)");
  if (g.bins % g.sectors != 0)
    bad_option("--bins", std::to_string(g.bins) + " is no multiple of --sectors " +
                             std::to_string(g.sectors) +
                             ", so sectors would be unequal or asymmetric about the axis");
  if (static_cast<long long>(g.rings) * g.bins > core::kMaxPolarCells)
    bad_option("--rings", std::to_string(g.rings) + " x --bins " + std::to_string(g.bins) +
                              " exceeds " + std::to_string(core::kMaxPolarCells) + " polar cells");
  if (kernel && g.sectors > kernel::kMaxKernelSectors)
    bad_option("--sectors", std::to_string(g.sectors) + " exceeds the integer kernel's " +
                                std::to_string(kernel::kMaxKernelSectors) +
                                " (--arith int, --agreement)");
  // What is left to the golden check (nothing, with the options' own checks) is named too.
  naming_flags({{"FOV", "--fov"},
                {"cell size", "--cell"},
                {"rings", "--rings"},
                {"bins", "--bins"},
                {"sectors", "--sectors"}},
               [&] { core::check_sectoral_grid(g); });
}

void add_ism_command(CLI::App& app) {
  auto a = std::make_shared<IsmArgs>();
  CLI::App* cmd = app.add_subcommand("ism", "the exact ISM of one reading, as CSV or JSON");
  cmd->footer(
      "Narrow FOV (eq. 2.12): needs --sigma, --cell, --z and --length; CSV k,d,p, one row a "
      "cell. --fov selects the large FOV over the sensor's polar grid, CSV ring,bin,p, with the "
      "cone model of docs/algorithms.md 3: sigma = sigma0 (1 + k_d d) (1 + k_theta theta) "
      "(1 + k_size / |S|) / (1 + k_size), sigma0 being --sigma. With --arith int, the index "
      "column is the integer kernel's at the fixed-point reading nearest z, and p the double ISM "
      "at that same reading.");
  CLI::Option* fov = cmd->add_option("--fov", a->fov_degrees,
                                     "large-FOV mode: the sensor's field of view (degrees)")
                         ->check(real_range(0.0, 180.0, true, true));
  // Both modes.
  cmd->add_option("--sigma,--sigma0", a->sigma,
                  "sensor standard deviation at distance 0 (m) (with --fov: default 0.02)")
      ->check(positive());
  cmd->add_option("--k-d", a->k_d,
                  "relative growth of sigma per metre (default 0; with --fov 0.05)")
      ->check(non_negative());
  cmd->add_option("--cell", a->cell, "cell size (m) (with --fov: default 0.05)")->check(positive());
  CLI::Option* z = cmd->add_option("--z", a->z, "the reading (m)")->check(finite());
  cmd->add_option("--bits", a->bits,
                  "S_eps index width (default 8); without --fov, adds the index column")
      ->transform(whole_range(2, 16));
  cmd->add_option("--eps", a->eps, "eps of S_eps (default 0.05)")
      ->check(real_range(0.0, 0.5, true, true));
  cmd->add_flag("--json", a->json, "print JSON instead of CSV");
  // Narrow FOV.
  cmd->add_option("--length", a->length, "length of the line of sight (m)")
      ->check(positive())
      ->excludes(fov);
  // Large FOV.
  cmd->add_option("--bins", a->grid.bins, "angular bins across the FOV (A)")
      ->transform(whole_range(1, core::kMaxBins))
      ->capture_default_str()
      ->needs(fov);
  cmd->add_option("--rings", a->grid.rings, "range rings (R)")
      ->transform(whole_range(1, 100'000'000))
      ->capture_default_str()
      ->needs(fov);
  cmd->add_option("--sectors", a->grid.sectors, "sectors (Ns), dividing the bins")
      ->transform(whole_range(1, core::kMaxSectors))
      ->capture_default_str()
      ->needs(fov);
  cmd->add_option("--k-theta", a->model.k_theta, "relative growth of sigma at the FOV's edge")
      ->check(non_negative())
      ->capture_default_str()
      ->needs(fov);
  cmd->add_option("--k-size", a->model.k_size, "relative growth of sigma for a one-sector obstacle")
      ->check(non_negative())
      ->capture_default_str()
      ->needs(fov);
  CLI::Option* agreement =
      cmd->add_option("--agreement", a->agreement,
                      "instead of the ISM, print the integer kernel's agreement with the "
                      "quantized double ISM over this many random readings and the edge readings")
          ->transform(whole_range(0, 10'000'000))
          ->needs(fov)
          ->excludes(z);
  cmd->add_option("--seed", a->seed, "seed of the random readings of --agreement")
      ->transform(seed_number())
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
  cmd->callback([a] {
    try {
      a->fov_degrees ? run_sectoral_ism(*a) : run_narrow_ism(*a);
    } catch (const std::invalid_argument& e) {
      rethrow_naming_kernel_options(e, ism_flags());
    }
  });
}

}  // namespace intgrid::cli
