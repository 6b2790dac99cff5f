// The Cortex-M3 firmware: the instruction counter's calibration, then every operation of the
// workload in both arithmetics, one line each, parsed by embedded_check on the host.
#include <cstdio>

#include "testbench/cortex_m3/platform.hpp"
#include "testbench/cortex_m3/workload.hpp"

namespace {
// newlib's printf here knows %llu but neither %zu nor <cinttypes>' macros.
unsigned long long ull(unsigned long long v) {
  return v;
}
}  // namespace

int main() {
  using namespace intgrid;
  for (const unsigned iterations : {1000u, 1234567u}) {
    const cortex_m3::Calibration c = cortex_m3::calibrate(iterations);
    std::printf("calibration iterations=%u expected=%llu measured=%llu resolution=%u\n", iterations,
                ull(c.expected), ull(c.measured), unsigned{cortex_m3::instructions_per_tick});
  }
  embedded::Workload workload;
  for (std::size_t i = 0; i < embedded::kOperations; ++i)
    for (const bool integer : {true, false}) {
      const auto operation = static_cast<embedded::Operation>(i);
      const cortex_m3::RegionCost cost =
          cortex_m3::measure([&] { workload.run(operation, integer); });
      const embedded::Result r = workload.result(operation, integer);
      std::printf(
          "operation name=%s arithmetic=%s cells=%llu instructions=%llu allocations=%llu "
          "digest=%016llx\n",
          embedded::name_of(operation), integer ? "int" : "double", ull(r.cells),
          ull(cost.instructions), ull(cost.allocations), ull(r.digest));
    }
  std::printf("heap bytes=%llu\n", ull(cortex_m3::heap_bytes()));
  std::printf("done\n");
  return 0;
}
