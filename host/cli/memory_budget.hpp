// The memory a job may ask for, checked before its large allocations (docs/cli.md, "Memory"):
// a small valid input (two scans kilometres apart, an ISM spread of 1e9 m) would otherwise ask
// for tens of gigabytes and end in std::bad_alloc after minutes at the limit, or in the kernel's
// out-of-memory kill, without naming what made it large. An estimate over the limit is refused
// up front as a bad option, naming the option or input that sets the size.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

namespace intgrid::cli {

// The default limit: three quarters of the machine's physical memory (the rest for the system
// and the command's small allocations, which the estimates leave out).
double default_memory_limit_bytes();

// "29.1 GB", "412 MB", "64.0 kB": bytes in decimal units, three significant digits.
std::string memory_text(double bytes);

// Adds --max-memory MB to cmd, the same option for every command; `limit_bytes` holds the limit
// in bytes (the default until the option is given). The std::size_t form sets a library's
// configuration (localization::GlobalLocConfig::memory_limit).
void add_max_memory_option(CLI::App& cmd, double& limit_bytes);
void add_max_memory_option(CLI::App& cmd, std::size_t& limit_bytes);

// Throws OptionError "OPTION: WHAT needs about N, more than the memory limit of L
// (--max-memory)" when bytes > limit_bytes (or is not finite).
void require_memory(double bytes, double limit_bytes, const std::string& option,
                    const std::string& what);

}  // namespace intgrid::cli
