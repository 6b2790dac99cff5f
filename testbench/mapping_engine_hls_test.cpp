// hls/mapping_engine.hpp against golden (golden/core/include/intgrid/core/ray_insertion.hpp):
// the quarter-wave sine at every angle, random rays cell for cell with their line-of-sight
// cells, the packed ISM table bin for bin, and the bundled real log's scans at their reference
// poses inserted into a tile, cell for cell against golden's integer insertion of the same
// window. Built twice: the second program has INTGRID_HLS_WIDTH_CHECK on, and each test then
// also asserts that no value left its declared width.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "hls/mapping_engine.hpp"
#include "intgrid/core/ray_insertion.hpp"
#include "testbench/mapping_engine_log.hpp"
#include "testbench/mapping_engine_table.hpp"
#if !defined(INTGRID_HLS_WIDTH_CHECK)
#include "testbench/mapping_engine_hls_synth.hpp"
#endif

namespace intgrid::hw {
namespace {

namespace hls = intgrid::hls;

constexpr std::int32_t kCellMm = kLogCellMm;
constexpr int kTileBits = 8;
constexpr int kTailCells = 1 << 16;
using Engine = hls::MappingEngine<8, kTileBits, kLogBins, kTailCells>;

// In the checked build: forget what came before this test, and at its end, that nothing
// overflowed.
class WidthGuard {
 public:
  WidthGuard() {
#if defined(INTGRID_HLS_WIDTH_CHECK)
    hls::width_log() = {};
#endif
  }
  ~WidthGuard() {
#if defined(INTGRID_HLS_WIDTH_CHECK)
    EXPECT_GT(hls::width_log().stores, 0u);
    EXPECT_EQ(hls::width_log().overflows, 0u) << "a value left its declared width";
#endif
  }
};

std::unique_ptr<Engine> engine_with_sine(const std::vector<std::int32_t>& sine) {
  auto engine = std::make_unique<Engine>();
  const PackedSine packed = pack_quarter_sine(sine);
  for (std::size_t j = 0; j < packed.coarse.size(); ++j)
    engine->load_sine_coarse(static_cast<int>(j), packed.coarse[j]);
  for (std::size_t j = 0; j < packed.steps.size(); ++j)
    engine->load_sine_steps(static_cast<int>(j), packed.steps[j]);
  return engine;
}

TEST(MappingEngineHls, QuarterWaveSineIsGoldensTableAtEveryAngle) {
  const WidthGuard guard;
  const std::vector<std::int32_t> sine = core::make_sine_table_q16();
  const auto engine = engine_with_sine(sine);
  const core::IntegerRays rays(sine, kCellMm);
  for (std::int32_t a = 0; a < 65536; ++a) {
    ASSERT_EQ(engine->sin(hls::mapping::Angle(a)).value(), rays.sin(a)) << "angle " << a;
    ASSERT_EQ(engine->cos(hls::mapping::Angle(a)).value(), rays.cos(a)) << "angle " << a;
  }
}

// The packed form holds only steps of 0..7: a table that rises faster is refused, by entry.
TEST(MappingEngineHls, SinePackingRefusesAStepPastThreeBits) {
  std::vector<std::int32_t> sine = core::make_sine_table_q16();
  EXPECT_NO_THROW(pack_quarter_sine(sine));
  sine[37] += 8;
  try {
    pack_quarter_sine(sine);
    ADD_FAILURE() << "a step of 8 or more was packed";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("entry 37"), std::string::npos) << e.what();
  }
}

// A ray's cells and line-of-sight cells: golden's walk with k = (d + c/2) / c divided out,
// against the engine's counter.
TEST(MappingEngineHls, RayWalkIsGoldensCellForCell) {
  const WidthGuard guard;
  const std::vector<std::int32_t> sine = core::make_sine_table_q16();
  const auto engine = engine_with_sine(sine);
  std::mt19937_64 rng(20);
  std::size_t cells = 0;
  for (int ray = 0; ray < 4000; ++ray) {
    // Cells of 1 mm to golden's 10 m; every fourth ray along or next to an axis, every fourth
    // along a diagonal.
    const std::int32_t c = ray % 3 == 0 ? kCellMm : 1 + static_cast<std::int32_t>(rng() % 10000);
    // The sensor within its cell as the tile's feeder places it: sx = cx c + p, p in
    // [-c/2, c - c/2).
    const auto p = [&] {
      return static_cast<std::int32_t>(rng() % static_cast<std::uint64_t>(c)) - c / 2;
    };
    const std::int32_t px = p();
    std::int32_t py = p();
    std::int32_t angle = static_cast<std::int32_t>(rng() % 65536);
    if (ray % 4 == 1) angle = static_cast<std::int32_t>((rng() % 4) * 16384 + rng() % 3) - 1;
    if (ray % 4 == 2) {  // diagonals from the cell's diagonal: ties between the two boundaries
      angle = static_cast<std::int32_t>((rng() % 4) * 16384 + 8192);
      py = px;
    }
    angle &= 0xFFFF;
    const std::int64_t cells_long = 1 + static_cast<std::int64_t>(rng() % 300);
    const auto limit = static_cast<std::uint32_t>(
        std::min<std::int64_t>(cells_long * c + c / 2, (std::int64_t{1} << 18) + c / 2));
    std::vector<std::tuple<std::int64_t, std::int64_t, std::int64_t>> golden, ours;
    core::IntegerRays(sine, c).walk(px, py, angle, limit, [&](int dx, int dy, std::int64_t d) {
      golden.emplace_back(dx, dy, (static_cast<std::int32_t>(d) + c / 2) / c);
    });
    engine->configure({static_cast<std::uint32_t>(c), kLogZStepMm, kLogMaxRangeMm});
    engine->begin_scan({0, 0, px, py, 0});
    const std::uint32_t walked = engine->walk(
        hls::mapping::Angle(angle), limit, [&](auto dx, auto dy, hls::mapping::Count k) {
          ours.emplace_back(dx.value(), dy.value(), k.value());
        });
    ASSERT_EQ(ours, golden) << "cell " << c << " mm, p (" << px << ", " << py << "), angle "
                            << angle << ", limit " << limit;
    ASSERT_EQ(walked, golden.size());
    cells += golden.size();
  }
  EXPECT_GT(cells, 100000u);
}

TEST(MappingEngineHls, PackedIsmTableIsGoldensBinForBin) {
  const core::NarrowIsmTable table = log_ism_table();
  const PackedIsmTable packed = pack_ism_table(table);
  ASSERT_EQ(packed.bins.size(), static_cast<std::size_t>(kLogBins));
  for (std::size_t bin = 0; bin < packed.bins.size(); ++bin) {
    const PackedIsmBin& b = packed.bins[bin];
    const std::int8_t* golden = table.values.data() + table.begin[bin];
    ASSERT_EQ(b.cells, table.begin[bin + 1] - table.begin[bin]);
    for (std::uint32_t k = 1; k <= b.cells; ++k) {
      const std::int8_t value = k <= b.core ? b.constant : packed.tail[b.tail + k - b.core - 1];
      ASSERT_EQ(value, golden[k - 1]) << "bin " << bin << ", cell " << k;
    }
  }
  // Shared tails keep the table small: most of a reading is its core.
  EXPECT_LT(packed.tail.size() * 20, table.values.size());
  std::printf("ISM table: %zu bins, %zu cells written out, %zu tail cells packed\n",
              packed.bins.size(), table.values.size(), packed.tail.size());
}

// Every scan of the bundled log at its reference pose, into a 12.8 m tile around the start.
TEST(MappingEngineHls, BundledLogTileIsGoldensIntegerInsertion) {
  const WidthGuard guard;
  constexpr int kSide = Engine::kSide;
  const EngineLog log = engine_log(kSide);
  ASSERT_LE(log.packed.tail.size(), static_cast<std::size_t>(kTailCells));
  const auto engine = std::make_unique<Engine>();
  load_engine(*engine, log);
  std::uint64_t walked = 0, readings = 0;
  for (const EngineScan& scan : log.scans) {
    engine->begin_scan(scan.pose);
    for (const hls::RangeReading& reading : scan.readings) {
      walked += engine->insert(reading);
      readings += reading.range_mm != 0 ? 1 : 0;
    }
  }
  std::size_t informed = 0, saturated = 0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const std::int8_t g = log.golden.at(x, y);
      ASSERT_EQ(engine->cell(x, y).value(), g) << "cell (" << x << ", " << y << ")";
      informed += g != 0 ? 1 : 0;
      saturated += (g == log.max_index || g == -log.max_index) ? 1 : 0;
    }
  }
  // A real map: most of the tile seen, walls and free space saturated.
  EXPECT_GT(informed, static_cast<std::size_t>(kSide * kSide / 2));
  EXPECT_GT(saturated, 1000u);
  std::printf("%zu scans, %llu readings, %llu cells walked (%.0f a scan), %zu cells informed\n",
              log.scans.size(), static_cast<unsigned long long>(readings),
              static_cast<unsigned long long>(walked),
              static_cast<double>(walked) / static_cast<double>(log.scans.size()), informed);
}

#if !defined(INTGRID_HLS_WIDTH_CHECK)
// The header as an HLS tool compiles it (mapping_engine_hls_synth.cpp) inserts a reading.
TEST(MappingEngineHls, SynthesizedHeaderInsertsAWall) {
  EXPECT_TRUE(hls_synth::mapping_engine_b8_t8_self_check());
}
#endif

}  // namespace
}  // namespace intgrid::hw
