// The double-precision SLAM's per-scan path: the same code as the integer one.
#include "grid_slam_engine_impl.hpp"

namespace intgrid::slam {
template class GridSlamEngine<DoubleProbabilities>;
}  // namespace intgrid::slam
