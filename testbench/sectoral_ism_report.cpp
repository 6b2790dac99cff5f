// sectoral_ism_report [READINGS]: measures the Verilated sectoral ISM RTL and prints one JSON
// line per configuration. All figures are measured in simulation, each run checked against
// golden (exit status 1 if any check fails):
//   setup_cycles     reading accepted -> engine idle again, isolated readings (min/mean/max)
//   latency_cycles   reading accepted -> its first cell valid, isolated, no back-pressure
//   cycles_per_cell  total cycles / cells, readings back to back (no input gaps), with
//                    y_ready always high, and with y_ready random at 50%
//   streaming_latency_mean  accepted -> first cell, back to back (queueing included)
//   verilator_cells_per_second, verilator_cycles_per_second  host speed, no back-pressure
// Readings: uniform over [0, reach), i.e. every one informs some rings (seed fixed).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <random>
#include <vector>

#include "Vsectoral_ism_cone12.h"
#include "Vsectoral_ism_cone16.h"
#include "intgrid/kernel/hardware_configs.hpp"
#include "testbench/sectoral_ism_rtl_bench.hpp"

using namespace intgrid::core;
using namespace intgrid::kernel;

namespace {

using namespace intgrid;
using namespace intgrid::hw;

struct Stats {
  std::uint64_t min = 0, max = 0;
  double mean = 0.0;
};
Stats stats(const std::vector<std::uint64_t>& v) {
  Stats s;
  if (v.empty()) return s;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  s.mean = double(std::accumulate(v.begin(), v.end(), std::uint64_t{0})) / double(v.size());
  return s;
}

template <class Model>
bool report(const char* name, std::size_t count) {
  const IsmKernelTables k = make_ism_hw_kernel(ism_hw_config(name));
  std::mt19937_64 rng(2024);
  std::uniform_int_distribution<std::uint32_t> any(0, k.reach - 1);
  std::vector<std::uint32_t> z(count);
  for (std::uint32_t& x : z) x = any(rng);
  IsmRtlBench<Model> bench(k);
  IsmBenchOptions iso;
  iso.isolated = true;
  iso.ready = 1.0;
  iso.gap = 0.0;
  const IsmBenchResult a = bench.run(z, iso);
  IsmBenchOptions stream = iso;
  stream.isolated = false;
  const IsmBenchResult b = bench.run(z, stream);
  IsmBenchOptions pressed = stream;
  pressed.ready = 0.5;
  pressed.seed = 17;
  const IsmBenchResult c = bench.run(z, pressed);
  const bool ok = a.ok() && b.ok() && c.ok();
  const Stats setup = stats(a.setup_cycles), latency = stats(a.latencies);
  std::printf(
      "{\"kernel\": \"sectoral_ism\", \"config\": \"%s\", \"readings\": %zu, "
      "\"cells_per_reading\": %zu, \"checked\": %s, "
      "\"setup_cycles\": {\"min\": %llu, \"mean\": %.1f, \"max\": %llu}, "
      "\"latency_cycles\": {\"min\": %llu, \"mean\": %.1f, \"max\": %llu}, "
      "\"cycles_per_cell\": {\"no_backpressure\": %.3f, \"backpressure_50\": %.3f}, "
      "\"streaming_latency_mean\": {\"no_backpressure\": %.1f, \"backpressure_50\": %.1f}, "
      "\"verilator_cells_per_second\": %.0f, \"verilator_cycles_per_second\": %.0f}\n",
      name, count, k.grid.cells(), ok ? "true" : "false",
      static_cast<unsigned long long>(setup.min), setup.mean,
      static_cast<unsigned long long>(setup.max), static_cast<unsigned long long>(latency.min),
      latency.mean, static_cast<unsigned long long>(latency.max),
      double(b.cycles) / double(b.cells), double(c.cycles) / double(c.cells),
      stats(b.latencies).mean, stats(c.latencies).mean, double(b.cells) / b.host_seconds,
      double(b.cycles) / b.host_seconds);
  if (!ok)
    std::fprintf(stderr, "%s\n%s\n%s\n", a.summary().c_str(), b.summary().c_str(),
                 c.summary().c_str());
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t count = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 1000;
  bool ok = report<Vsectoral_ism_cone16>("cone16", count);
  ok = report<Vsectoral_ism_cone12>("cone12", count) && ok;
  return ok ? 0 : 1;
}
