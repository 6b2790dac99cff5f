// The Freiburg SLAM benchmark's relations files and the SLAM's trajectories, read; trajectories
// written in the TUM format for other tools (evo, the TUM RGB-D scripts).
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <vector>

#include "intgrid/core/trajectory.hpp"

namespace intgrid::io {

// One relation and the line it was read from (1-based), for messages about it.
struct RelationRecord {
  std::size_t line = 0;
  core::Relation relation;
};

// Reads a relations file: one relation a line, `t1 t2 x y z roll pitch yaw` (seconds, metres,
// radians; the motion from the pose at t1 to the pose at t2 in the frame of the pose at t1).
// Blank lines and lines starting with '#' are skipped. z, roll and pitch must be numbers and
// are not used (the motion is planar). Throws InputError naming file, line and field (t1, t2, x,
// y, z, roll, pitch, yaw) for a missing, unparsable or non-finite field or an extra one, and
// (line 0, field "relations") for a file that holds no relation or cannot be read.
std::vector<RelationRecord> read_relations(const std::filesystem::path& file);

// Reads a trajectory as `intgrid slam` writes it (trajectory.txt): one pose a line, `t x y theta`
// (seconds, metres, radians), in time order; blank lines and '#' comments skipped. Throws
// InputError naming file, line and field (t, x, y, theta) for a missing, unparsable or non-finite
// field, an extra one or a time earlier than the line before, and (line 0, field "poses") for a
// file without any pose.
std::vector<core::TimedPose> read_trajectory(const std::filesystem::path& file);

// The relations of records, in order.
std::vector<core::Relation> relations_of(std::span<const RelationRecord> records);

// Writes trajectory atomically in the TUM format: one line a pose, `t x y z qx qy qz qw`, z = 0,
// the unit quaternion of the heading (qx = qy = 0, qz = sin(theta / 2), qw = cos(theta / 2) with
// theta wrapped to (-pi, pi], so qw >= 0), every number with the shortest digits that read back
// to the same double. No header line. Throws std::runtime_error if writing fails.
void write_tum_trajectory(const std::filesystem::path& file,
                          std::span<const core::TimedPose> trajectory);

}  // namespace intgrid::io
