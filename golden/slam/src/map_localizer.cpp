// MapLocalizer (map_localizer.hpp): the map given whole as the per-scan path's one submap.
#include "intgrid/slam/map_localizer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/units.hpp"
#include "intgrid/slam/grid_slam.hpp"
#include "submap_setup.hpp"
#include "submap_tracking.hpp"

namespace intgrid::slam {

struct MapLocalizer::Engine {
  virtual ~Engine() = default;
  virtual TrackStep localize(const QuantizedScan& scan, const SlamSensor& sensor) = 0;
  // The last scan's hits at `pose`, and of them those within a cell of an occupied map cell.
  virtual std::pair<std::size_t, std::size_t> fit(const SlamPose& pose) const = 0;
  SubmapSlamConfig config;
  RecentSensors sensors;
};

template <class Cell>
struct MapLocalizer::EngineOf final : MapLocalizer::Engine {
  EngineOf(const SubmapSlamConfig& c, const core::SepsCodec& codec,
           const core::Grid<std::int8_t>& map, const SlamPose& initial)
      : tracker(make_tracker_setup(c, codec), make_table<Cell>(c, codec)) {
    config = c;
    std::vector<Cell> cells;
    cells.reserve(map.cells.size());
    for (const std::int8_t n : map.cells) {
      if constexpr (std::is_same_v<Cell, LogOdds>)
        cells.push_back({static_cast<double>(n)});
      else
        cells.push_back(n);
    }
    tracker.localize_in(LocalGrid<Cell>(tracker.setup().cell_mm, 0, 0, map.geometry.width,
                                        map.geometry.height, std::move(cells)),
                        initial);
    // Cells within one cell (Chebyshev) of a cell of positive index.
    const int w = map.geometry.width, h = map.geometry.height;
    std::vector<std::int8_t> near(map.cells.size(), 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (map.cells[static_cast<std::size_t>(y) * w + x] <= 0) continue;
        for (int v = std::max(0, y - 1); v <= std::min(h - 1, y + 1); ++v)
          for (int u = std::max(0, x - 1); u <= std::min(w - 1, x + 1); ++u)
            near[static_cast<std::size_t>(v) * w + u] = 1;
      }
    near_occupied = LocalGrid<std::int8_t>(tracker.setup().cell_mm, 0, 0, w, h, std::move(near));
  }
  TrackStep localize(const QuantizedScan& scan, const SlamSensor& s) override {
    return tracker.localize(scan, s);
  }
  std::pair<std::size_t, std::size_t> fit(const SlamPose& pose) const override {
    std::vector<int> cx, cy;
    matching_detail::hit_cells(tracker.rays(), tracker.points(), pose.x_mm, pose.y_mm,
                               static_cast<std::int32_t>(pose.theta), cx, cy);
    std::size_t near = 0;
    for (std::size_t p = 0; p < cx.size(); ++p) near += near_occupied.at(cx[p], cy[p]) > 0;
    return {cx.size(), near};
  }
  LocalTracker<Cell> tracker;
  LocalGrid<std::int8_t> near_occupied{1};
};

core::Grid<std::int8_t> map_indices(const core::ProbabilityGrid& map,
                                    const SubmapSlamConfig& config) {
  check_submap_slam_config(config);
  const core::SepsCodec codec = make_codec(config);
  core::Grid<std::int8_t> indices(map.geometry, std::int8_t{0});
  for (std::size_t i = 0; i < map.cells.size(); ++i)
    indices.cells[i] = static_cast<std::int8_t>(codec.quantize_nearest(map.cells[i]));
  return indices;
}

MapLocalizer::MapLocalizer(const SubmapSlamConfig& config, core::Arithmetic arithmetic,
                           const core::Grid<std::int8_t>& map, const core::Pose2& initial) {
  check_submap_slam_config(config);
  const core::GridGeometry& g = map.geometry;
  core::require_field(std::abs(g.resolution - config.cell) <= 1e-9 * config.cell, "cell",
                      "must be the map's cell (" + core::number_text(g.resolution) + " m)");
  const core::SepsCodec codec = make_codec(config);
  for (const std::int8_t n : map.cells)
    core::require_field(std::abs(int{n}) <= codec.max_index(), "map",
                        "holds the index " + std::to_string(int{n}) + ", beyond the codec's " +
                            std::to_string(codec.max_index()));
  core::require_field(
      std::isfinite(initial.x) && std::isfinite(initial.y) && std::isfinite(initial.theta),
      "initial", "must be a finite pose");
  frame_ = {g.origin_x + 0.5 * g.resolution, g.origin_y + 0.5 * g.resolution, 0.0};
  const SlamPose start = to_slam_pose(core::relative(frame_, initial));
  if (arithmetic == core::Arithmetic::integer)
    engine_ = std::make_unique<EngineOf<std::int8_t>>(config, codec, map, start);
  else
    engine_ = std::make_unique<EngineOf<LogOdds>>(config, codec, map, start);
}

MapLocalizer::~MapLocalizer() = default;
MapLocalizer::MapLocalizer(MapLocalizer&&) noexcept = default;
MapLocalizer& MapLocalizer::operator=(MapLocalizer&&) noexcept = default;

MapFix MapLocalizer::localize(const core::Scan& scan) {
  const std::string label = scan_label(++scans_, scan.t);
  const std::shared_ptr<const SlamSensor> sensor = recent_sensor(engine_->sensors, scan, label);
  const QuantizedScan q =
      quantize_scan(scan, previous_robot_ ? &*previous_robot_ : nullptr,
                    engine_->config.sensor.max_range, label, readings_, unusable_readings_);
  previous_robot_ = scan.robot;
  const TrackStep step = engine_->localize(q, *sensor);
  MapFix fix;
  fix.pose = core::compose(frame_, to_pose2(step.pose));
  fix.pose.theta = core::wrap_angle(fix.pose.theta);
  fix.matched = step.matched;
  fix.wide = step.wide;
  fix.evidence = static_cast<double>(step.score_permille) * 1e-3;
  const auto [hits, near] = engine_->fit(step.pose);
  fix.hits = hits;
  fix.fit = hits > 0 ? static_cast<double>(near) / static_cast<double>(hits) : 0.0;
  return fix;
}

}  // namespace intgrid::slam
