// The intgrid command: analysis, mapping and the demo of the golden model.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <stdexcept>

#include "cli/commands.hpp"
#include "intgrid/io/input_error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"intgrid: integer-arithmetic occupancy grids, from the exact inverse sensor model"};
  app.require_subcommand(1);
  intgrid::cli::add_ism_command(app);
  intgrid::cli::add_resolution_command(app);
  intgrid::cli::add_map_command(app);
  intgrid::cli::add_compare_command(app);
  intgrid::cli::add_figure_command(app);
  intgrid::cli::add_demo_command(app);
  intgrid::cli::add_simulate_command(app);
  intgrid::cli::add_slam_command(app);
  intgrid::cli::add_globloc_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const intgrid::io::InputError& e) {
    std::fprintf(stderr, "intgrid: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "intgrid: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
