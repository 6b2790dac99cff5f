// The bundled real log as the mapping engine's stimulus: every scan at its reference pose in
// the frame of a tile whose centre is where the sensor starts, as the engine takes it (the
// sensor's cell, its offset in mm from that cell's centre, angles in units of 2^-16 turn, ranges
// in mm), with the ISM table and golden's tile of the same scans
// (core::insert_scan_along_rays). Shared by the HLS test and the SystemC model's test.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hls/mapping_engine.hpp"
#include "intgrid/core/narrow_ism.hpp"
#include "intgrid/core/ray_insertion.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/units.hpp"
#include "intgrid/io/log_io.hpp"
#include "testbench/mapping_engine_table.hpp"
#include "tests/data_dir.hpp"

namespace intgrid::hw {

// The bundled log's SLAM settings (slam::SubmapSlamConfig's defaults): 5 cm cells, sigma 3 cm,
// 8-bit indices, readings to 30 m in 6 mm bins, empty evidence divided by 4.
inline constexpr std::int32_t kLogCellMm = 50;
inline constexpr std::int32_t kLogZStepMm = 6;
inline constexpr std::int32_t kLogMaxRangeMm = 30000;
inline constexpr int kLogBins = kLogMaxRangeMm / kLogZStepMm + 2;

inline core::SepsCodec log_codec() {
  return core::SepsCodec::for_levels(8, core::narrow_pmax(kLogCellMm / 1000.0, 0.03), 16);
}

inline core::NarrowIsmTable log_ism_table() {
  return core::make_index_ism_table(core::GaussianBeamModel{0.03, 0.0}, kLogCellMm / 1000.0,
                                    log_codec(), kLogZStepMm, kLogMaxRangeMm, 4);
}

struct EngineScan {
  hls::ScanPose pose;
  std::vector<hls::RangeReading> readings;
};

struct EngineLog {
  std::vector<std::int32_t> sine;  // golden's whole table
  PackedSine packed_sine;          // its quarter wave in the engine's form
  core::NarrowIsmTable table;
  PackedIsmTable packed;
  std::vector<EngineScan> scans;
  core::Grid<std::int8_t> golden;  // side x side cells
  int max_index = 0;
};

// The tables, and an empty side x side tile, of the bundled log's settings.
inline EngineLog empty_engine_log(int side) {
  EngineLog out;
  out.sine = core::make_sine_table_q16();
  out.packed_sine = pack_quarter_sine(out.sine);
  out.table = log_ism_table();
  out.packed = pack_ism_table(out.table);
  out.max_index = log_codec().max_index();
  out.golden = core::Grid<std::int8_t>({side, side, kLogCellMm / 1000.0, 0.0, 0.0}, 0);
  return out;
}

// Golden's tile of out.scans: core::insert_scan_along_rays of each, in order.
inline void insert_golden(EngineLog& out) {
  const core::IntegerRays rays(out.sine, kLogCellMm);
  for (const EngineScan& scan : out.scans) {
    std::vector<std::int32_t> bearing, range_mm;
    for (const hls::RangeReading& r : scan.readings) {
      bearing.push_back(static_cast<std::int32_t>(r.bearing.value()));
      range_mm.push_back(static_cast<std::int32_t>(r.range_mm.value()));
    }
    core::insert_scan_along_rays(
        out.golden, rays, out.table, static_cast<int>(scan.pose.cx.value()),
        static_cast<int>(scan.pose.cy.value()), scan.pose.px.value(), scan.pose.py.value(),
        static_cast<std::int32_t>(scan.pose.heading.value()), bearing, range_mm, kLogMaxRangeMm,
        out.max_index);
  }
}

// The scans of data/malaga_telecom_loop_reference.log in a side x side tile.
inline EngineLog engine_log(int side) {
  EngineLog out = empty_engine_log(side);
  const core::Log log =
      io::read_log(std::string(test::data_dir()) + "/malaga_telecom_loop_reference.log");
  // The tile's cell (0, 0) centre, half a tile from where the sensor starts.
  const core::Pose2 start = log.scans.front().sensor_pose();
  const double ox = start.x - side / 2 * kLogCellMm / 1000.0;
  const double oy = start.y - side / 2 * kLogCellMm / 1000.0;
  for (const core::Scan& scan : log.scans) {
    const core::Pose2 sensor = scan.sensor_pose();
    const std::int64_t sx = core::millimetres(sensor.x - ox), sy = core::millimetres(sensor.y - oy);
    using core::ray_detail::floor_div;
    const auto cx = static_cast<int>(floor_div<std::int64_t>(sx + kLogCellMm / 2, kLogCellMm));
    const auto cy = static_cast<int>(floor_div<std::int64_t>(sy + kLogCellMm / 2, kLogCellMm));
    const std::int64_t px = sx - std::int64_t{cx} * kLogCellMm;
    const std::int64_t py = sy - std::int64_t{cy} * kLogCellMm;
    const auto heading = static_cast<std::uint32_t>(core::angle_units(sensor.theta) & 0xFFFF);
    EngineScan engine_scan;
    engine_scan.pose = {cx, cy, px, py, heading};
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      const double r = scan.ranges[i];
      engine_scan.readings.push_back(
          {static_cast<std::uint32_t>(core::angle_units(scan.bearing(i)) & 0xFFFF),
           scan.is_valid_range(r) ? static_cast<std::uint32_t>(core::millimetres(r)) : 0u});
    }
    out.scans.push_back(std::move(engine_scan));
  }
  insert_golden(out);
  return out;
}

// Scans whose rays land exactly on the engine's decisions, which a real log seldom shows: the
// sensor on a cell's edge or corner (an offset of -c/2), rays along the axes (the projection d
// then meets a line-of-sight threshold (m c - c/2) exactly) and the diagonals (both boundaries
// met at once), and one angle unit off them; a few ranges each.
inline EngineLog tie_scans(int side) {
  EngineLog out = empty_engine_log(side);
  constexpr std::int32_t kHalf = kLogCellMm / 2;
  const std::int32_t offsets[][2] = {
      {-kHalf, -kHalf}, {-kHalf, 0}, {0, -kHalf}, {0, 0}, {kHalf - 1, -kHalf}};
  for (const auto& offset : offsets) {
    for (const std::uint32_t heading : {0u, 8192u, 16384u}) {
      EngineScan scan;
      scan.pose = {side / 2, side / 2, offset[0], offset[1], heading};
      for (std::uint32_t direction = 0; direction < 8; ++direction) {
        for (const std::uint32_t off : {0u, 1u, 65535u}) {
          for (const std::uint32_t range : {300u, 1000u, 2525u, 4000u}) {
            scan.readings.push_back({(direction * 8192u + off) & 0xFFFFu, range});
          }
        }
      }
      out.scans.push_back(std::move(scan));
    }
  }
  insert_golden(out);
  return out;
}

// An engine's memories loaded for the log: the packed quarter-wave sine, the packed ISM table.
template <class Engine>
void load_engine(Engine& engine, const EngineLog& log) {
  engine.configure({kLogCellMm, kLogZStepMm, kLogMaxRangeMm});
  for (std::size_t j = 0; j < log.packed_sine.coarse.size(); ++j)
    engine.load_sine_coarse(static_cast<int>(j), log.packed_sine.coarse[j]);
  for (std::size_t j = 0; j < log.packed_sine.steps.size(); ++j)
    engine.load_sine_steps(static_cast<int>(j), log.packed_sine.steps[j]);
  for (std::size_t bin = 0; bin < log.packed.bins.size(); ++bin) {
    const PackedIsmBin& b = log.packed.bins[bin];
    engine.load_bin(static_cast<int>(bin), {b.cells, b.core, b.constant, b.tail});
  }
  for (std::size_t i = 0; i < log.packed.tail.size(); ++i)
    engine.load_tail(static_cast<int>(i), log.packed.tail[i]);
  engine.clear();
}

}  // namespace intgrid::hw
