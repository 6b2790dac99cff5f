// The double-precision SLAM's per-scan path: the same code as the integer one.
#include "grid_slam_impl.hpp"

namespace intgrid::slam {
template class GridSlam<DoubleProbabilities>;
}  // namespace intgrid::slam
