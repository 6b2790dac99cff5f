// Benchmarks of the golden model: the exact narrow ISM, grid fusion (S_eps
// index addition against Bayesian fusion of doubles) and whole-log scan
// insertion on the bundled Malaga log. Run: intgrid_bench (see bench/README.md).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/mapping.hpp"
#include "intgrid/core/narrow_ism.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/core/scan_insertion.hpp"
#include "intgrid/core/sectoral_ism.hpp"
#include "intgrid/core/sensor_model.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/core/ugamma.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/kernel/ism_kernel.hpp"
#include "intgrid/localization/global_localization.hpp"
#include "intgrid/simulation/simulator.hpp"
#include "scan_insertion.hpp"

using namespace intgrid::core;
using namespace intgrid::kernel;
using namespace intgrid::localization;
using namespace intgrid::simulation;
using namespace intgrid::io;

namespace {

using namespace intgrid;

// ---------------------------------------------------------------------------
// 1. The narrow ISM over N line-of-sight cells, reading in the middle of the line.

void BM_NarrowIsm(benchmark::State& state) {
  const auto cells = static_cast<std::size_t>(state.range(0));
  const GaussianBeamModel model{0.03, 0.0};
  constexpr double kCell = 0.05;
  const double z = static_cast<double>(cells) * kCell * 0.5;
  std::vector<double> out(cells);
  for (auto _ : state) {
    narrow_ism(model, z, kCell, std::span<double>(out));
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_NarrowIsm)->RangeMultiplier(10)->Range(1000, 1000000)->Complexity(benchmark::oN);

// ---------------------------------------------------------------------------
// 1b. The sectoral ISM over N = R x A polar cells for a fixed number of sectors (Ns = 4):
// more rings (A = 16), or more bins per ring (R = 64); the reading in the middle. sigma
// stays 2 cm (k_d = 0): a million cells of 16 bins reach 3 km, where a growing sigma
// would describe no real cone sensor.
const ConeSensorModel kBenchCone{0.02, 0.0, 0.5, 0.5};

SectoralGrid sectoral_grid(int rings, int bins) {
  return SectoralGrid{0.5235987755982988, rings, bins, 4, 0.05};
}

void run_sectoral_ism(benchmark::State& state, const SectoralGrid& grid) {
  const double z = 0.5 * grid.rings * grid.cell + 0.013;
  std::vector<double> out(grid.cells());
  for (auto _ : state) {
    sectoral_ism(kBenchCone, grid, z, out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(grid.cells()));
  state.SetComplexityN(static_cast<std::int64_t>(grid.cells()));
}
void BM_SectoralIsm_Rings(benchmark::State& state) {
  run_sectoral_ism(state, sectoral_grid(static_cast<int>(state.range(0)) / 16, 16));
}
BENCHMARK(BM_SectoralIsm_Rings)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Complexity(benchmark::oN);
void BM_SectoralIsm_Bins(benchmark::State& state) {
  run_sectoral_ism(state, sectoral_grid(64, static_cast<int>(state.range(0)) / 64));
}
BENCHMARK(BM_SectoralIsm_Bins)
    ->Arg(64 * 16)
    ->Arg(64 * 64)
    ->Arg(64 * 256)
    ->Arg(64 * 1000)
    ->Complexity(benchmark::o1);  // the per-ring work depends on Ns only

// The bit-accurate integer kernel model on the same grids as the ring sweep.
void BM_IsmKernel_Rings(benchmark::State& state) {
  const SectoralGrid grid = sectoral_grid(static_cast<int>(state.range(0)) / 16, 16);
  const IsmKernelTables kernel = make_ism_kernel(kBenchCone, grid, SepsCodec(8, 0.05));
  const std::uint32_t reading = quantize_reading(kernel, 0.5 * grid.rings * grid.cell + 0.013);
  std::vector<std::int16_t> out(grid.cells());
  for (auto _ : state) {
    ism_kernel_indices(kernel, reading, out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_IsmKernel_Rings)->RangeMultiplier(10)->Range(1000, 1000000)->Complexity(benchmark::oN);

// ---------------------------------------------------------------------------
// 2. Fusing two 4096 x 4096 grids: int8 S_eps indices against double probabilities.

constexpr std::size_t kFuseSide = 4096;
constexpr std::size_t kFuseCells = kFuseSide * kFuseSide;
constexpr int kFuseMaxIndex = 127;

// Two grids of random indices in [-127, 127] from a fixed seed, built once.
struct IndexGrids {
  std::vector<std::int8_t> a, b;
};
const IndexGrids& index_grids() {
  static const IndexGrids grids = [] {
    std::mt19937 rng(20261125u);
    std::uniform_int_distribution<int> index(-kFuseMaxIndex, kFuseMaxIndex);
    IndexGrids g;
    g.a.resize(kFuseCells);
    g.b.resize(kFuseCells);
    for (std::int8_t& n : g.a) n = static_cast<std::int8_t>(index(rng));
    for (std::int8_t& n : g.b) n = static_cast<std::int8_t>(index(rng));
    return g;
  }();
  return grids;
}

// The same grids as the probabilities p_n of SepsCodec(8, 0.05).
struct ProbabilityGrids {
  std::vector<double> a, b;
};
const ProbabilityGrids& probability_grids() {
  static const ProbabilityGrids grids = [] {
    const SepsCodec codec(8, 0.05);
    const IndexGrids& indices = index_grids();
    ProbabilityGrids g;
    g.a.resize(kFuseCells);
    g.b.resize(kFuseCells);
    for (std::size_t i = 0; i < kFuseCells; ++i) {
      g.a[i] = codec.probability(indices.a[i]);
      g.b[i] = codec.probability(indices.b[i]);
    }
    return g;
  }();
  return grids;
}

// Times fuse(a, b, out) over the two index grids into a third: two grids read, one written.
template <class Fuse>
void time_int8_grids(benchmark::State& state, Fuse fuse) {
  const IndexGrids& grids = index_grids();
  std::vector<std::int8_t> out(kFuseCells);
  for (auto _ : state) {
    fuse(grids.a, grids.b, out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  const auto cells = static_cast<std::int64_t>(kFuseCells);
  state.SetItemsProcessed(state.iterations() * cells);
  state.SetBytesProcessed(state.iterations() * cells * 3 *
                          static_cast<std::int64_t>(sizeof(std::int8_t)));
}

void BM_FuseGrids_Int8Indices(benchmark::State& state) {
  time_int8_grids(state, [](const auto& a, const auto& b, std::vector<std::int8_t>& out) {
    fuse_indices<std::int8_t>(a, b, out, kFuseMaxIndex);
  });
}
BENCHMARK(BM_FuseGrids_Int8Indices)->Unit(benchmark::kMillisecond);

// The memory reference of int8 fusion: the same bytes moved (two grids read, one written) with
// an element-wise OR that the compiler vectorizes fully, so that its time is memory's; fusion
// at this time is at the machine's memory bandwidth (issue: fusion within 80% of it).
void BM_FuseGrids_MemoryReference(benchmark::State& state) {
  time_int8_grids(state, [](const auto& a, const auto& b, std::vector<std::int8_t>& out) {
    for (std::size_t i = 0; i < kFuseCells; ++i) out[i] = static_cast<std::int8_t>(a[i] | b[i]);
  });
}
BENCHMARK(BM_FuseGrids_MemoryReference)->Unit(benchmark::kMillisecond);

void BM_FuseGrids_DoubleBayes(benchmark::State& state) {
  const ProbabilityGrids& grids = probability_grids();
  std::vector<double> out(kFuseCells);
  for (auto _ : state) {
    for (std::size_t i = 0; i < kFuseCells; ++i)
      out[i] = fuse_probabilities(grids.a[i], grids.b[i]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  const auto cells = static_cast<std::int64_t>(kFuseCells);
  state.SetItemsProcessed(state.iterations() * cells);
  state.SetBytesProcessed(state.iterations() * cells * 3 *
                          static_cast<std::int64_t>(sizeof(double)));
}
BENCHMARK(BM_FuseGrids_DoubleBayes)->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------------------
// 3. Reading the bundled log; inserting every scan of the bundled reference log into a 5 cm grid
// (bench/scan_insertion.hpp).

// Reading the bundled 225-scan log from disk (items = scans; the file stays in the page cache).
void BM_ReadLog(benchmark::State& state) {
  std::size_t scans = 0;
  for (auto _ : state) {
    const Log log = read_log(INTGRID_DATA_DIR "/malaga_telecom_loop.log");
    scans += log.scans.size();
    benchmark::DoNotOptimize(log.scans.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(scans));
}
BENCHMARK(BM_ReadLog)->Unit(benchmark::kMillisecond);

using bench::BM_ScanInsertion_DoubleBayes;
using bench::BM_ScanInsertion_Int8;
BENCHMARK(BM_ScanInsertion_Int8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScanInsertion_DoubleBayes)->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------------------
// 4. U_gamma (docs/algorithms.md 5, default 16 bits, 16 steps per halving): sums and fusions of
// 4096 probabilities as integer exponents, against the same work in double.

constexpr std::size_t kUGammaTerms = 4096;

// 4096 random indices in [0, 160]: probabilities from 1 down to 2^-10 (fixed seed).
std::vector<UIndex> ugamma_terms(const UGamma& u, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<UIndex> index(0, 10 * u.steps_per_halving());
  std::vector<UIndex> terms(kUGammaTerms);
  for (UIndex& t : terms) t = index(rng);
  return terms;
}

// A chain of 4095 Zech additions (table lookups), as a normalization would sum.
void BM_UGamma_Add(benchmark::State& state) {
  const UGamma u;
  const std::vector<UIndex> terms = ugamma_terms(u, 41);
  for (auto _ : state) {
    UIndex total = u.zero();
    for (UIndex t : terms) total = u.add(total, t);
    benchmark::DoNotOptimize(total);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kUGammaTerms));
}
BENCHMARK(BM_UGamma_Add);

// The same sum pairwise (ceil(log2 n) roundings on any path instead of n - 1), in a scratch copy.
void BM_UGamma_AddPairwise(benchmark::State& state) {
  const UGamma u;
  const std::vector<UIndex> terms = ugamma_terms(u, 41);
  std::vector<UIndex> scratch(terms.size());
  for (auto _ : state) {
    std::copy(terms.begin(), terms.end(), scratch.begin());
    for (std::size_t n = scratch.size(); n > 1; n = (n + 1) / 2) {
      for (std::size_t k = 0; k < n / 2; ++k)
        scratch[k] = u.add(scratch[2 * k], scratch[2 * k + 1]);
      if (n % 2 == 1) scratch[n / 2] = scratch[n - 1];
    }
    benchmark::DoNotOptimize(scratch.front());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kUGammaTerms));
}
BENCHMARK(BM_UGamma_AddPairwise);

// Reference: the same sum in double as a user would write it over natural logs (log-sum-exp,
// one exp and one log1p per term) ...
void BM_Double_AddLogs(benchmark::State& state) {
  const UGamma u;
  std::vector<double> logs;
  for (UIndex t : ugamma_terms(u, 41)) logs.push_back(u.to_log(t));
  for (auto _ : state) {
    double total = logs.front();
    for (std::size_t k = 1; k < logs.size(); ++k) {
      const double hi = std::max(total, logs[k]), lo = std::min(total, logs[k]);
      total = hi + std::log1p(std::exp(lo - hi));
    }
    benchmark::DoNotOptimize(total);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kUGammaTerms));
}
BENCHMARK(BM_Double_AddLogs);

// ... or over the probabilities themselves (a plain sum, one dependent add per term).
void BM_Double_AddProbabilities(benchmark::State& state) {
  const UGamma u;
  std::vector<double> probabilities;
  for (UIndex t : ugamma_terms(u, 41)) probabilities.push_back(u.to_probability(t));
  for (auto _ : state) {
    double total = 0.0;
    for (double p : probabilities) total += p;
    benchmark::DoNotOptimize(total);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kUGammaTerms));
}
BENCHMARK(BM_Double_AddProbabilities);

// 4096 independent Bayesian fusions of two probabilities in (0.01, 0.99): two Phi_minus and
// one Phi_plus lookups each.
struct FusionPairs {
  std::vector<double> p, q;
  std::vector<UIndex> i, j;
};

FusionPairs fusion_pairs(const UGamma& u) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> unit(0.01, 0.99);
  FusionPairs pairs;
  for (std::size_t k = 0; k < kUGammaTerms; ++k) {
    pairs.i.push_back(u.from_probability(unit(rng)));
    pairs.j.push_back(u.from_probability(unit(rng)));
    pairs.p.push_back(u.to_probability(pairs.i.back()));
    pairs.q.push_back(u.to_probability(pairs.j.back()));
  }
  return pairs;
}

void BM_UGamma_Fuse(benchmark::State& state) {
  const UGamma u;
  const FusionPairs pairs = fusion_pairs(u);
  std::vector<UIndex> out(kUGammaTerms);
  for (auto _ : state) {
    for (std::size_t k = 0; k < kUGammaTerms; ++k) out[k] = u.fuse(pairs.i[k], pairs.j[k]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kUGammaTerms));
}
BENCHMARK(BM_UGamma_Fuse);

// Reference: p q / (p q + (1 - p)(1 - q)) in double on the same probabilities.
void BM_Double_Fuse(benchmark::State& state) {
  const UGamma u;
  const FusionPairs pairs = fusion_pairs(u);
  std::vector<double> out(kUGammaTerms);
  for (auto _ : state) {
    for (std::size_t k = 0; k < kUGammaTerms; ++k) {
      const double p = pairs.p[k], q = pairs.q[k];
      out[k] = p * q / (p * q + (1.0 - p) * (1.0 - q));
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kUGammaTerms));
}
BENCHMARK(BM_Double_Fuse);

// ---------------------------------------------------------------------------
// Global localization (docs/algorithms.md 7): the time of one reading on pose grids of N =
// 10^4..10^7 cells (0.2 m x 64 headings over square rooms of growing side, 10 cm map cells, an
// outer wall and random 0.4-1.2 m boxes covering about 8% of the floor, fixed seed), for the pose
// grid (claims table + dense form, integer), its walk form, and Markov localization (Gaussian beam
// model, double, one exp per candidate and a normalization). 60 readings simulated from one free
// pose (LiDAR all round, 8 m, 3 cm noise), used in turn. Markov's belief restarts from uniform
// every 8 readings and the pose grid's sum every 4096 (outside the timing), so no denormals and no
// overflow.

struct GlobalLocBench {
  std::unique_ptr<LocalizationMap> map;
  std::vector<RangeReading> readings;
};

const GlobalLocBench& global_loc_bench(std::int64_t pose_cells) {
  static std::map<std::int64_t, GlobalLocBench> cache;
  auto it = cache.find(pose_cells);
  if (it != cache.end()) return it->second;
  constexpr double kPoseRes = 0.2, kCell = 0.1;
  constexpr int kHeadings = 64;
  const int side = static_cast<int>(std::lround(std::sqrt(double(pose_cells) / kHeadings)));
  const int cells = 2 * side;  // map cells a side
  ProbabilityGrid world(GridGeometry{cells, cells, kCell, 0.0, 0.0}, 0.0);
  for (int k = 0; k < cells; ++k) {
    world.at(k, 0) = world.at(k, cells - 1) = 1.0;
    world.at(0, k) = world.at(cells - 1, k) = 1.0;
  }
  SimRandom random(17);
  const double area = double(cells) * double(cells);
  for (double covered = 0.0; covered < 0.08 * area;) {
    const int w = 4 + static_cast<int>(random.below(9)), h = 4 + static_cast<int>(random.below(9));
    const int x0 = static_cast<int>(random.below(std::uint64_t(std::max(1, cells - w))));
    const int y0 = static_cast<int>(random.below(std::uint64_t(std::max(1, cells - h))));
    for (int y = y0; y < std::min(cells, y0 + h); ++y)
      for (int x = x0; x < std::min(cells, x0 + w); ++x) world.at(x, y) = 1.0;
    covered += w * h;
  }
  GlobalLocConfig config;
  config.pose_res = kPoseRes;
  config.headings = kHeadings;
  config.sensor.max_range = 8.0;
  GlobalLocBench b;
  b.map = std::make_unique<LocalizationMap>(world, 0.65, 0.196, config);
  // A free pose near the middle.
  int i = b.map->width() / 2, j = b.map->height() / 2;
  while (!b.map->is_candidate(i, j)) i = (i + 1) % b.map->width();
  const Pose2 truth = b.map->pose_of(i, j, 0);
  const Scan scan = simulate_scan(world, lidar_sensor(60, 2.0 * std::numbers::pi, 8.0),
                                  RangeNoiseConfig{0.03, 0.0, 0.0}, {truth.x, truth.y, 0.3}, 5);
  b.readings = readings_of(scan, 0, config.sensor.max_range);
  return cache.emplace(pose_cells, std::move(b)).first->second;
}

void report_global_loc(benchmark::State& state, const GlobalLocBench& b) {
  state.counters["pose_cells"] = static_cast<double>(b.map->pose_cells());
  state.counters["candidates"] = static_cast<double>(b.map->candidate_cells());
  state.SetItemsProcessed(state.iterations());  // readings
  state.SetComplexityN(static_cast<std::int64_t>(b.map->pose_cells()));
}

// One form of the pose occupancy grid (dense or walk) adding one reading's claims.
using PoseGridForm = void (LocalizationMap::*)(const ReadingClaims&, std::span<std::int32_t>) const;

void BM_GlobalLoc_PoseGrid(benchmark::State& state, PoseGridForm form) {
  const GlobalLocBench& b = global_loc_bench(state.range(0));
  std::vector<std::int32_t> pog(b.map->pose_cells(), 0);
  std::size_t n = 0;
  for (auto _ : state) {
    if (n % 4096 == 4095) {
      state.PauseTiming();
      std::fill(pog.begin(), pog.end(), 0);
      state.ResumeTiming();
    }
    ((*b.map).*form)(b.map->claims(b.readings[n++ % b.readings.size()]), pog);
    benchmark::DoNotOptimize(pog.data());
    benchmark::ClobberMemory();
  }
  report_global_loc(state, b);
}
BENCHMARK_CAPTURE(BM_GlobalLoc_PoseGrid, dense, &LocalizationMap::add_reading_dense<std::int32_t>)
    ->RangeMultiplier(10)
    ->Range(10000, 10000000)
    ->Unit(benchmark::kMicrosecond)
    ->Complexity(benchmark::oN);
BENCHMARK_CAPTURE(BM_GlobalLoc_PoseGrid, walk, &LocalizationMap::add_reading_walk)
    ->RangeMultiplier(10)
    ->Range(10000, 10000000)
    ->Unit(benchmark::kMicrosecond)
    ->Complexity(benchmark::oN);

void BM_GlobalLoc_Markov(benchmark::State& state) {
  const GlobalLocBench& b = global_loc_bench(state.range(0));
  auto markov = std::make_unique<MarkovLocalization>(*b.map, GlobalMethod::markov);
  std::size_t n = 0;
  for (auto _ : state) {
    if (n % 8 == 7) {
      state.PauseTiming();
      markov = std::make_unique<MarkovLocalization>(*b.map, GlobalMethod::markov);
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(markov->update(b.readings[n++ % b.readings.size()]));
  }
  report_global_loc(state, b);
}
BENCHMARK(BM_GlobalLoc_Markov)
    ->RangeMultiplier(10)
    ->Range(10000, 10000000)
    ->Unit(benchmark::kMicrosecond)
    ->Complexity(benchmark::oN);

// The whole localization of the 60 readings from no prior (localize_global: every reading, then
// the best cell) on the 10^6-cell grid, per method; items = readings.
void BM_GlobalLoc_Localize(benchmark::State& state) {
  const GlobalLocBench& b = global_loc_bench(1000000);
  const auto method = static_cast<GlobalMethod>(state.range(0));
  for (auto _ : state) {
    const GlobalEstimate e = localize_global(*b.map, b.readings, Pose2{}, method);
    benchmark::DoNotOptimize(e.score);
  }
  state.counters["pose_cells"] = static_cast<double>(b.map->pose_cells());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(b.readings.size()));
}
BENCHMARK(BM_GlobalLoc_Localize)
    ->ArgName("method")
    ->DenseRange(0, 3)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
