// The integer SLAM's per-scan path. CMake builds this file with -mgeneral-regs-only where the
// compiler has it, so any floating point on this path is a build error.
#include "grid_slam_engine_impl.hpp"

namespace intgrid::slam {
template class GridSlamEngine<IndexProbabilities>;
}  // namespace intgrid::slam
