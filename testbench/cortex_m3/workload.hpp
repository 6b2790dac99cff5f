// The operations measured on the Cortex-M3, each in the integer arithmetic and in double
// precision, on the bundled real data (embedded_inputs.hpp, generated from data/ by
// make_embedded_inputs). One source serves the firmware and the host check: the construction
// builds every input and table (floating point and heap allowed), run() is the measured region.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

namespace intgrid::embedded {

enum class Operation {
  tile_fusion,             // two 64 x 64 grid tiles fused cell by cell
  scan_insertion,          // a real scan's precomputed narrow ISMs laid along its rays
  scan_rays,               // the same rays and table reads without the fusion: what both share
  pose_grid_update,        // one SLAM scan: motion and localization on a 5 x 5 x 5 window
  pose_grid_motion,        // the same scan without its localization
  pose_occupancy_reading,  // one reading's claims added to a 40 x 40 x 32 pose grid
  // The same reading, in double precision as Markov localization takes it (one exp per
  // candidate pose): what a floating-point implementation runs instead of the pose grid.
  markov_reading,
};
inline constexpr std::size_t kOperations = 7;

// The name printed and parsed: tile_fusion, scan_insertion, ...
const char* name_of(Operation operation);

// What one run did: the cells it worked on (per the operation's unit) and a digest of its result.
struct Result {
  std::uint64_t cells = 0;
  std::uint64_t digest = 0;
};

// The bytes of the constant inputs compiled into the image (scans, map window, ISM table).
std::size_t input_bytes();

class Workload {
 public:
  Workload();
  ~Workload();
  // The measured region: allocates nothing.
  void run(Operation operation, bool integer);
  // After run(operation, integer).
  Result result(Operation operation, bool integer) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace intgrid::embedded
