// How far a built map's obstacles are from the true ones: the thesis's E(d) (docs/algorithms.md 6),
// the average over the occupied cells of a built map of the distance to the nearest occupied
// cell of the true map.
#pragma once

#include <cstddef>
#include <vector>

#include "intgrid/core/grid.hpp"

namespace intgrid::core {

// Squared distance, in cells, from each cell centre of a width x height grid (x fastest) to the
// nearest occupied cell centre (Felzenszwalb and Huttenlocher's exact Euclidean transform);
// infinity everywhere if no cell is occupied.
std::vector<double> squared_distance_transform(const std::vector<char>& occupied, int width,
                                               int height);

struct ObstacleDistance {
  std::size_t cells = 0;  // occupied cells of the built map
  double mean = 0.0;      // E(d), metres (NaN if cells is 0)
  double max = 0.0;       // metres (NaN if cells is 0)
};

// What "the nearest obstacle" of the true map is.
enum class ObstacleExtent {
  // The square of each occupied cell: a built cell whose centre lies in or on the edge of a true
  // occupied cell is at distance 0. Grids offset by half a cell (a SLAM map is centred on the
  // first pose, not on the world's cells) then measure 0 for a perfect map.
  cell,
  // The centre of each occupied cell: grids offset by half a cell in x and y measure at least
  // resolution / sqrt(2) for a perfect map.
  centre,
};

// For every cell of built with P > built_threshold, the Euclidean distance from its centre to
// the nearest cell of truth with P > truth_threshold (its square or its centre, per extent;
// NaN cells are neither), in world coordinates: the grids may differ in size, origin and
// resolution. Exact: a bound from the Euclidean distance transform of truth (Felzenszwalb and
// Huttenlocher) limits a search of truth's occupied cells around each built cell. Throws
// std::invalid_argument if truth has no occupied cell or either geometry is invalid.
ObstacleDistance distance_to_nearest_obstacle(const ProbabilityGrid& built, double built_threshold,
                                              const ProbabilityGrid& truth, double truth_threshold,
                                              ObstacleExtent extent = ObstacleExtent::cell);

// distance_to_nearest_obstacle(...).mean.
double mean_distance_to_nearest_obstacle(const ProbabilityGrid& built, double built_threshold,
                                         const ProbabilityGrid& truth, double truth_threshold,
                                         ObstacleExtent extent = ObstacleExtent::cell);

}  // namespace intgrid::core
