// The mapping engine (hls/mapping_engine.hpp) as a cycle-accurate SystemC model: the schedule
// its RTL is to have. One SC_CTHREAD on clk_i.pos() with a synchronous active-low reset
// (rst_ni), ready/valid ports; the values come from the HLS engine's per-step helpers, so the
// bits are golden's, and the schedule is this file's:
//   command stream  a beat is a scan pose (in_pose_i: the sensor's cell and offset, the heading
//                   in in_angle_i) or a reading (bearing in in_angle_i, range in in_range_i). It
//                   enters a one-beat slot (in_ready_o = the slot is empty, registered) while
//                   the reading before it is walked.
//   set-up          a used reading's range bin is a division, by a restoring divider of
//                   kDivideCycles cycles in the slot, overlapped with the walk before it, and a
//                   cycle to read the bin's entry; then one start cycle sets the ray up (a pose:
//                   the start cycle only).
//   walk            one cell a cycle, the tile's read-modify-write. The RTL can hold that on
//                   single-port RAMs by banking the tile as a checkerboard: successive cells of a
//                   walk differ by one step in x or in y, so they lie in banks of opposite
//                   (x + y) parity, and the read of one and the write of the one before it go to
//                   different banks. The last cell's write lands the cycle after the walk.
//   read port       rd_addr_i (y * side + x) in, the cell on rd_data_o the next cycle; served
//                   when nothing is in flight (idle_o), rd_ready_o combinational.
//   load port       one write a cycle (ld_valid_i) into the settings (ld_target_i 0: address 0
//                   the cell, 1 the z step, 2 the maximum range, in mm), the quarter-wave sine's
//                   coarse entries (1) and steps (2, hls::MappingEngine::load_sine_steps), an
//                   ISM bin (3: {tail, constant, core, cells} packed from bit 0 up as kBinBits)
//                   or a tail entry (4); the host loads them once for a sensor.
//   reset           clears the tile, a cell a cycle (kSide^2 cycles, in_ready_o low).
#pragma once

#include <cstdint>

#include <systemc>

#include "hls/mapping_engine.hpp"

namespace intgrid::sc {

template <int B, int TILE_BITS, int BINS, int TAIL_CELLS>
struct MappingEngineModule : ::sc_core::sc_module {
  using Engine = hls::MappingEngine<B, TILE_BITS, BINS, TAIL_CELLS>;
  static constexpr int kSide = Engine::kSide;
  // A used reading's bin: one quotient bit a cycle over the range's bits.
  static constexpr int kDivideCycles = hls::mapping::kRangeBits + 1;
  // A bin's entry on the load port: cells and core (kRangeBits + 1 bits each), the constant (B),
  // the tail's address.
  static constexpr int kCountBits = hls::mapping::kRangeBits + 1;
  static constexpr int kBinBits = 2 * kCountBits + B + Engine::kTailBits;
  static_assert(kBinBits <= 64, "a bin's entry must fit the 64-bit load bus");

  ::sc_core::sc_in<bool> clk_i{"clk_i"};
  ::sc_core::sc_in<bool> rst_ni{"rst_ni"};  // synchronous, active low
  // command stream
  ::sc_core::sc_in<bool> in_valid_i{"in_valid_i"};
  ::sc_core::sc_out<bool> in_ready_o{"in_ready_o"};
  ::sc_core::sc_in<bool> in_pose_i{"in_pose_i"};
  ::sc_core::sc_in<::sc_dt::sc_int<hls::mapping::kCoordBits>> in_cx_i{"in_cx_i"};
  ::sc_core::sc_in<::sc_dt::sc_int<hls::mapping::kCoordBits>> in_cy_i{"in_cy_i"};
  ::sc_core::sc_in<::sc_dt::sc_int<hls::mapping::kCellBits + 1>> in_px_i{"in_px_i"};
  ::sc_core::sc_in<::sc_dt::sc_int<hls::mapping::kCellBits + 1>> in_py_i{"in_py_i"};
  ::sc_core::sc_in<::sc_dt::sc_uint<16>> in_angle_i{"in_angle_i"};
  ::sc_core::sc_in<::sc_dt::sc_uint<hls::mapping::kRangeBits>> in_range_i{"in_range_i"};
  // tile read port
  ::sc_core::sc_in<bool> rd_valid_i{"rd_valid_i"};
  ::sc_core::sc_out<bool> rd_ready_o{"rd_ready_o"};
  ::sc_core::sc_in<::sc_dt::sc_uint<2 * TILE_BITS>> rd_addr_i{"rd_addr_i"};
  ::sc_core::sc_out<bool> rd_valid_o{"rd_valid_o"};
  ::sc_core::sc_in<bool> rd_ready_i{"rd_ready_i"};
  ::sc_core::sc_out<::sc_dt::sc_int<B>> rd_data_o{"rd_data_o"};
  ::sc_core::sc_out<bool> idle_o{"idle_o"};  // cleared, no beat in the slot, no walk, no write
  // load port
  ::sc_core::sc_in<bool> ld_valid_i{"ld_valid_i"};
  ::sc_core::sc_in<::sc_dt::sc_uint<3>> ld_target_i{"ld_target_i"};
  ::sc_core::sc_in<::sc_dt::sc_uint<16>> ld_addr_i{"ld_addr_i"};
  ::sc_core::sc_in<::sc_dt::sc_uint<64>> ld_data_i{"ld_data_i"};

  SC_HAS_PROCESS(MappingEngineModule);
  explicit MappingEngineModule(const ::sc_core::sc_module_name& name)
      : ::sc_core::sc_module(name), engine_(new Engine()) {
    SC_CTHREAD(run, clk_i.pos());
    reset_signal_is(rst_ni, false);
    SC_METHOD(read_ready);
    sensitive << rst_ni << idle_q_ << rd_valid_q_ << rd_ready_i;
  }
  ~MappingEngineModule() override { delete engine_; }
  MappingEngineModule(const MappingEngineModule&) = delete;
  MappingEngineModule& operator=(const MappingEngineModule&) = delete;

  // Cells walked since reset: the walk's cycles.
  std::uint64_t cells_walked() const { return cells_walked_; }

 private:
  // Held on the heap: the tile alone is 2^(2 TILE_BITS) cells.
  Engine* engine_;
  // Registered state the combinational read_ready reads.
  ::sc_core::sc_signal<bool> idle_q_{"idle_q"}, rd_valid_q_{"rd_valid_q"};
  // The slot.
  bool slot_full_ = false, slot_pose_ = false;
  int countdown_ = 0;  // divider and bin-read cycles left before the slot's beat may start
  typename Engine::Settings settings_{};
  hls::ScanPose slot_pose_value_{};
  hls::RangeReading slot_reading_{};
  int clearing_ = 0;  // tile cells left to clear
  // The walk, and its last cell's write.
  bool walking_ = false, draining_ = false;
  typename Engine::Bin ism_{};
  typename Engine::Ray ray_{};
  std::uint64_t cells_walked_ = 0;

  void read_ready() {
    rd_ready_o.write(rst_ni.read() && idle_q_.read() && (!rd_valid_q_.read() || rd_ready_i.read()));
  }

  void run() {
    slot_full_ = false;
    countdown_ = 0;
    engine_->clear();
    clearing_ = kSide * kSide;
    walking_ = false;
    draining_ = false;
    cells_walked_ = 0;
    rd_valid_q_.write(false);
    rd_valid_o.write(false);
    rd_data_o.write(0);
    drive_state();
    while (true) {
      wait();
      clock_edge();
    }
  }

  void drive_state() {
    const bool idle = clearing_ == 0 && !slot_full_ && !walking_ && !draining_;
    in_ready_o.write(clearing_ == 0 && !slot_full_);
    idle_q_.write(idle);
    idle_o.write(idle);
  }

  // One rising edge out of reset; everything read holds the value settled before the edge.
  void clock_edge() {
    const bool in_fire = in_valid_i.read() && clearing_ == 0 && !slot_full_;
    const bool rd_fire = rd_valid_i.read() && rd_ready_o.read();
    const bool rd_taken = rd_valid_q_.read() && rd_ready_i.read();

    if (ld_valid_i.read()) load();
    if (clearing_ > 0) --clearing_;
    draining_ = walking_;  // the cell walked at this edge is written at the next
    if (walking_) {
      engine_->fuse_cell(ism_, ray_.ix, ray_.iy, ray_.k);
      Engine::advance(ray_);
      ++cells_walked_;
      walking_ = !ray_.done();
    } else if (slot_full_ && countdown_ == 0) {
      start_slot();
    }
    if (slot_full_ && countdown_ > 0) --countdown_;

    if (in_fire) {
      slot_full_ = true;
      slot_pose_ = in_pose_i.read();
      if (slot_pose_) {
        slot_pose_value_ = {in_cx_i.read().to_int(), in_cy_i.read().to_int(),
                            in_px_i.read().to_int(), in_py_i.read().to_int(),
                            static_cast<std::uint32_t>(in_angle_i.read().to_uint())};
        countdown_ = 0;
      } else {
        slot_reading_ = {static_cast<std::uint32_t>(in_angle_i.read().to_uint()),
                         static_cast<std::uint32_t>(in_range_i.read().to_uint())};
        // The divider runs only for a used reading.
        countdown_ = engine_->is_used(slot_reading_.range_mm) ? kDivideCycles + 1 : 0;
      }
    }

    if (rd_taken) rd_valid_q_.write(false);
    if (rd_fire) {
      const auto address = static_cast<std::uint32_t>(rd_addr_i.read().to_uint());
      const int x = static_cast<int>(address & ((1u << TILE_BITS) - 1u));
      const int y = static_cast<int>(address >> TILE_BITS);
      rd_data_o.write(static_cast<int>(engine_->cell(x, y).value()));
      rd_valid_q_.write(true);
    }
    rd_valid_o.write(rd_fire || (rd_valid_q_.read() && !rd_taken));
    drive_state();
  }

  // A write on the load port; one to an address past its memory is dropped.
  void load() {
    const auto address = static_cast<int>(ld_addr_i.read().to_uint());
    const std::uint64_t data = ld_data_i.read().to_uint64();
    const auto field = [data](int lo, int bits) {
      return static_cast<std::uint32_t>((data >> lo) & ((std::uint64_t{1} << bits) - 1u));
    };
    switch (ld_target_i.read().to_uint()) {
      case 0:
        if (address == 0) settings_.cell_mm = field(0, hls::mapping::kCellBits);
        if (address == 1) settings_.z_step_mm = field(0, hls::mapping::kRangeBits);
        if (address == 2) settings_.max_range_mm = field(0, hls::mapping::kRangeBits);
        engine_->configure(settings_);
        break;
      case 1:
        if (address < hls::mapping::kSineCoarse) engine_->load_sine_coarse(address, field(0, 17));
        break;
      case 2:
        if (address < hls::mapping::kSineCoarse - 1)
          engine_->load_sine_steps(
              address, data & ((std::uint64_t{1} << hls::mapping::SineSteps::width) - 1u));
        break;
      case 3: {
        if (address >= BINS) break;
        typename Engine::Bin bin;
        bin.cells = field(0, kCountBits);
        bin.core = field(kCountBits, kCountBits);
        bin.constant = hls::sint<B>(hls::sign_extend<B>(field(2 * kCountBits, B)));
        bin.tail = field(2 * kCountBits + B, Engine::kTailBits);
        engine_->load_bin(address, bin);
        break;
      }
      case 4:
        if (address < TAIL_CELLS)
          engine_->load_tail(address, hls::sint<B>(hls::sign_extend<B>(field(0, B))));
        break;
      default:  // no memory
        break;
    }
  }

  // The start cycle: a pose becomes the scan's; a used reading's bin is read and its ray set up.
  void start_slot() {
    slot_full_ = false;
    if (slot_pose_) {
      engine_->begin_scan(slot_pose_value_);
      return;
    }
    hls::uint<hls::mapping::kRangeBits + 1> limit;
    if (!engine_->reading_ism(slot_reading_.range_mm, ism_, limit)) return;
    ray_ = engine_->start_ray(engine_->reading_angle(slot_reading_.bearing), limit);
    walking_ = !ray_.done();
  }
};

}  // namespace intgrid::sc
