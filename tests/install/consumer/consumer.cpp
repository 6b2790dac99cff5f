// Reads a ROS map with intgrid::io, fuses two S_eps readings with intgrid::core and checks the
// result against the probabilities it stands for: fails (exit 1) on any disagreement.
#include <cmath>
#include <cstdio>

#include "intgrid/core/seps.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/io/map_io.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const intgrid::io::RosMap map = intgrid::io::read_ros_map(argv[1]);
  const intgrid::core::SepsCodec codec(8, 0.05);
  const auto a = codec.quantize_nearest(0.7), b = codec.quantize_nearest(0.6);
  const double fused = codec.probability(codec.fuse(a, b));
  const double pa = codec.probability(a), pb = codec.probability(b);
  const double bayes = pa * pb / (pa * pb + (1 - pa) * (1 - pb));
  std::printf("map %d x %d cells; fused %.4f, Bayes %.4f\n", map.grid.geometry.width,
              map.grid.geometry.height, fused, bayes);
  return map.grid.geometry.width > 0 && std::abs(fused - bayes) < 0.05 ? 0 : 1;
}
