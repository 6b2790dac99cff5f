// Localization in a known map, scan after scan: SubmapSlam's localization event (the odometry's
// prediction matched by index sums in a narrow window, in the wide one when the scan does not fit
// there; submap_tracking.hpp) against a map given whole instead of the active submap. No mapping
// and no loop closure: the map stays as given. Integer arithmetic on the per-scan path, as the
// SLAM's front end; the double arithmetic beside it.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/mapping.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/slam/submap_slam.hpp"

namespace intgrid::slam {

// One scan's estimate.
struct MapFix {
  core::Pose2 pose;      // the robot's, in the map's frame
  bool matched = false;  // the scan had tracking.min_hits hits and was matched
  bool wide = false;     // the wide window was searched
  double evidence =
      0.0;  // the narrow match's hits' sum, a share of every hit on the strongest cell
  // At `pose`: the scan's hits (readings below the maximum range), and the share of them within
  // one cell of an occupied map cell (index > 0): how well the scan fits the map there, read
  // from the map alone (a lost robot's hits fall anywhere).
  std::size_t hits = 0;
  double fit = 0.0;
};

// A map's probabilities in config's S_eps indices (the submaps' codec): each cell's nearest
// index, unknown (NaN) cells 0; the geometry unchanged. A map file read back (the SLAM's own
// map.pgm, or another's) becomes what MapLocalizer takes.
core::Grid<std::int8_t> map_indices(const core::ProbabilityGrid& map,
                                    const SubmapSlamConfig& config);

class MapLocalizer {
 public:
  // map: S_eps indices of config's codec, as SubmapSlam::map() writes them, in cells of
  // config.cell; initial: the robot's pose in the map's frame at the first scan localize takes.
  // Throws std::invalid_argument naming the field for a bad configuration or a map of another
  // cell size.
  MapLocalizer(const SubmapSlamConfig& config, core::Arithmetic arithmetic,
               const core::Grid<std::int8_t>& map, const core::Pose2& initial);
  ~MapLocalizer();
  MapLocalizer(MapLocalizer&&) noexcept;
  MapLocalizer& operator=(MapLocalizer&&) noexcept;

  // The next scan: its odometry increment from the one before (none for the first) predicts the
  // pose, the match in the map corrects it. Throws std::invalid_argument for a scan SubmapSlam
  // would refuse.
  MapFix localize(const core::Scan& scan);

 private:
  struct Engine;
  template <class Cell>
  struct EngineOf;
  std::unique_ptr<Engine> engine_;
  core::Pose2 frame_;  // the per-scan path's frame in the map's: cell (0, 0)'s centre
  std::optional<core::Pose2> previous_robot_;
  std::size_t scans_ = 0, readings_ = 0, unusable_readings_ = 0;
};

}  // namespace intgrid::slam
