// The subcommands of `intgrid`; each runs from its parse callback.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/map_job.hpp"
#include "intgrid/localization/global_localization.hpp"
#include "intgrid/slam/grid_slam.hpp"

namespace intgrid::cli {

void add_ism_command(CLI::App& app);
void add_resolution_command(CLI::App& app);
void add_map_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_figure_command(CLI::App& app);
void add_demo_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_slam_command(CLI::App& app);
void add_globloc_command(CLI::App& app);
// The SLAM settings as options (--res, --lambda, --xi, ...), shared by slam and the figures.
void add_slam_options(CLI::App& cmd, slam::SlamConfig& config);
// Global localization's settings (--pose-res, --headings, --sigma, --max-range) and --method,
// shared by globloc and the figures.
void add_global_loc_options(CLI::App& cmd, localization::GlobalLocConfig& config);
CLI::Option* add_global_method_option(CLI::App& cmd, localization::GlobalMethod& method);

// Shared by the subcommands.
void print_json(const nlohmann::json& j);
// --arith int|float; the caller states the default.
CLI::Option* add_arithmetic_option(CLI::App& cmd, core::Arithmetic& arithmetic,
                                   const std::string& help);
// Throws std::invalid_argument unless the reading --z is a finite distance >= 0.
void check_reading_option(double z);

}  // namespace intgrid::cli
