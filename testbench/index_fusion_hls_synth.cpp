// hls/index_fusion.hpp compiled as an HLS tool sees it: __SYNTHESIS__ defined (by CMake for this
// file only), so every INTGRID_HLS_PRAGMA expands to a real `#pragma HLS ...` (which GCC ignores;
// the file is built with -Wno-unknown-pragmas). Shows the pragma spelling is valid C++ in every
// place it appears, and holds the top function an HLS run synthesizes (`set_top
// index_fusion_b8_l8`).
#ifndef __SYNTHESIS__
#error "index_fusion_hls_synth.cpp must be compiled with __SYNTHESIS__ defined"
#endif

#include "testbench/index_fusion_hls_synth.hpp"

namespace intgrid::hls_synth {

std::uint32_t saturating_add_b8(std::uint32_t a, std::uint32_t b) {
  return hls::saturating_add<8>(a, b);
}

hls::Beat<12, 8> fuse_beat_b12_l8(const hls::Beat<12, 8>& a, const hls::Beat<12, 8>& b) {
  return hls::fuse_beat<12, 8>(a, b);
}

bool tile_b8_l8_self_check() {
  static hls::FusionTile<8, 8, 16> tile;
  std::array<hls::Beat<8, 8>, 16> in{};
  for (int l = 0; l < 8; ++l) hls::set_lane<8, 8>(in[3], l, 100);  // +100 per call in beat 3
  tile.clear();
  tile.accumulate(in);
  tile.accumulate(in);  // 200 saturates at 127
  std::array<hls::Beat<8, 8>, 16> out{};
  tile.read(out);
  std::array<hls::Beat<8, 8>, 16> y{};
  hls::fuse_block<8, 8, 16>(in, in, y);
  return hls::get_lane<8, 8>(out[3], 5) == 127 && hls::get_lane<8, 8>(out[2], 5) == 0 &&
         hls::get_lane<8, 8>(y[3], 0) == 127;
}

// Free running (no start/done handshake) and pipelined at II = 1: a beat of a and b enters and a
// fused beat leaves every cycle, the AXI4-Stream handshakes playing the RTL's ready/valid.
void index_fusion_b8_l8(const std::uint64_t a[1], const std::uint64_t b[1], std::uint64_t y[1]) {
  INTGRID_HLS_PRAGMA("HLS INTERFACE mode=axis port=a")
  INTGRID_HLS_PRAGMA("HLS INTERFACE mode=axis port=b")
  INTGRID_HLS_PRAGMA("HLS INTERFACE mode=axis port=y")
  INTGRID_HLS_PRAGMA("HLS INTERFACE mode=ap_ctrl_none port=return")
  INTGRID_HLS_PRAGMA("HLS PIPELINE II=1")
  static_assert(hls::IndexBeat<8, 8>::kWords == 1, "one 64-bit word a beat");
  y[0] = hls::fuse_beat<8, 8>(hls::Beat<8, 8>{a[0]}, hls::Beat<8, 8>{b[0]})[0];
}

}  // namespace intgrid::hls_synth
