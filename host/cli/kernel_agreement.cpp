#include "cli/kernel_agreement.hpp"

#include <cstdio>
#include <random>

#include "intgrid/figures/polar_render.hpp"

namespace intgrid::cli {
namespace {

double share(std::size_t part, std::size_t whole) {
  return whole ? double(part) / double(whole) : 0.0;
}

}  // namespace

std::vector<std::uint32_t> kernel_agreement_readings(const kernel::IsmKernelTables& kernel,
                                                     std::size_t drawn, std::uint64_t seed) {
  const core::SectoralGrid& grid = kernel.grid;
  std::mt19937_64 random(seed);
  std::uniform_int_distribution<std::uint32_t> uniform(
      0, kernel::quantize_reading(kernel, grid.ring_distance(grid.rings + 1)));
  std::vector<std::uint32_t> readings;
  readings.reserve(drawn + static_cast<std::size_t>(grid.rings) + 2);
  for (std::size_t i = 0; i < drawn; ++i) readings.push_back(uniform(random));
  readings.push_back(0);
  for (int ring = 1; ring <= grid.rings; ++ring)
    readings.push_back(kernel::quantize_reading(kernel, grid.ring_distance(ring)));
  readings.push_back(kernel::quantize_reading(kernel, (grid.rings + 0.5) * grid.cell));
  return readings;
}

KernelAgreementReport kernel_agreement_report(const core::ConeSensorModel& model,
                                              const core::SectoralGrid& grid,
                                              const core::SepsCodec& codec, std::size_t drawn,
                                              std::uint64_t seed) {
  const kernel::IsmKernelTables kernel = kernel::make_ism_kernel(model, grid, codec);
  const std::vector<std::uint32_t> readings = kernel_agreement_readings(kernel, drawn, seed);
  return {grid,  codec.bits(), codec.eps(),
          drawn, seed,         kernel::measure_kernel_agreement(model, kernel, codec, readings)};
}

nlohmann::json kernel_agreement_json(const KernelAgreementReport& r) {
  const kernel::KernelAgreement& a = r.agreement;
  return {{"grid", figures::polar_grid_json(r.grid)},
          {"bits", r.bits},
          {"eps", r.eps},
          {"seed", r.seed},
          {"readings", a.readings},
          {"readings_drawn", r.drawn},
          {"readings_at_edges", a.readings - r.drawn},
          {"cells", a.cells},
          {"equal", a.equal},
          {"one_step", a.one_step},
          {"further", a.more},
          {"equal_share", a.equal_share()},
          {"one_step_share", share(a.one_step, a.cells)},
          {"worst_step", a.worst_step}};
}

void print_kernel_agreement(const KernelAgreementReport& r) {
  const kernel::KernelAgreement& a = r.agreement;
  std::printf(
      "integer ISM kernel against the conservatively quantized double ISM (FOV %g deg, R = %d, "
      "A = %d, Ns = %d, cell %g m, %d-bit S_eps, eps %g):\n",
      figures::degrees(r.grid.fov), r.grid.rings, r.grid.bins, r.grid.sectors, r.grid.cell, r.bits,
      r.eps);
  std::printf("readings: %zu (%zu drawn with seed %llu, %zu at the edges)\n", a.readings, r.drawn,
              static_cast<unsigned long long>(r.seed), a.readings - r.drawn);
  std::printf("cells: %zu\n", a.cells);
  std::printf("equal: %.4f%%\n", 100.0 * a.equal_share());
  std::printf("one step off: %.4f%%\n", 100.0 * share(a.one_step, a.cells));
  std::printf("further off: %zu\n", a.more);
  std::printf("worst step: %d\n", a.worst_step);
}

}  // namespace intgrid::cli
