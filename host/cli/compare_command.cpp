#include "cli/commands.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include "intgrid/core/map_compare.hpp"
#include "intgrid/io/map_io.hpp"

namespace intgrid::cli {

void add_compare_command(CLI::App& app) {
  struct Args {
    std::filesystem::path map, reference;
    double tolerance_cells = 2.0;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd =
      app.add_subcommand("compare", "agreement of a map's occupied cells with a reference map's");
  cmd->add_option("--map", a->map, "map YAML")->required();
  cmd->add_option("--reference", a->reference, "reference map YAML")->required();
  cmd->add_option("--tolerance-cells", a->tolerance_cells,
                  "distance counted as near, in reference cells")
      ->check(non_negative())
      ->capture_default_str();
  cmd->add_flag("--json", a->json, "print JSON");
  cmd->callback([a] {
    const io::RosMap ours = io::read_ros_map(a->map), reference = io::read_ros_map(a->reference);
    const core::MapAgreement m = core::compare_occupied(
        ours.grid, ours.occupied_thresh, reference.grid, reference.occupied_thresh,
        a->tolerance_cells * reference.grid.geometry.resolution);
    if (a->json) return print_json(agreement_json(m));
    std::printf("occupied cells: %zu ours, %zu reference\n", m.ours_occupied, m.reference_occupied);
    std::printf("ours within %.3g cells of the reference's: %.1f%%\n", a->tolerance_cells,
                100.0 * m.ours_near_reference);
    std::printf("reference's within %.3g cells of ours: %.1f%%\n", a->tolerance_cells,
                100.0 * m.reference_near_ours);
  });
}

}  // namespace intgrid::cli
