// hls/mapping_engine.hpp compiled as an HLS tool sees it: __SYNTHESIS__ defined (by CMake for
// this file only), every INTGRID_HLS_PRAGMA a real `#pragma HLS ...` (GCC ignores them; built
// with -Wno-unknown-pragmas), C++17. Holds the top function an HLS run synthesizes (`set_top
// mapping_engine_b8_t8`).
#ifndef __SYNTHESIS__
#error "mapping_engine_hls_synth.cpp must be compiled with __SYNTHESIS__ defined"
#endif

#include "testbench/mapping_engine_hls_synth.hpp"

#include <memory>

namespace intgrid::hls_synth {

void mapping_engine_b8_t8(MappingEngineB8T8& engine, const hls::ScanPose& pose,
                          const hls::RangeReading readings[1024], int count) {
  engine.begin_scan(pose);
  for (int i = 0; i < 1024; ++i) {
    if (i >= count) break;
    engine.insert(readings[i]);
  }
}

bool mapping_engine_b8_t8_self_check() {
  const auto engine = std::make_unique<MappingEngineB8T8>();
  engine->configure({50, 6, 30000});
  // sin 0 and 1 suffice along +x: the coarse entries at 0 and a quarter turn, no steps.
  engine->load_sine_coarse(hls::mapping::kSineCoarse - 1, 65536);
  // 1 m in bin 167: 20 cells, the first 18 empty (-3), then +20 and +40.
  engine->load_bin(167, {20, 18, -3, 0});
  engine->load_tail(0, 20);
  engine->load_tail(1, 40);
  engine->clear();
  hls::RangeReading reading{0, 1000};
  mapping_engine_b8_t8(*engine, {100, 100, 0, 0, 0}, &reading, 1);
  return engine->cell(100, 100).value() == 0 && engine->cell(101, 100).value() == -3 &&
         engine->cell(118, 100).value() == -3 && engine->cell(119, 100).value() == 20 &&
         engine->cell(120, 100).value() == 40 && engine->cell(121, 100).value() == 0 &&
         engine->cell(110, 101).value() == 0;
}

}  // namespace intgrid::hls_synth
