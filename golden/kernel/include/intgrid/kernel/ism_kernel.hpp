// The bit-accurate integer model of the sectoral ISM hardware kernel (docs/hardware.md,
// kernel 2): it defines the exact bits the HLS, SystemC and RTL layers must produce.
//
// The kernel runs the ring recursion of intgrid/core/sectoral_ism.hpp in base-2 logarithms
// held as 32-bit fixed-point integers, so that the huge range of 2^-M_r never leaves
// the word: products are additions, the 2^-n priors are integer offsets (the log-domain
// form of a shift), sums take one ROM lookup (log2(1 + 2^-d)), and the last step
// compares the log-odds against constant S_eps thresholds instead of dividing.
// The sensor model enters through ROM tables built here, once per configuration, from
// the double-precision model.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "intgrid/core/sectoral_ism.hpp"
#include "intgrid/core/seps.hpp"

namespace intgrid::kernel {

// The kernel holds at most this many sectors: its class and condition ROMs grow as Ns^3.
inline constexpr int kMaxKernelSectors = 16;

struct IsmKernelFormat {
  int reading_frac_bits = 8;     // the reading z, in cells, with this many fractional bits
  int log_frac_bits = 8;         // every log2 value, in Q.F
  int quad_coef_frac_bits = 16;  // log2(e) / (2 sigma^2), in cells^-2
};

// Everything the hardware holds, in the exact integers it holds them.
struct IsmKernelTables {
  core::SectoralGrid grid;
  IsmKernelFormat format;
  int classes = 0;     // pattern classes (theta(S), |S|) per ring
  int conditions = 0;  // 2 Ns + 1
  int max_index = 0;   // indices saturate at +-max_index
  // |z - d_r| of this many cells or more contributes nothing: past it the density,
  // even times the largest prior ratio, lies far below anything the indices resolve.
  int window_cells = 0;
  std::uint32_t reach = 0;  // readings at or past reach (in reading units) inform no cell

  std::vector<std::uint32_t> quad_coef;  // [(r - 1) * classes + c]
  std::vector<std::int32_t> log_norm;    // [(r - 1) * classes + c]: log2(sigma sqrt(2 pi))
  std::vector<std::int32_t> log_weight;  // [v * classes + c], kLogZero if impossible
  std::vector<std::uint16_t> log_add;    // [d] = round(2^F log2(1 + 2^(-d / 2^F)))
  std::vector<std::int32_t> thresholds;  // [n - 1]: smallest log2-odds (Q.F) of index n

  static constexpr std::int32_t kLogZero = -(std::int32_t{1} << 30);  // log2(0)
};

// Builds the tables. Throws std::invalid_argument if the model, grid or codec is invalid
// or the configuration does not fit the kernel's words (more than kMaxKernelSectors
// sectors, log values past 2^29, a window past 4096 cells).
IsmKernelTables make_ism_kernel(const core::ConeSensorModel& model, const core::SectoralGrid& grid,
                                const core::SepsCodec& codec, const IsmKernelFormat& format = {});

// The kernel's fixed-point reading for z metres: round(z / cell * 2^reading_frac_bits).
// Throws std::invalid_argument for NaN, negative or unrepresentable (>= 2^31 units) z.
std::uint32_t quantize_reading(const IsmKernelTables& kernel, double z);
// The metres a fixed-point reading stands for.
double reading_metres(const IsmKernelTables& kernel, std::uint32_t reading);

// The kernel's arithmetic, one operation each, as the hardware does them.
std::int32_t kernel_log_add(const IsmKernelTables& kernel, std::int32_t a, std::int32_t b);
std::int32_t kernel_log_mul(std::int32_t a, std::int32_t b);
int kernel_index_of_log_odds(const IsmKernelTables& kernel, std::int32_t log_num,
                             std::int32_t log_den);

// The S_eps index of every polar cell for one reading, ring-major like sectoral_ism.
void ism_kernel_indices(const IsmKernelTables& kernel, std::uint32_t reading,
                        std::span<std::int16_t> out);
std::vector<std::int16_t> ism_kernel_indices(const IsmKernelTables& kernel, std::uint32_t reading);

// How the kernel's indices compare with the conservatively quantized double ISM at the
// same readings: cells equal, one step apart, and further apart.
struct KernelAgreement {
  std::size_t readings = 0;
  std::size_t cells = 0;
  std::size_t equal = 0;
  std::size_t one_step = 0;
  std::size_t more = 0;
  int worst_step = 0;
  double equal_share() const { return cells ? double(equal) / double(cells) : 0.0; }
};
KernelAgreement measure_kernel_agreement(const core::ConeSensorModel& model,
                                         const IsmKernelTables& kernel,
                                         const core::SepsCodec& codec,
                                         std::span<const std::uint32_t> readings);

}  // namespace intgrid::kernel
