// The subcommands of `intgrid`, one file each (NAME_command.cpp); each runs from its parse
// callback. What they share is in command_common.cpp.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/map_job.hpp"
#include "cli/options.hpp"
#include "intgrid/core/map_compare.hpp"
#include "intgrid/core/sectoral_ism.hpp"
#include "intgrid/localization/global_localization.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"

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
void add_localize_command(CLI::App& app);
void add_hw_config_command(CLI::App& app);
// The grid engine's settings as options (--cell, --lambda, --xi, ...), for the figures' sweeps.
// `intgrid slam` adds the same options (slam_command.cpp), the five both engines have setting
// whichever engine runs.
void add_slam_options(CLI::App& cmd, slam::GridSlamConfig& config);
// Throws OptionError naming the flag for a SLAM setting the golden check refuses.
void check_slam_options(const slam::GridSlamConfig& config);
// Global localization's settings (--pose-cell, --headings, --sigma, --max-range, --levels,
// --veto-levels) and --method, shared by globloc and the figures.
void add_global_loc_options(CLI::App& cmd, localization::GlobalLocConfig& config);
CLI::Option* add_global_method_option(CLI::App& cmd, localization::GlobalMethod& method);
// GlobalLocConfig's fields as check_global_loc_config and LocalizationMap name them -> the flags
// of add_global_loc_options.
const FieldFlags& global_loc_flags();
const FieldFlags& pose_search_flags();  // PoseSearchOptions field -> globloc flag
// Throws OptionError for what add_global_loc_options' validators cannot see alone (--veto-levels
// above --levels), then runs check_global_loc_config with its fields named as flags.
void check_global_loc_options(const localization::GlobalLocConfig& config);

// Shared by the subcommands.
void print_json(const nlohmann::json& j);
// --arith int|float; the caller states the default.
CLI::Option* add_arithmetic_option(CLI::App& cmd, core::Arithmetic& arithmetic,
                                   const std::string& help);
// The polar grid's options --fov, --cell, --rings, --bins, --sectors, checked together
// (check_sectoral_grid's limits, named as flags; with kernel, the integer kernel's sectors).
void check_grid_options(const core::SectoralGrid& grid, bool kernel);
// Throws OptionError unless the reading --z is a finite distance >= 0.
void check_reading_option(double z);
// The sensor model and the integer set (--sigma, --k-d, --bits, --levels, --eps, --veto-bound),
// shared by map and demo.
void add_model_options(CLI::App& cmd, MapJobOptions& o);
// An insertion's counts, and a map's agreement with a reference map, as JSON.
nlohmann::json stats_json(const core::InsertionStats& s);
nlohmann::json agreement_json(const core::MapAgreement& a);

}  // namespace intgrid::cli
