#include "cli/map_job.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/log_input.hpp"
#include "cli/options.hpp"
#include "cli/output_folder_option.hpp"
#include "cli/progress.hpp"
#include "intgrid/core/parallel.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/core/scan_insertion.hpp"
#include "intgrid/io/image_io.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/io/map_io.hpp"
#include "intgrid/io/text_io.hpp"

namespace intgrid::cli {
namespace {

// The golden model's fields -> the options of `map` (and `demo`) that set them.
FieldFlags map_flags(const MapJobOptions& o) {
  return {{"sigma", "--sigma"},
          {"k_d", "--k-d"},
          {"cell size", "--cell"},
          {"resolution", "--cell"},
          {"index width", "--bits"},
          {"eps", o.eps ? "--eps" : "--levels"},
          {"the number of levels", "--levels"}};
}

core::SepsCodec codec_for(const MapJobOptions& o) {
  if (o.eps) return core::SepsCodec(o.bits, *o.eps);
  if (o.levels >= core::max_index_for_bits(o.bits))
    bad_option("--levels", "must be below the largest index of --bits " + std::to_string(o.bits) +
                               " (" + std::to_string(core::max_index_for_bits(o.bits)) +
                               "): a reading's occupied index would then saturate every cell");
  const double pmax =
      naming_flags(map_flags(o), [&] { return core::narrow_pmax(o.resolution, o.model.sigma0); });
  const std::string why = option_number(o.resolution) + " m cells with --sigma " +
                          option_number(o.model.sigma0) + " m give the ISM a Pmax of " +
                          option_number(pmax);
  if (!(pmax > 0.5 && pmax < 1.0))
    bad_option("--cell", why + ", outside (1/2, 1), so --levels cannot set eps: give --eps");
  try {
    return core::SepsCodec::for_levels(o.bits, pmax, o.levels);
  } catch (const std::invalid_argument& e) {
    bad_option("--cell", why + ", too close to 1/2 for --levels " + std::to_string(o.levels) +
                             " to set eps (" + e.what() + "): use larger cells or give --eps");
  }
}

// The grid covering the log; a log without a valid reading is a bad input file, a grid too big
// for the cell size a bad --cell.
core::GridGeometry geometry_for(const core::Log& log, const MapJobOptions& o) {
  try {
    return core::geometry_covering(log.scans, o.resolution, o.margin);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    if (what.find("valid reading") != std::string::npos)
      throw io::InputError(o.log, 0, "ranges", what);
    if (what.find("2^32") != std::string::npos)
      bad_option("--cell", option_number(o.resolution) + " m is too fine for the log: " + what);
    rethrow_naming_flags(e, map_flags(o));
  }
}

int thread_count(const MapJobOptions& o) {
  return core::threads_or_every_core(o.threads);
}

// The job's large allocations, estimated before any is made: the grid (the probabilities, the
// integer path's indices, the image and the PGM's bytes) and the ISM of the longest reading
// (in double, and in the integer path quantized once per bin of range, core::ism_range_bin as
// the inserter counts them, which it keeps), once for each thread.
void require_memory_for(const core::Log& log, const core::GridGeometry& geometry,
                        const MapJobOptions& o) {
  const double cells = static_cast<double>(geometry.width) * geometry.height;
  const double index_bytes =
      o.arithmetic == core::Arithmetic::integer ? (o.bits <= 8 ? 1.0 : 2.0) : 0.0;
  require_memory(cells * (sizeof(double) + index_bytes + 4.0), o.max_memory_bytes, "--cell",
                 "a grid of " + std::to_string(geometry.width) + " x " +
                     std::to_string(geometry.height) + " cells of " + option_number(o.resolution) +
                     " m over what the log saw (" + option_number(geometry.width * o.resolution) +
                     " x " + option_number(geometry.height * o.resolution) + " m)");
  double longest = 0.0;
  std::set<long long> bins;  // the integer inserter's ISM per bin of range
  for (const core::Scan& scan : log.scans)
    for (const double z : scan.ranges)
      if (core::classify_range(z, scan.max_range) == core::RangeClass::valid) {
        longest = std::max(longest, z);
        if (index_bytes > 0.0) bins.insert(core::ism_range_bin(z, core::kIsmRangeStep));
      }
  const double ism_cells = std::ceil((longest + 8.0 * o.model.sigma(longest)) / o.resolution);
  const double ism_bytes = ism_cells *
                           (sizeof(double) + static_cast<double>(bins.size()) * index_bytes) *
                           thread_count(o);
  const auto metres = [](double v) { return io::printed("%.3g m", v); };
  require_memory(ism_bytes, o.max_memory_bytes, o.model.k_d * longest > 1.0 ? "--k-d" : "--sigma",
                 "the ISM of the log's longest reading (" + metres(longest) +
                     ", spread over 8 sigma = " + metres(8.0 * o.model.sigma(longest)) + ") in " +
                     metres(o.resolution) + " cells" +
                     (index_bytes > 0.0
                          ? ", kept for each distinct range (" + std::to_string(bins.size()) + "),"
                          : ""));
}

// The grid's rows cut into `count` bands of about as many scans' sensor positions each (a
// scan's cells lie around its sensor), so that the threads share the work; any cut gives the
// same map.
std::vector<core::RowBand> row_bands(const core::Log& log, const core::GridGeometry& geometry,
                                     int count) {
  std::vector<int> rows;
  for (const core::Scan& scan : log.scans)
    rows.push_back(std::clamp(geometry.cell_y(scan.sensor_pose().y), 0, geometry.height - 1));
  std::sort(rows.begin(), rows.end());
  std::vector<core::RowBand> bands;
  int first = 0;
  for (int b = 1; b <= count && first < geometry.height; ++b) {
    const int last = b == count ? geometry.height - 1
                                : std::max(first, rows[rows.size() * static_cast<std::size_t>(b) /
                                                       static_cast<std::size_t>(count)]);
    bands.push_back({first, last});
    first = last + 1;
  }
  return bands;
}

// Runs insert(band, stats, progress) for each band on its own thread (core::run_parts; the
// first band with the progress), and returns the first band's reading counts with every band's
// cells.
template <class Insert>
core::InsertionStats insert_by_bands(const std::vector<core::RowBand>& bands,
                                     const core::Progress& progress, const Insert& insert) {
  std::vector<core::InsertionStats> stats(bands.size());
  core::run_parts(bands.size(), static_cast<int>(bands.size()), [&](std::size_t b) {
    insert(bands[b], stats[b], b == 0 ? progress : core::Progress{});
  });
  core::InsertionStats total = stats.front();
  total.cells_updated = 0;
  for (const core::InsertionStats& s : stats) total.cells_updated += s.cells_updated;
  return total;
}

template <class Index>
core::ProbabilityGrid map_with_indices(const core::Log& log, const MapJobOptions& o,
                                       const core::SepsCodec& codec,
                                       const core::GridGeometry& geometry,
                                       const std::vector<core::RowBand>& bands,
                                       core::InsertionStats& stats) {
  core::Grid<Index> grid(geometry, Index{0});
  TerminalProgress progress("mapping (integer)");
  stats = insert_by_bands(
      bands, std::ref(progress),
      [&](core::RowBand band, core::InsertionStats& s, const core::Progress& p) {
        // Each thread keeps its own ISM per reading.
        core::IndexScanInserter<Index> inserter(o.model, o.resolution, codec, o.veto);
        core::insert_scans(grid, log.scans, inserter, s, band, p);
      });
  return core::to_probabilities(grid, codec);
}

MapJobResult map_log(const core::Log& log, const core::GridGeometry& geometry,
                     const MapJobOptions& o) {
  MapJobResult result;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<core::RowBand> bands = row_bands(log, geometry, thread_count(o));
  if (o.arithmetic == core::Arithmetic::integer) {
    result.codec = codec_for(o);
    result.map =
        o.bits <= 8
            ? map_with_indices<std::int8_t>(log, o, *result.codec, geometry, bands, result.stats)
            : map_with_indices<std::int16_t>(log, o, *result.codec, geometry, bands, result.stats);
  } else {
    core::check_model(o.model);
    result.map = core::ProbabilityGrid(geometry, 0.5);
    TerminalProgress progress("mapping (double)");
    result.stats =
        insert_by_bands(bands, std::ref(progress),
                        [&](core::RowBand band, core::InsertionStats& s, const core::Progress& p) {
                          core::insert_scans(result.map, log.scans, o.model, s, band, p);
                        });
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

MapJobResult run_map_job(const MapJobOptions& o) {
  LogInput input = read_log_input(o.log);
  const core::Log& log = input.log;
  const core::GridGeometry geometry = geometry_for(log, o);
  // libpng writes at most a million pixels a row or column (its default limit).
  if (geometry.width > 1000000 || geometry.height > 1000000)
    bad_option("--cell", option_number(o.resolution) + " m cells make a map of " +
                             std::to_string(geometry.width) + " x " +
                             std::to_string(geometry.height) +
                             " cells, past the million pixels a side its PNG can hold");
  require_memory_for(log, geometry, o);
  io::OutputFolder out = open_output_folder(o.out);
  MapJobResult result = naming_flags(map_flags(o), [&] { return map_log(log, geometry, o); });
  result.skipped_records = std::move(input.skipped);

  io::write_ros_map(out.file("map.yaml"), io::RosMap{result.map});
  io::RgbImage image = io::render_probability_grid(result.map);
  std::vector<core::Pose2> path;
  for (const core::Scan& scan : log.scans) path.push_back(scan.sensor_pose());
  io::draw_polyline_world(image, geometry, path, {220, 30, 30});
  io::write_png(out.file("map.png"), image);
  out.commit();
  return result;
}

}  // namespace intgrid::cli
