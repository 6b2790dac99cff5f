// Agreement between two occupancy maps of the same place: the share of one's
// occupied cells that lie near an occupied cell of the other, both ways.
#pragma once

#include <cstddef>

#include "intgrid/core/grid.hpp"

namespace intgrid::core {

struct MapAgreement {
  std::size_t ours_occupied = 0;
  std::size_t reference_occupied = 0;
  double ours_near_reference = 0.0;  // share of our occupied cells near a reference one
  double reference_near_ours = 0.0;  // share of the reference's occupied cells near ours
};

// Cells with P > threshold are occupied; "near" is a centre-to-centre distance
// of at most `tolerance` metres. The grids may differ in resolution and origin.
MapAgreement compare_occupied(const ProbabilityGrid& ours, double our_threshold,
                              const ProbabilityGrid& reference, double reference_threshold,
                              double tolerance);

}  // namespace intgrid::core
