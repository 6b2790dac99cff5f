#include "cli/commands.hpp"

#include <cstdio>
#include <memory>
#include <optional>
#include "intgrid/core/resolution.hpp"

namespace intgrid::cli {

void add_resolution_command(CLI::App& app) {
  struct Args {
    double sigma = 0.02, pmax = 0.9;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "resolution", "the smallest cell size whose ISM reaches a Pmax, and its worst case");
  cmd->footer(
      "Thesis 2.4.2: the smallest cell size s whose narrow-FOV ISM reaches --pmax with the "
      "reading on a cell centre, the worst-case Pmax at that s (the reading anywhere in a "
      "cell), and the s that reaches --pmax wherever the reading falls (only up to 2/3).");
  cmd->add_option("--sigma", a->sigma, "sensor standard deviation (m)")
      ->required()
      ->check(positive());
  cmd->add_option("--pmax", a->pmax, "wanted maximum occupancy probability")
      ->required()
      ->check(real_range(0.5, 1.0, true, true));
  cmd->add_flag("--json", a->json, "print JSON");
  cmd->callback([a] {
    static const FieldFlags kFlags = {{"Pmax", "--pmax"}, {"sigma", "--sigma"}};
    const double cell =
        naming_flags(kFlags, [&] { return core::smallest_cell_for_pmax(a->sigma, a->pmax); });
    const core::WorstCasePmax worst = core::narrow_pmax_worst_case(cell, a->sigma);
    std::optional<double> cell_worst;
    if (a->pmax <= 2.0 / 3.0)
      cell_worst = naming_flags(
          kFlags, [&] { return core::smallest_cell_for_pmax(a->sigma, a->pmax, true); });
    if (a->json) {
      print_json(
          {{"sigma", a->sigma},
           {"pmax", a->pmax},
           {"cell", cell},
           {"cell_over_sigma", cell / a->sigma},
           {"worst_case_pmax", worst.pmax},
           {"worst_case_offset_cells", worst.offset},
           {"cell_for_worst_case", cell_worst ? nlohmann::json(*cell_worst) : nlohmann::json()}});
      return;
    }
    std::printf("cell size for Pmax %.6g with z on a cell centre: %.6g m (s/sigma = %.4f)\n",
                a->pmax, cell, cell / a->sigma);
    std::printf("worst-case Pmax at that cell size: %.6g (z %.3f cells past a centre)\n",
                worst.pmax, worst.offset);
    if (cell_worst)
      std::printf("cell size for Pmax %.6g wherever z falls: %.6g m\n", a->pmax, *cell_worst);
    else
      std::printf(
          "no cell size reaches Pmax %.6g wherever z falls: the worst case never passes 2/3\n",
          a->pmax);
  });
}

}  // namespace intgrid::cli
