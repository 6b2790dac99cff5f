#include "cli/map_job.hpp"

#include <chrono>

#include "cli/progress.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/io/image_io.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/io/map_io.hpp"

namespace intgrid::cli {
namespace {

core::SepsCodec codec_for(const MapJobOptions& o) {
  if (o.eps) return core::SepsCodec(o.bits, *o.eps);
  return core::SepsCodec::for_levels(o.bits, core::narrow_pmax(o.resolution, o.model.sigma0),
                                     o.levels);
}

template <class Index>
core::ProbabilityGrid map_with_indices(const core::Log& log, const MapJobOptions& o,
                                       const core::SepsCodec& codec,
                                       const core::GridGeometry& geometry,
                                       core::InsertionStats& stats) {
  core::IndexScanInserter<Index> inserter(o.model, o.resolution, codec, o.veto);
  TerminalProgress progress("mapping (integer)");
  return core::to_probabilities(
      core::map_indices(log.scans, inserter, geometry, stats, std::ref(progress)), codec);
}

}  // namespace

MapJobResult run_map_job(const MapJobOptions& o) {
  const core::Log log = io::read_log(o.log);
  const core::GridGeometry geometry = core::geometry_covering(log.scans, o.resolution, o.margin);
  MapJobResult result;
  const auto start = std::chrono::steady_clock::now();
  if (o.arithmetic == core::Arithmetic::integer) {
    result.codec = codec_for(o);
    result.map =
        o.bits <= 8 ? map_with_indices<std::int8_t>(log, o, *result.codec, geometry, result.stats)
                    : map_with_indices<std::int16_t>(log, o, *result.codec, geometry, result.stats);
  } else {
    TerminalProgress progress("mapping (double)");
    result.map =
        core::map_probabilities(log.scans, o.model, geometry, result.stats, std::ref(progress));
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::filesystem::create_directories(o.out);
  io::write_ros_map(o.out / "map.yaml", io::RosMap{result.map});
  io::RgbImage image = io::render_probability_grid(result.map);
  std::vector<core::Pose2> path;
  for (const core::Scan& scan : log.scans) path.push_back(scan.sensor_pose());
  io::draw_polyline_world(image, geometry, path, {220, 30, 30});
  io::write_png(o.out / "map.png", image);
  return result;
}

}  // namespace intgrid::cli
