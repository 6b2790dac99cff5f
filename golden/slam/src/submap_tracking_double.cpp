// SubmapSlam's per-scan path in the double arithmetic: the same code on LogOdds submaps.
#include "submap_tracking.hpp"

namespace intgrid::slam {

template class LocalTracker<LogOdds>;

}  // namespace intgrid::slam
