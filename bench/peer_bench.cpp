// Scan insertion against peer libraries, in one process: every scan of the bundled reference
// log (99 scans at their reference poses) into a fresh 5 cm map by intgrid's integer and double
// insertion, MRPT's occupancy grid (COccupancyGridMap2D: int8 log-odds cells, one Bresenham ray
// per beam) and OctoMap (an OcTree at 5 cm, the scan as a point cloud ray-cast in 3D). Items are
// scans; the table printed after the runs gives each one's scans/s and its CPU time against
// intgrid's integer insertion. What each map computes differs (intgrid updates every cell of a
// beam's angular footprint with the exact ISM; the peers one ray of cells per beam), so the
// ratios compare what a user gets for the same log, not the same work.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/poses/CPose3D.h>
#include <octomap/octomap.h>

#include "intgrid/core/types.hpp"
#include "scan_insertion.hpp"

namespace {

namespace core = intgrid::core;
using intgrid::bench::BM_ScanInsertion_DoubleBayes;
using intgrid::bench::BM_ScanInsertion_Int8;
using intgrid::bench::kMapCell;
using intgrid::bench::reference_log;

BENCHMARK(BM_ScanInsertion_Int8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScanInsertion_DoubleBayes)->Unit(benchmark::kMillisecond);

// A scan as MRPT's observation: its beams spread symmetrically over `aperture` about the
// sensor's axis, so the axis is turned to the middle bearing.
mrpt::obs::CObservation2DRangeScan mrpt_scan(const core::Scan& s) {
  mrpt::obs::CObservation2DRangeScan obs;
  const std::size_t n = s.ranges.size();
  obs.resizeScan(n);
  obs.aperture = static_cast<float>(std::abs(s.dangle) * static_cast<double>(n - 1));
  obs.rightToLeft = s.dangle > 0.0;
  obs.maxRange = static_cast<float>(s.max_range);
  const double middle = s.angle0 + 0.5 * s.dangle * static_cast<double>(n - 1);
  obs.sensorPose = mrpt::poses::CPose3D(s.sensor_mount.x, s.sensor_mount.y, 0.0,
                                        s.sensor_mount.theta + middle, 0.0, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const bool valid = s.is_valid_range(s.ranges[i]);
    obs.setScanRange(i, valid ? static_cast<float>(s.ranges[i]) : 0.0f);
    obs.setScanRangeValidity(i, valid);
  }
  return obs;
}

void BM_Peer_Mrpt(benchmark::State& state) {
  const intgrid::bench::LogFixture& f = reference_log();
  std::vector<mrpt::obs::CObservation2DRangeScan> observations;
  std::vector<mrpt::poses::CPose3D> poses;
  for (const core::Scan& s : f.log.scans) {
    observations.push_back(mrpt_scan(s));
    poses.emplace_back(s.robot.x, s.robot.y, 0.0, s.robot.theta, 0.0, 0.0);
  }
  const core::GridGeometry& g = f.geometry;
  mrpt::maps::COccupancyGridMap2D grid(
      static_cast<float>(g.origin_x), static_cast<float>(g.origin_x + g.width * g.resolution),
      static_cast<float>(g.origin_y), static_cast<float>(g.origin_y + g.height * g.resolution),
      static_cast<float>(kMapCell));
  grid.insertionOptions.maxDistanceInsertion = 1e3f;  // the scans' own maximum range decides
  grid.insertionOptions.considerInvalidRangesAsFreeSpace = false;
  std::size_t scans = 0;
  for (auto _ : state) {
    state.PauseTiming();
    grid.fill(0.5f);
    state.ResumeTiming();
    for (std::size_t i = 0; i < observations.size(); ++i)
      grid.insertObservation(observations[i], poses[i]);
    scans += observations.size();
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(scans));
  std::size_t known = 0;  // cells the log moved off 1/2: what the map learnt
  for (unsigned y = 0; y < grid.getSizeY(); ++y)
    for (unsigned x = 0; x < grid.getSizeX(); ++x) known += grid.getCell(x, y) != 0.5f;
  state.counters["cells_known"] = static_cast<double>(known);
}
BENCHMARK(BM_Peer_Mrpt)->Unit(benchmark::kMillisecond);

void BM_Peer_OctoMap(benchmark::State& state) {
  const intgrid::bench::LogFixture& f = reference_log();
  // Each scan's hits in the world frame and its sensor's position.
  std::vector<octomap::Pointcloud> clouds(f.log.scans.size());
  std::vector<octomap::point3d> origins;
  for (std::size_t k = 0; k < f.log.scans.size(); ++k) {
    const core::Scan& s = f.log.scans[k];
    const core::Pose2 sensor = s.sensor_pose();
    origins.emplace_back(static_cast<float>(sensor.x), static_cast<float>(sensor.y), 0.0f);
    for (std::size_t i = 0; i < s.ranges.size(); ++i) {
      if (!s.is_valid_range(s.ranges[i])) continue;
      const double a = sensor.theta + s.bearing(i);
      clouds[k].push_back(static_cast<float>(sensor.x + s.ranges[i] * std::cos(a)),
                          static_cast<float>(sensor.y + s.ranges[i] * std::sin(a)), 0.0f);
    }
  }
  octomap::OcTree tree(kMapCell);
  std::size_t scans = 0;
  for (auto _ : state) {
    state.PauseTiming();
    tree.clear();
    state.ResumeTiming();
    for (std::size_t k = 0; k < clouds.size(); ++k) tree.insertPointCloud(clouds[k], origins[k]);
    scans += clouds.size();
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(scans));
  state.counters["leaf_nodes"] = static_cast<double>(tree.getNumLeafNodes());
}
BENCHMARK(BM_Peer_OctoMap)->Unit(benchmark::kMillisecond);

// The console report, and each benchmark's CPU time per iteration (all the log's scans) kept
// for the table of ratios printed after the runs.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs)
      if (r.run_type == Run::RT_Iteration && !r.error_occurred)
        cpu_seconds_[r.benchmark_name()] = r.GetAdjustedCPUTime() / 1e3;  // reported in ms
  }
  void print_ratios() const {
    const auto reference = cpu_seconds_.find("BM_ScanInsertion_Int8");
    if (reference == cpu_seconds_.end()) return;
    const auto scans = static_cast<double>(reference_log().log.scans.size());
    std::printf("\n| insertion | scans/s | CPU time against intgrid integer |\n|---|---:|---:|\n");
    for (const auto& [name, seconds] : cpu_seconds_)
      std::printf("| %s | %.0f | %.2fx |\n", name.c_str(), scans / seconds,
                  seconds / reference->second);
  }

 private:
  std::map<std::string, double> cpu_seconds_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.print_ratios();
  benchmark::Shutdown();
  return 0;
}
