// The intgrid command: analysis, mapping and the demo of the golden model.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <stdexcept>

#include "host/commands.hpp"
#include "host/input_error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"intgrid: integer-arithmetic occupancy grids, from the exact inverse sensor model"};
  app.require_subcommand(1);
  intgrid::add_ism_command(app);
  intgrid::add_resolution_command(app);
  intgrid::add_map_command(app);
  intgrid::add_compare_command(app);
  intgrid::add_figure_command(app);
  intgrid::add_demo_command(app);
  intgrid::add_simulate_command(app);
  intgrid::add_slam_command(app);
  intgrid::add_globloc_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const intgrid::InputError& e) {
    std::fprintf(stderr, "intgrid: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "intgrid: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
