#include "cli/memory_budget.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "cli/options.hpp"

namespace intgrid::cli {

double default_memory_limit_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  // Without the figure (sysconf fails): 4 GB, the least a host that runs the pipeline has.
  if (pages <= 0 || page <= 0) return 4e9;
  return 0.75 * static_cast<double>(pages) * static_cast<double>(page);
}

std::string memory_text(double bytes) {
  static constexpr const char* kUnits[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int unit = 0;
  while (bytes >= 999.5 && unit < 6) bytes /= 1000.0, ++unit;
  char text[48];
  if (bytes >= 999.5)  // past the largest unit
    std::snprintf(text, sizeof text, "%.3g %s", bytes, kUnits[unit]);
  else if (unit == 0 || bytes >= 99.95)
    std::snprintf(text, sizeof text, "%.0f %s", bytes, kUnits[unit]);
  else
    std::snprintf(text, sizeof text, "%.*f %s", bytes >= 9.995 ? 1 : 2, bytes, kUnits[unit]);
  return text;
}

namespace {

void add_max_memory_option(CLI::App& cmd, const std::function<void(double)>& set_bytes) {
  const double limit = default_memory_limit_bytes();
  set_bytes(limit);
  cmd.add_option_function<double>(
         "--max-memory", [set_bytes](double mb) { set_bytes(mb * 1e6); },
         "the most memory the run's large buffers may take (MB; default: 3/4 of this "
         "machine's, " +
             memory_text(limit) + "): a larger grid is refused before it is allocated")
      ->check(real_range(1.0, 1e9))
      ->type_name("MB");
}

}  // namespace

void add_max_memory_option(CLI::App& cmd, double& limit_bytes) {
  add_max_memory_option(cmd, [&limit_bytes](double bytes) { limit_bytes = bytes; });
}

void add_max_memory_option(CLI::App& cmd, std::size_t& limit_bytes) {
  add_max_memory_option(
      cmd, [&limit_bytes](double bytes) { limit_bytes = static_cast<std::size_t>(bytes); });
}

void require_memory(double bytes, double limit_bytes, const std::string& option,
                    const std::string& what) {
  if (std::isfinite(bytes) && bytes <= limit_bytes) return;
  bad_option(option, what + " needs about " +
                         (std::isfinite(bytes) ? memory_text(bytes) : std::string("unbounded")) +
                         ", more than the memory limit of " + memory_text(limit_bytes) +
                         " (--max-memory)");
}

}  // namespace intgrid::cli
