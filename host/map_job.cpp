#include "host/map_job.hpp"

#include <chrono>

#include "golden/resolution.hpp"
#include "host/image_io.hpp"
#include "host/log_io.hpp"
#include "host/map_io.hpp"
#include "host/progress.hpp"

namespace intgrid {
namespace {

SepsCodec codec_for(const MapJobOptions& o) {
  if (o.eps) return SepsCodec(o.bits, *o.eps);
  return SepsCodec::for_levels(o.bits, narrow_pmax(o.resolution, o.model.sigma0), o.levels);
}

template <class Index>
ProbabilityGrid map_with_indices(const Log& log, const MapJobOptions& o, const SepsCodec& codec,
                                 const GridGeometry& geometry, InsertionStats& stats) {
  IndexScanInserter<Index> inserter(o.model, o.resolution, codec, o.veto);
  TerminalProgress progress("mapping (integer)");
  return to_probabilities(map_indices(log.scans, inserter, geometry, stats, std::ref(progress)),
                          codec);
}

}  // namespace

MapJobResult run_map_job(const MapJobOptions& o) {
  const Log log = read_log(o.log);
  const GridGeometry geometry = geometry_covering(log.scans, o.resolution, o.margin);
  MapJobResult result;
  const auto start = std::chrono::steady_clock::now();
  if (o.arithmetic == Arithmetic::integer) {
    result.codec = codec_for(o);
    result.map =
        o.bits <= 8 ? map_with_indices<std::int8_t>(log, o, *result.codec, geometry, result.stats)
                    : map_with_indices<std::int16_t>(log, o, *result.codec, geometry, result.stats);
  } else {
    TerminalProgress progress("mapping (double)");
    result.map = map_probabilities(log.scans, o.model, geometry, result.stats, std::ref(progress));
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::filesystem::create_directories(o.out);
  write_ros_map(o.out / "map.yaml", RosMap{result.map});
  RgbImage image = render_probability_grid(result.map);
  std::vector<Pose2> path;
  for (const Scan& scan : log.scans) path.push_back(scan.sensor_pose());
  draw_polyline_world(image, geometry, path, {220, 30, 30});
  write_png(o.out / "map.png", image);
  return result;
}

}  // namespace intgrid
