// A trajectory's two records, shared by the SLAM that estimates them and the readers and writers
// that move them in and out of files: a pose at a time, and a relation (the true motion between
// two times, as the SLAM benchmark states it).
#pragma once

#include "intgrid/core/types.hpp"

namespace intgrid::core {

struct TimedPose {
  double t = 0.0;  // seconds
  Pose2 pose;
};

// The motion from the pose at t1 to the pose at t2, in the frame of the pose at t1.
struct Relation {
  double t1 = 0.0;
  double t2 = 0.0;
  Pose2 motion;
};

}  // namespace intgrid::core
