// How the integer ISM kernel agrees with the conservatively quantized double ISM over a
// reproducible set of readings: for `intgrid ism --agreement` and the demo.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "intgrid/kernel/ism_kernel.hpp"

namespace intgrid::cli {

// `drawn` fixed-point readings uniform over 0 .. (rings + 1) cells (std::mt19937_64 seeded
// with seed), then the edge readings: 0, each ring exactly, half a cell past the last ring.
std::vector<std::uint32_t> kernel_agreement_readings(const kernel::IsmKernelTables& kernel,
                                                     std::size_t drawn, std::uint64_t seed);

struct KernelAgreementReport {
  core::SectoralGrid grid;
  int bits = 0;
  double eps = 0.0;
  std::size_t drawn = 0;
  std::uint64_t seed = 0;
  kernel::KernelAgreement agreement;
};

// Builds the kernel (throwing std::invalid_argument as make_ism_kernel does) and measures its
// agreement over kernel_agreement_readings.
KernelAgreementReport kernel_agreement_report(const core::ConeSensorModel& model,
                                              const core::SectoralGrid& grid,
                                              const core::SepsCodec& codec, std::size_t drawn,
                                              std::uint64_t seed);

nlohmann::json kernel_agreement_json(const KernelAgreementReport& report);
// One line per figure, for people.
void print_kernel_agreement(const KernelAgreementReport& report);

}  // namespace intgrid::cli
