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
  core::NarrowIsmTable table;
  PackedIsmTable packed;
  std::vector<EngineScan> scans;
  core::Grid<std::int8_t> golden;  // side x side cells
  int max_index = 0;
};

// The scans of data/malaga_telecom_loop_reference.log in a side x side tile.
inline EngineLog engine_log(int side) {
  EngineLog out;
  const core::Log log =
      io::read_log(std::string(test::data_dir()) + "/malaga_telecom_loop_reference.log");
  out.sine = core::make_sine_table_q16();
  out.table = log_ism_table();
  out.packed = pack_ism_table(out.table);
  out.max_index = log_codec().max_index();
  out.golden = core::Grid<std::int8_t>({side, side, kLogCellMm / 1000.0, 0.0, 0.0}, 0);
  const core::IntegerRays rays(out.sine, kLogCellMm);
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
    const auto heading = static_cast<std::int32_t>(core::angle_units(sensor.theta) & 0xFFFF);
    std::vector<std::int32_t> bearing, range_mm;
    EngineScan engine_scan;
    engine_scan.pose = {cx, cy, px, py, static_cast<std::uint32_t>(heading)};
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      bearing.push_back(static_cast<std::int32_t>(core::angle_units(scan.bearing(i)) & 0xFFFF));
      const double r = scan.ranges[i];
      range_mm.push_back(scan.is_valid_range(r) ? static_cast<std::int32_t>(core::millimetres(r))
                                                : 0);
      engine_scan.readings.push_back({static_cast<std::uint32_t>(bearing.back()),
                                      static_cast<std::uint32_t>(range_mm.back())});
    }
    core::insert_scan_along_rays(out.golden, rays, out.table, cx, cy, px, py, heading, bearing,
                                 range_mm, kLogMaxRangeMm, out.max_index);
    out.scans.push_back(std::move(engine_scan));
  }
  return out;
}

// An engine's memories loaded for the log: the quarter-wave sine, the packed ISM table.
template <class Engine>
void load_engine(Engine& engine, const EngineLog& log) {
  engine.configure({kLogCellMm, kLogZStepMm, kLogMaxRangeMm});
  for (int a = 0; a <= hls::mapping::kQuarterTurn; ++a)
    engine.load_sine(a, static_cast<std::uint32_t>(log.sine[static_cast<std::size_t>(a)]));
  for (std::size_t bin = 0; bin < log.packed.bins.size(); ++bin) {
    const PackedIsmBin& b = log.packed.bins[bin];
    engine.load_bin(static_cast<int>(bin), {b.cells, b.core, b.constant, b.tail});
  }
  for (std::size_t i = 0; i < log.packed.tail.size(); ++i)
    engine.load_tail(static_cast<int>(i), log.packed.tail[i]);
  engine.clear();
}

}  // namespace intgrid::hw
