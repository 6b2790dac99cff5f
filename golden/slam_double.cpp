// The double-precision SLAM's per-scan path: the same code as the integer one.
#include "golden/slam_impl.hpp"

namespace intgrid {
template class GridSlam<DoubleProbabilities>;
}  // namespace intgrid
