// The mapping engine, as synthesizable C++: a scan's readings laid along integer rays,
// each line-of-sight cell given its reading's narrow-ISM index and fused into a tile of S_eps
// cells in on-chip RAM by kernel 1's saturating adder. Bit for bit golden's
// insert_scan_along_rays (golden/core/include/intgrid/core/ray_insertion.hpp) over the tile: the
// same rays (Amanatides-Woo with exact integer comparisons, the same sine table), the same cells
// in the same order, the same sums.
//
// Only the form differs, for hardware:
//   - the sine table is a quarter wave, kQuarterTurn + 1 entries, the other quadrants by symmetry,
//     held as every 16th entry (kSineCoarse of 17 bits) and the 3-bit steps after each (15 in a
//     45-bit word a block): 63 kbit instead of 278. Golden's table rises by 0 to 7 from one
//     entry to the next (testbench/mapping_engine_table.hpp checks it when it packs the table),
//     and the lookups are equal to golden's whole table at every angle
//     (testbench/mapping_engine_hls_test.cpp);
//   - the line-of-sight cell k = (d + c/2) / c, a division a cell in golden, is a counter: the
//     projection d of a visited cell's centre never decreases along a ray and grows by at most
//     one cell a step, so k steps by one where d passes its next threshold;
//   - a reading's ISM is a core and a tail: cells 1..core take one constant (the reading's empty
//     index), the others come from a tail RAM, where readings of the same tail share one copy.
//
// Widths (the sensor's readings below 2^kRangeBits mm, cells of at most 10^4 mm as golden's):
//   cell, z step        uint<kCellBits>, uint<kRangeBits>
//   sensor offset p     sint<kCellBits + 1>: within half a cell of its cell's centre
//   doubled mm x, y     sint<kCellBits + 3>
//   sin, cos (Q16)      sint<18>; magnitudes uint<17>
//   tx, ty, d           sint<kWalkBits>: the boundary distances times |sin|, |cos|, and the
//                       projection in Q17 mm; (2^19 + 2^14) 2^17 < 2^37 with room for a step
//   cell coordinates    sint<kCoordBits>: the sensor within 2^(kCoordBits-2) cells of the tile
//   k, cells a reading  uint<kRangeBits + 1>
// Everything has a fixed width and a static size; no floating point, no dynamic memory, no
// recursion, no I/O; nothing but standard headers and the kernels' own.
#pragma once

#include <array>
#include <cstdint>

#include "hls/fixed_int.hpp"
#include "hls/hls_pragma.hpp"
#include "hls/index_fusion.hpp"

namespace intgrid::hls {

namespace mapping {
inline constexpr int kRangeBits = 18;  // readings below 262.144 m
inline constexpr int kCellBits = 14;   // cells of 1 .. 10^4 mm
inline constexpr int kWalkBits = kRangeBits + 21;
inline constexpr int kCoordBits = 26;
inline constexpr int kQuarterTurn = 16384;  // angle units (2^16 a turn)
inline constexpr int kSineBlock = 16;       // quarter-wave entries a coarse entry covers
inline constexpr int kSineCoarse = kQuarterTurn / kSineBlock + 1;  // 1025: 0, 16, .., 16384
inline constexpr int kSineStepBits = 3;                            // a step of 0..7
using SineSteps = uint<(kSineBlock - 1) * kSineStepBits>;          // steps 16 j + 1 .. 16 j + 15
using Angle = uint<16>;
using Sine = sint<18>;
using Count = uint<kRangeBits + 1>;
}  // namespace mapping

// Where a scan was taken: the sensor in tile cell (cx, cy), (px, py) mm from that cell's centre
// (at most half a cell each way), heading in angle units.
struct ScanPose {
  sint<mapping::kCoordBits> cx, cy;
  sint<mapping::kCellBits + 1> px, py;
  mapping::Angle heading;
};

// One reading: its bearing in the sensor's frame (angle units) and its range (mm, 0 for none).
struct RangeReading {
  mapping::Angle bearing;
  uint<mapping::kRangeBits> range_mm;
};

// The ISM of one range bin: `cells` line-of-sight cells, 1..core of them `constant`, the others
// tail RAM entries from `tail` on.
template <int B, int TAIL_BITS>
struct IsmBin {
  mapping::Count cells, core;
  sint<B> constant;
  uint<TAIL_BITS> tail;
};

// B-bit S_eps cells, a 2^TILE_BITS square tile; BINS range bins, TAIL_CELLS tail entries.
template <int B, int TILE_BITS, int BINS, int TAIL_CELLS>
class MappingEngine {
 public:
  static constexpr int kSide = 1 << TILE_BITS;
  static constexpr int kTailBits = unsigned_bits(TAIL_CELLS);
  using Bin = IsmBin<B, kTailBits>;
  using Walk = sint<mapping::kWalkBits>;

  // The grid's cell and the ISM table's range step (mm), and the range at and past which
  // readings are not used.
  struct Settings {
    uint<mapping::kCellBits> cell_mm;
    uint<mapping::kRangeBits> z_step_mm;
    uint<mapping::kRangeBits> max_range_mm;
  };

  void configure(const Settings& settings) { settings_ = settings; }
  // The quarter-wave sine S(a) = sin(2 pi a / 2^16) 2^16 rounded (golden's make_sine_table_q16):
  // S(16 j) for j = 0 .. kSineCoarse - 1, and the steps S(16 j + i) - S(16 j + i - 1), i = 1..15
  // (3 bits each, step i at bits 3 (i - 1) and up).
  void load_sine_coarse(int j, uint<17> value) {
    sine_coarse_[static_cast<std::uint32_t>(j)] = value;
  }
  void load_sine_steps(int j, mapping::SineSteps steps) {
    sine_steps_[static_cast<std::uint32_t>(j)] = steps;
  }
  // S(e), e = 0 .. kQuarterTurn: the coarse entry below plus the steps up to e.
  uint<17> quarter_sine(std::uint32_t e) const {
    const std::uint32_t j = e / mapping::kSineBlock, r = e % mapping::kSineBlock;
    const mapping::SineSteps steps = sine_steps_[j % (mapping::kSineCoarse - 1)];
    uint<7> rise = 0;  // at most 15 steps of 7
    for (int i = 1; i < mapping::kSineBlock; ++i) {
      INTGRID_HLS_PRAGMA("HLS UNROLL")
      const auto step =
          static_cast<std::uint32_t>((steps.value() >> ((i - 1) * mapping::kSineStepBits)) & 7);
      if (static_cast<std::uint32_t>(i) <= r) rise = rise + uint<3>(step);
    }
    return sine_coarse_[j] + rise;
  }
  void load_bin(int bin, const Bin& value) { bins_[static_cast<std::uint32_t>(bin)] = value; }
  void load_tail(int address, sint<B> value) { tail_[static_cast<std::uint32_t>(address)] = value; }
  // Every cell back to "no information" (index 0).
  void clear() {
    for (int i = 0; i < kSide * kSide; ++i) {
      INTGRID_HLS_PRAGMA("HLS PIPELINE II=1")
      tile_[static_cast<std::uint32_t>(i)] = 0;
    }
  }

  mapping::Sine sin(mapping::Angle a) const {
    const std::uint32_t angle = a;
    const std::uint32_t quadrant = angle >> 14, within = angle & (mapping::kQuarterTurn - 1);
    const std::uint32_t entry = (quadrant & 1u) != 0 ? mapping::kQuarterTurn - within : within;
    const uint<17> magnitude = quarter_sine(entry);
    return quadrant >= 2 ? mapping::Sine(-magnitude) : mapping::Sine(magnitude);
  }
  mapping::Sine cos(mapping::Angle a) const {
    return sin(mapping::Angle((a.value() + mapping::kQuarterTurn) & 0xFFFF));
  }

  void begin_scan(const ScanPose& pose) { pose_ = pose; }

  // A ray being walked: the cell (ix, iy) it is in (relative to the sensor's), that cell's
  // line-of-sight cell k, and the registers that decide the next step. The next boundary along
  // each axis is met first where tx = bx |sin| < ty = by |cos| (bx, by the doubled millimetres to
  // it); a step along x adds c2 |sin| to tx and c2 |cos| to 2^17 d, along y c2 |cos| to ty and
  // c2 |sin| to 2^17 d. k counts the thresholds (m c - c/2) 2^17 that d has reached, m >= 1.
  struct Ray {
    sint<mapping::kCoordBits> ix, iy;
    mapping::Count k;
    Walk tx, ty, d_q17, next_q17;
    Walk c2_cos, c2_sin, cell_q17, end_q17;
    bool forward_x, forward_y;
    bool done() const { return !(d_q17 < end_q17); }  // d has passed the walk's limit
  };

  // The ray from the scan's sensor along `angle`, walked until the projection d of a cell's
  // centre passes limit_mm: its first cell, the one holding the sensor.
  Ray start_ray(mapping::Angle angle, uint<mapping::kRangeBits + 1> limit_mm) const {
    const uint<mapping::kCellBits> c = settings_.cell_mm;
    const uint<mapping::kCellBits + 1> c2 = shl<1>(c);
    // Doubled millimetres from the lower-left corner of the sensor's cell; the cell holding the
    // sensor is that one or a neighbour.
    const sint<mapping::kCellBits + 3> x = shl<1>(pose_.px) + c, y = shl<1>(pose_.py) + c;
    const sint<2> ix0 = x < 0 ? -1 : (x >= c2 ? 1 : 0);
    const sint<2> iy0 = y < 0 ? -1 : (y >= c2 ? 1 : 0);
    const mapping::Sine cs = cos(angle), sn = sin(angle);
    const uint<17> acs = magnitude(cs), asn = magnitude(sn);
    const sint<2> one = 1;
    Ray r;
    r.forward_x = cs > 0;
    r.forward_y = sn > 0;
    const sint<mapping::kCellBits + 3> bx =
        r.forward_x ? Walk((ix0 + one) * c2 - x) : Walk(x - ix0 * c2);
    const sint<mapping::kCellBits + 3> by =
        r.forward_y ? Walk((iy0 + one) * c2 - y) : Walk(y - iy0 * c2);
    r.ix = ix0;
    r.iy = iy0;
    r.tx = bx * asn;
    r.ty = by * acs;
    r.c2_cos = c2 * acs;
    r.c2_sin = c2 * asn;
    r.d_q17 = (ix0 * c2 + c - x) * cs + (iy0 * c2 + c - y) * sn;
    r.end_q17 = shl<17>(uint<mapping::kRangeBits + 2>(limit_mm + uint<1>(1)));
    r.cell_q17 = shl<17>(c);
    r.next_q17 = shl<17>(uint<mapping::kCellBits>(c - shr<1>(c)));
    r.k = 0;
    count_threshold(r);
    return r;
  }

  // One step to the next cell the ray crosses.
  static void advance(Ray& r) {
    const sint<2> one = 1;
    if (r.tx < r.ty) {
      r.ix = r.forward_x ? r.ix + one : r.ix - one;
      r.tx = r.tx + r.c2_sin;
      r.d_q17 = r.d_q17 + r.c2_cos;
    } else {
      r.iy = r.forward_y ? r.iy + one : r.iy - one;
      r.ty = r.ty + r.c2_cos;
      r.d_q17 = r.d_q17 + r.c2_sin;
    }
    count_threshold(r);
  }

  // Walks the cells the ray from the scan's sensor along `angle` crosses, visit(dx, dy, k) for
  // each with k its line-of-sight cell (k = (d + c/2) / c, d the projection of its centre in mm),
  // until d passes limit_mm. Returns the cells walked (a cell a cycle in hardware).
  template <class Visit>
  std::uint32_t walk(mapping::Angle angle, uint<mapping::kRangeBits + 1> limit_mm,
                     Visit&& visit) const {
    std::uint32_t walked = 0;
    for (Ray r = start_ray(angle, limit_mm); !r.done(); advance(r)) {
      visit(r.ix, r.iy, r.k);
      ++walked;
    }
    return walked;
  }

  // Whether a reading of z mm is used: 0 < z < the maximum range.
  bool is_used(uint<mapping::kRangeBits> z) const { return z != 0 && z < settings_.max_range_mm; }

  // Whether a reading is used, and if so its range bin's ISM (the
  // division is the one golden's table makes) and the length of its walk.
  bool reading_ism(uint<mapping::kRangeBits> z, Bin& ism,
                   uint<mapping::kRangeBits + 1>& limit_mm) const {
    if (!is_used(z)) return false;
    const auto bin = static_cast<std::uint32_t>((z + shr<1>(settings_.z_step_mm)).value() /
                                                settings_.z_step_mm.value());
    ism = bins_[bin];
    const uint<mapping::kCellBits> c = settings_.cell_mm;
    limit_mm = ism.cells * c + shr<1>(c);
    return true;
  }

  // The ray's direction for a reading of the scan begun last.
  mapping::Angle reading_angle(mapping::Angle bearing) const {
    return mapping::Angle((pose_.heading + bearing).value() & 0xFFFF);
  }

  // Fuses line-of-sight cell k of a reading's ISM into the tile at (dx, dy) from the sensor's
  // cell, if k lies in 1..cells and the cell in the tile.
  void fuse_cell(const Bin& ism, sint<mapping::kCoordBits> dx, sint<mapping::kCoordBits> dy,
                 mapping::Count k) {
    if (k == 0 || k > ism.cells) return;
    const sint<mapping::kCoordBits + 1> x = pose_.cx + dx, y = pose_.cy + dy;
    if (x < 0 || x >= kSide || y < 0 || y >= kSide) return;
    const sint<B> value = k <= ism.core
                              ? ism.constant
                              : tail_[static_cast<std::uint32_t>(ism.tail + k - ism.core) - 1u];
    const std::uint32_t address =
        (static_cast<std::uint32_t>(y) << TILE_BITS) | static_cast<std::uint32_t>(x);
    tile_[address] =
        uint<B>(saturating_add<B>(tile_[address], static_cast<std::uint32_t>(value.value()) &
                                                      ((std::uint32_t{1} << B) - 1u)));
  }

  // One reading of the scan begun last: its ISM fused into the tile along its ray. Returns the
  // cells walked.
  std::uint32_t insert(const RangeReading& reading) {
    Bin ism;
    uint<mapping::kRangeBits + 1> limit;
    if (!reading_ism(reading.range_mm, ism, limit)) return 0;
    return walk(reading_angle(reading.bearing), limit,
                [&](sint<mapping::kCoordBits> dx, sint<mapping::kCoordBits> dy, mapping::Count k) {
                  fuse_cell(ism, dx, dy, k);
                });
  }

  // The read port: the S_eps index of cell (x, y).
  sint<B> cell(int x, int y) const {
    return sint<B>(sign_extend<B>(
        tile_[(static_cast<std::uint32_t>(y) << TILE_BITS) | static_cast<std::uint32_t>(x)]));
  }

 private:
  // d grows by at most one cell a step, so it passes at most one threshold.
  static void count_threshold(Ray& r) {
    if (r.d_q17 >= r.next_q17) {
      r.k = r.k + uint<1>(1);
      r.next_q17 = r.next_q17 + r.cell_q17;
    }
  }

  Settings settings_{};
  ScanPose pose_{};
  std::array<uint<17>, mapping::kSineCoarse> sine_coarse_{};
  std::array<mapping::SineSteps, mapping::kSineCoarse - 1> sine_steps_{};
  std::array<Bin, BINS> bins_{};
  std::array<sint<B>, TAIL_CELLS> tail_{};
  std::array<uint<B>, static_cast<std::size_t>(kSide) * kSide> tile_{};
};

}  // namespace intgrid::hls
