#include "intgrid/kernel/ism_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "intgrid/core/failure.hpp"

namespace intgrid::kernel {
namespace {

using Log = std::int32_t;
constexpr Log kLogZero = IsmKernelTables::kLogZero;
// Every finite log value the kernel forms stays within +-2^29, so sums of two never
// overflow the 32-bit word and never reach the zero sentinel.
constexpr double kLogRange = double(1 << 29);

void require(bool ok, const std::string& message) {
  if (!ok) core::fail<std::invalid_argument>("ISM kernel: " + message);
}

// The integer arithmetic of the kernel, for the shared ring recursion.
struct KernelLogArith {
  const IsmKernelTables& kernel;
  std::uint32_t reading;

  Log zero() const { return kLogZero; }
  Log add(Log a, Log b) const { return kernel_log_add(kernel, a, b); }
  Log mul(Log a, Log b) const { return kernel_log_mul(a, b); }
  Log log_density(int ring, std::size_t c) const {
    const IsmKernelFormat& f = kernel.format;
    const std::int64_t error = std::int64_t{reading} - (std::int64_t{ring} << f.reading_frac_bits);
    const std::uint64_t magnitude = static_cast<std::uint64_t>(error < 0 ? -error : error);
    if (magnitude >= std::uint64_t(kernel.window_cells) << f.reading_frac_bits) return kLogZero;
    const std::size_t at = static_cast<std::size_t>(ring - 1) * std::size_t(kernel.classes) + c;
    const int shift = 2 * f.reading_frac_bits + f.quad_coef_frac_bits - f.log_frac_bits;
    const std::uint64_t quad = (magnitude * magnitude * kernel.quad_coef[at]) >> shift;
    return static_cast<Log>(-static_cast<std::int64_t>(quad) - kernel.log_norm[at]);
  }
  Log log_weight(int v, std::size_t c) const {
    return kernel.log_weight[static_cast<std::size_t>(v) * std::size_t(kernel.classes) + c];
  }
  Log ring_prior(int ring) const {
    return static_cast<Log>(
        -((std::int64_t{ring} - 1) * kernel.grid.bins << kernel.format.log_frac_bits));
  }
  Log two() const { return Log{1} << kernel.format.log_frac_bits; }
  int output(Log log_num, Log log_den) const {
    return kernel_index_of_log_odds(kernel, log_num, log_den);
  }
};

Log round_log(double value_q) {
  require(std::abs(value_q) < kLogRange, "a log2 table value leaves the 2^29 range");
  return static_cast<Log>(std::lround(value_q));
}

}  // namespace

IsmKernelTables make_ism_kernel(const core::ConeSensorModel& model, const core::SectoralGrid& grid,
                                const core::SepsCodec& codec, const IsmKernelFormat& format) {
  core::check_model(model);
  core::check_sectoral_grid(grid);
  require(grid.sectors <= kMaxKernelSectors, "sectors (Ns = " + std::to_string(grid.sectors) +
                                                 ") exceed the kernel's " +
                                                 std::to_string(kMaxKernelSectors));
  require(format.reading_frac_bits >= 0 && format.reading_frac_bits <= 12,
          "reading fraction bits must be 0..12");
  require(format.log_frac_bits >= 2 && format.log_frac_bits <= 12,
          "log fraction bits must be 2..12");
  require(format.quad_coef_frac_bits >= 4 && format.quad_coef_frac_bits <= 24,
          "quadratic coefficient fraction bits must be 4..24");

  IsmKernelTables k;
  k.grid = grid;
  k.format = format;
  k.max_index = codec.max_index();
  const core::PatternClasses pc = core::pattern_classes(grid);
  k.classes = static_cast<int>(pc.classes());
  k.conditions = pc.conditions();
  const double one = std::exp2(format.log_frac_bits);  // 1.0 in Q.F

  require(double(grid.rings) * grid.bins * one < kLogRange,
          "rings x bins x 2^F leaves the 2^29 range of the log words");
  double sigma_min = std::numeric_limits<double>::infinity(), sigma_max = 0.0;
  for (int r = 1; r <= grid.rings; ++r)
    for (std::size_t c = 0; c < pc.classes(); ++c) {
      const double sigma = model.sigma(grid.ring_distance(r), pc.theta[c], pc.size[c]);
      sigma_min = std::min(sigma_min, sigma);
      sigma_max = std::max(sigma_max, sigma);
      const double sigma_cells = sigma / grid.cell;
      const double coef = std::round(std::numbers::log2e / (2.0 * sigma_cells * sigma_cells) *
                                     std::exp2(format.quad_coef_frac_bits));
      require(coef >= 1.0 && coef < 4294967296.0,
              "sigma is out of the quadratic coefficient's 32-bit range for this cell size");
      k.quad_coef.push_back(static_cast<std::uint32_t>(coef));
      k.log_norm.push_back(round_log(std::log2(sigma * std::sqrt(2.0 * std::numbers::pi)) * one));
    }
  for (const double w : pc.log_weight)
    k.log_weight.push_back(std::isinf(w) ? kLogZero : round_log(w * std::numbers::log2e * one));
  for (int d = 0;; ++d) {
    const auto phi = std::lround(one * std::log2(1.0 + std::exp2(-d / one)));
    if (phi == 0) break;
    k.log_add.push_back(static_cast<std::uint16_t>(phi));
  }
  const double lambda_bits = codec.lambda() * std::numbers::log2e;
  for (int n = 1; n <= k.max_index; ++n)
    k.thresholds.push_back(round_log(std::ceil(n * lambda_bits * one)));

  // The window: a ring |e| cells from z, however large its prior (2^A a ring nearer),
  // must lie below the least term any index resolves, with room for the spread of
  // normalizations and weights.
  const double bits_per_cell2_min =
      std::numbers::log2e / (2.0 * std::pow(sigma_max / grid.cell, 2.0));
  const double bits_per_cell2_max =
      std::numbers::log2e / (2.0 * std::pow(sigma_min / grid.cell, 2.0));
  const double margin = k.max_index * lambda_bits + 32.0 + std::log2(sigma_max / sigma_min) +
                        0.25 * bits_per_cell2_max + grid.bins;
  int window = 1;
  while (bits_per_cell2_min * window * window - double(grid.bins) * (window + 1) < margin ||
         window < grid.bins / (2.0 * bits_per_cell2_min))
    ++window;
  require(window <= 4096, "sigma is too wide for the cell size: the window passes 4096 cells");
  k.window_cells = window;
  const double window_units = std::ldexp(double(window), format.reading_frac_bits);
  require(window_units * window_units *
                  double(*std::max_element(k.quad_coef.begin(), k.quad_coef.end())) <
              std::ldexp(1.0, 63),
          "the quadratic term overflows 64 bits inside the window");
  require(bits_per_cell2_max * window * window * one < kLogRange,
          "the quadratic term leaves the 2^29 range inside the window");
  const double reach = std::ldexp(double(grid.rings) + window, format.reading_frac_bits);
  require(reach < 2147483648.0, "rings + window do not fit a 31-bit reading");
  k.reach = static_cast<std::uint32_t>(reach);
  return k;
}

std::uint32_t quantize_reading(const IsmKernelTables& kernel, double z) {
  if (std::isnan(z)) core::fail<std::invalid_argument>("reading z is NaN");
  if (z < 0.0) core::fail<std::invalid_argument>("reading z is negative");
  const double units =
      std::round(std::ldexp(z / kernel.grid.cell, kernel.format.reading_frac_bits));
  if (!(units < 2147483648.0))
    core::fail<std::invalid_argument>("reading z does not fit the kernel's 31-bit reading");
  return static_cast<std::uint32_t>(units);
}

double reading_metres(const IsmKernelTables& kernel, std::uint32_t reading) {
  return std::ldexp(double(reading), -kernel.format.reading_frac_bits) * kernel.grid.cell;
}

std::int32_t kernel_log_add(const IsmKernelTables& kernel, std::int32_t a, std::int32_t b) {
  if (a == kLogZero) return b;
  if (b == kLogZero) return a;
  const Log hi = std::max(a, b);
  const auto d = static_cast<std::size_t>(hi - std::min(a, b));
  return d < kernel.log_add.size() ? hi + kernel.log_add[d] : hi;
}

std::int32_t kernel_log_mul(std::int32_t a, std::int32_t b) {
  if (a == kLogZero || b == kLogZero) return kLogZero;
  const std::int64_t product = std::int64_t{a} + b;
  return product <= kLogZero ? kLogZero : static_cast<Log>(product);
}

int kernel_index_of_log_odds(const IsmKernelTables& kernel, std::int32_t log_num,
                             std::int32_t log_den) {
  if (log_num == kLogZero && log_den == kLogZero) return 0;
  if (log_num == kLogZero) return -kernel.max_index;
  if (log_den == kLogZero) return kernel.max_index;
  const std::int64_t odds = std::int64_t{log_num} - log_den;
  const std::int64_t magnitude = odds < 0 ? -odds : odds;
  // Index n when the odds pass threshold n: the count of thresholds at or below them.
  const auto n = static_cast<int>(
      std::upper_bound(kernel.thresholds.begin(), kernel.thresholds.end(), magnitude) -
      kernel.thresholds.begin());
  return odds < 0 ? -n : n;
}

void ism_kernel_indices(const IsmKernelTables& kernel, std::uint32_t reading,
                        std::span<std::int16_t> out) {
  const core::SectoralGrid& grid = kernel.grid;
  if (out.size() != grid.cells())
    core::fail<std::invalid_argument>("ism_kernel_indices: output size differs from rings x bins");
  const KernelLogArith arith{kernel, reading};
  const auto per_sector = static_cast<std::size_t>(grid.bins_per_sector());
  core::sectoral_ism_rings(arith, grid.rings, grid.sectors, std::size_t(kernel.classes),
                           [&](int ring, int sector, int index) {
                             const auto first = static_cast<std::size_t>(ring - 1) *
                                                    static_cast<std::size_t>(grid.bins) +
                                                static_cast<std::size_t>(sector) * per_sector;
                             std::fill_n(out.begin() + static_cast<std::ptrdiff_t>(first),
                                         per_sector, static_cast<std::int16_t>(index));
                           });
}

std::vector<std::int16_t> ism_kernel_indices(const IsmKernelTables& kernel, std::uint32_t reading) {
  std::vector<std::int16_t> out(kernel.grid.cells());
  ism_kernel_indices(kernel, reading, out);
  return out;
}

KernelAgreement measure_kernel_agreement(const core::ConeSensorModel& model,
                                         const IsmKernelTables& kernel,
                                         const core::SepsCodec& codec,
                                         std::span<const std::uint32_t> readings) {
  KernelAgreement a;
  std::vector<double> exact(kernel.grid.cells());
  std::vector<std::int16_t> bits(kernel.grid.cells());
  for (const std::uint32_t reading : readings) {
    core::sectoral_ism(model, kernel.grid, reading_metres(kernel, reading), exact);
    ism_kernel_indices(kernel, reading, bits);
    ++a.readings;
    for (std::size_t i = 0; i < exact.size(); ++i) {
      const int step = std::abs(bits[i] - codec.quantize_conservative(exact[i]));
      ++a.cells;
      if (step == 0)
        ++a.equal;
      else if (step == 1)
        ++a.one_step;
      else
        ++a.more;
      a.worst_step = std::max(a.worst_step, step);
    }
  }
  return a;
}

}  // namespace intgrid::kernel
