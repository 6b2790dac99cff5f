// The ROS map reader on any YAML and image: the input is the YAML, a line "%%IMAGE%%", then the
// image's bytes (written as map.pgm beside it; the seeds' YAML names map.pgm). A map whose
// cells are probabilities and whose geometry is usable, or one InputError naming the YAML or the
// image it names.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_input.hpp"
#include "intgrid/io/map_io.hpp"

using namespace intgrid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  constexpr std::string_view kSeparator = "\n%%IMAGE%%\n";
  const std::size_t at = input.find(kSeparator);
  const auto yaml = fuzz::write_input("map.yaml", input.substr(0, at));
  fuzz::write_input("map.pgm",
                    at == std::string_view::npos ? "" : input.substr(at + kSeparator.size()));
  try {
    const io::RosMap map = io::read_ros_map(yaml);
    const core::GridGeometry& g = map.grid.geometry;
    fuzz::require(g.width > 0 && g.height > 0 && g.resolution >= 1e-4 && g.resolution <= 100.0);
    fuzz::require(std::isfinite(g.origin_x) && std::isfinite(g.origin_y));
    fuzz::require(map.grid.cells.size() == g.size());
    for (const double p : map.grid.cells) fuzz::require(std::isnan(p) || (p >= 0.0 && p <= 1.0));
  } catch (const io::InputError& e) {
    fuzz::check_refusal(e, yaml, /*any_file=*/true);
  }
  return 0;
}
