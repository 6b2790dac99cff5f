// The files the hardware layers build the sectoral ISM kernel from, as text: for a named
// configuration (hardware_configs.hpp), golden's tables (make_ism_hw_kernel) and the widths
// derived from them (derive_ism_hw), in the formats of hls/, systemc/ and rtl/:
//   sectoral_ism_NAME_*.mem       one $readmemh file per ROM of rtl/ (one hex word a line)
//   sectoral_ism_NAME.vc          Verilator -G parameter list of the top `sectoral_ism`
//   sectoral_ism_NAME.svh         the same as a parameter-override macro for wrappers
//   sectoral_ism_NAME.ys          the same as Yosys chparam commands
//   sectoral_ism_NAME_config.hpp  a constexpr configuration struct for hls/ and systemc/
// Pure: nothing is read or written; `intgrid hw-config` (host/cli/hw_config_command.cpp) writes
// the RTL's files, testbench/ism_kernel_export.cpp the C++ header.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "intgrid/kernel/hardware_configs.hpp"

namespace intgrid::kernel {

struct GeneratedFile {
  std::string name;  // file name, no folder: sectoral_ism_cone16_quad_coef.mem, ...
  std::string text;
};

// The ROMs of the top rtl/sectoral_ism.sv, in the order of ism_table_files' .mem files: ROM
// <rom> is the file sectoral_ism_NAME_<rom>.mem, named by the top's parameter <ROM>_FILE.
inline constexpr const char* kIsmRomNames[] = {"quad_coef", "log_norm",   "log_weight",
                                               "log_add",   "thresholds", "threshold_bucket"};

// The files of `config`: the six .mem files (in kIsmRomNames order), then .vc, .svh, .ys and
// _config.hpp. The parameter files name each .mem file as mem_dir / its name (lexically
// normalized): the folder as the tools will resolve it, e.g. config/cone16 for a configuration
// folder rtl/config/cone16 (tools run in rtl/). Deterministic:
// the same configuration and folder give the same bytes. Throws std::invalid_argument where
// derive_ism_hw does (a configuration that does not fit the RTL's words).
std::vector<GeneratedFile> ism_table_files(const IsmHwConfig& config,
                                           const std::filesystem::path& mem_dir);

}  // namespace intgrid::kernel
