// The subcommands of `intgrid`; each runs from its parse callback.
#pragma once

#include <CLI/CLI.hpp>

namespace intgrid {

void add_ism_command(CLI::App& app);
void add_resolution_command(CLI::App& app);
void add_map_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_demo_command(CLI::App& app);

}  // namespace intgrid
