// Runs the workload on the host and the firmware under QEMU, checks that every integer result
// is bit-identical and that no measured region allocated, and writes the instruction table.
//   embedded_check --firmware ELF --qemu QEMU --size SIZE [--report MD] [--results MD]
// --report writes the table (Markdown); --results replaces the generated section of a Markdown
// file (docs/results.md) between its embedded-table markers. Exit 1 on a mismatch, 2 on a usage or
// run error.
#include <atomic>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/text_io.hpp"
#include "testbench/cortex_m3/workload.hpp"

using namespace intgrid::io;

namespace {

std::atomic<std::size_t> g_allocations{0};

}  // namespace

// Allocation counting on the host, as the firmware counts on the chip.
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace {

using namespace intgrid;

struct Measured {
  std::uint64_t cells = 0;
  std::uint64_t instructions = 0;
  std::uint64_t allocations = 0;
  std::uint64_t digest = 0;
};
using Key = std::pair<std::string, std::string>;  // operation, arithmetic

struct Calibration {
  std::uint64_t iterations = 0, expected = 0, measured = 0, resolution = 0;
};

struct Target {
  std::map<Key, Measured> operations;
  std::vector<Calibration> calibrations;
  std::uint64_t heap_bytes = 0;
  bool done = false;
};

std::string run_command(const std::string& command, int& status) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run: " + command);
  std::string out;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  status = pclose(pipe);
  return out;
}

std::string value_of(const std::string& line, const std::string& key) {
  const std::size_t at = line.find(" " + key + "=");
  if (at == std::string::npos)
    throw std::runtime_error("firmware line without " + key + ": " + line);
  const std::size_t begin = at + key.size() + 2;
  return line.substr(begin, line.find(' ', begin) - begin);
}

Target parse_target(const std::string& output) {
  Target t;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("calibration ", 0) == 0) {
      t.calibrations.push_back(
          {std::stoull(value_of(line, "iterations")), std::stoull(value_of(line, "expected")),
           std::stoull(value_of(line, "measured")), std::stoull(value_of(line, "resolution"))});
    } else if (line.rfind("operation ", 0) == 0) {
      t.operations[{value_of(line, "name"), value_of(line, "arithmetic")}] = {
          std::stoull(value_of(line, "cells")), std::stoull(value_of(line, "instructions")),
          std::stoull(value_of(line, "allocations")),
          std::stoull(value_of(line, "digest"), nullptr, 16)};
    } else if (line.rfind("heap ", 0) == 0) {
      t.heap_bytes = std::stoull(value_of(line, "bytes"));
    } else if (line == "done") {
      t.done = true;
    }
  }
  return t;
}

std::map<Key, Measured> run_host() {
  embedded::Workload workload;
  std::map<Key, Measured> out;
  for (std::size_t i = 0; i < embedded::kOperations; ++i)
    for (const bool integer : {true, false}) {
      const auto operation = static_cast<embedded::Operation>(i);
      const std::size_t before = g_allocations;
      workload.run(operation, integer);
      const std::size_t allocations = g_allocations - before;
      const embedded::Result r = workload.result(operation, integer);
      out[{embedded::name_of(operation), integer ? "int" : "double"}] = {r.cells, 0, allocations,
                                                                         r.digest};
    }
  return out;
}

std::string first_line(const std::string& text) {
  return text.substr(0, text.find('\n'));
}

const std::map<std::string, std::string> kTitles = {
    {"tile_fusion", "index fusion of two 64 x 64 tiles"},
    {"scan_insertion", "scan insertion (361 readings, precomputed ISM table)"},
    {"scan_rays", "of which the rays and table reads alone (no fusion)"},
    {"pose_grid_update", "pose-grid update (motion + localization, 5 x 5 x 5 window, 30 beams)"},
    {"pose_grid_motion", "of which the motion step and the estimate alone (no localization)"},
    {"pose_occupancy_reading", "pose occupancy grid reading (40 x 40 x 32 pose cells)"},
    {"markov_reading", "the same reading: pose grid against a Markov update (one exp per pose)"},
};

// The allocated sections of `size -A`: what the image puts in code memory and in RAM.
std::string image_sections(const std::string& size_a) {
  std::ostringstream md;
  md << "| section | bytes |\n|---|---:|\n";
  std::istringstream lines(size_a);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string name;
    std::uint64_t bytes = 0;
    if (!(fields >> name >> bytes) || name.empty() || name[0] != '.') continue;
    if (name.rfind(".debug", 0) == 0 || name == ".comment" || name == ".ARM.attributes") continue;
    md << "| `" << name << "` | " << bytes << " |\n";
  }
  return md.str();
}

std::string table(const Target& t, const std::string& size_a, const std::string& tools) {
  std::ostringstream md;
  md << "| operation | cells | integer: instructions | per cell | soft-float double: "
        "instructions | per cell | double / integer |\n|---|---:|---:|---:|---:|---:|---:|\n";
  for (std::size_t i = 0; i < embedded::kOperations; ++i) {
    const std::string name = embedded::name_of(static_cast<embedded::Operation>(i));
    const Measured& n = t.operations.at({name, "int"});
    const Measured& d = t.operations.at({name, "double"});
    const double cells = static_cast<double>(n.cells);
    md << "| " << kTitles.at(name) << " | " << n.cells << " | " << n.instructions << " | "
       << printed("%.1f", static_cast<double>(n.instructions) / cells) << " | " << d.instructions
       << " | " << printed("%.1f", static_cast<double>(d.instructions) / cells) << " | "
       << printed("%.1f", static_cast<double>(d.instructions) / static_cast<double>(n.instructions))
       << "x |\n";
  }
  md << "\nCells: grid cells fused, cells the scan's rays update, poses of the window, pose "
        "cells.\nCounter check: ";
  for (const Calibration& c : t.calibrations)
    md << "a loop of " << c.expected << " instructions counted " << c.measured << "; ";
  md << "resolution " << (t.calibrations.empty() ? 0 : t.calibrations[0].resolution)
     << " instructions.\n\nImage (`arm-none-eabi-size -A`, allocated sections). `.text` holds "
        "the code and the constant inputs ("
     << embedded::input_bytes()
     << " bytes); `.stack` and `.heap` are the linker script's reservations (256 KiB in SRAM, "
        "16 MiB in PSRAM), not use: malloc took "
     << t.heap_bytes
     << " bytes of the heap (its high-water mark, every table and grid of the "
        "workload).\n\n"
     << image_sections(size_a) << "\n"
     << tools << "\n";
  return md.str();
}

void replace_section(const std::string& path, const std::string& content) {
  std::string s = read_input_file(path);
  const std::string begin = "<!-- embedded-table:begin -->\n", end = "<!-- embedded-table:end -->";
  const std::size_t a = s.find(begin), b = s.find(end);
  if (a == std::string::npos || b == std::string::npos || b < a)
    throw std::runtime_error(path + ": no embedded-table markers");
  s.replace(a + begin.size(), b - a - begin.size(), content);
  write_file_atomically(path, s);
}

int check(int argc, char** argv) {
  std::map<std::string, std::string> args;
  for (int i = 1; i + 1 < argc; i += 2) args[argv[i]] = argv[i + 1];
  if (!args.count("--firmware") || !args.count("--qemu") || !args.count("--size")) {
    std::fprintf(stderr,
                 "usage: embedded_check --firmware ELF --qemu QEMU --size SIZE [--report MD] "
                 "[--results MD]\n");
    return 2;
  }
  const std::string elf = args["--firmware"];
  int status = 0;
  const std::string output =
      run_command(args["--qemu"] +
                      " -M mps2-an385 -cpu cortex-m3 -nographic -monitor none -serial none"
                      " -semihosting-config enable=on,target=native -icount shift=0 -kernel '" +
                      elf + "'",
                  status);
  std::fputs(output.c_str(), stdout);
  const Target target = parse_target(output);
  if (status != 0 || !target.done) {
    std::fprintf(stderr, "embedded_check: the firmware did not finish (status %d)\n", status);
    return 1;
  }
  const std::map<Key, Measured> host = run_host();
  int failures = 0;
  for (const auto& [key, h] : host) {
    const auto it = target.operations.find(key);
    if (it == target.operations.end()) {
      std::fprintf(stderr, "MISSING %s %s on the target\n", key.first.c_str(), key.second.c_str());
      ++failures;
      continue;
    }
    const Measured& m = it->second;
    const bool same = m.digest == h.digest && m.cells == h.cells;
    std::printf("%-24s %-6s host %016" PRIx64 " target %016" PRIx64 " %s, allocations %" PRIu64
                " host %" PRIu64 " target\n",
                key.first.c_str(), key.second.c_str(), h.digest, m.digest,
                same ? "identical" : "DIFFERENT", h.allocations, m.allocations);
    // Integer results must agree bit for bit; double ones may differ where newlib's libm
    // (exp, pow) rounds differently from the host's.
    if (key.second == "int" && !same) ++failures;
    if (h.allocations != 0 || m.allocations != 0) ++failures;
    if (m.instructions == 0) ++failures;
  }
  for (const Calibration& c : target.calibrations) {
    const auto error = static_cast<long long>(c.measured) - static_cast<long long>(c.expected);
    if (std::llabs(error) > static_cast<long long>(c.resolution)) {
      std::fprintf(stderr, "calibration: %" PRIu64 " counted for %" PRIu64 "\n", c.measured,
                   c.expected);
      ++failures;
    }
  }
  if (target.calibrations.empty()) ++failures;
  if (failures) {
    std::fprintf(stderr, "embedded_check: %d check(s) failed\n", failures);
    return 1;
  }
  int size_status = 0;
  const std::string size = run_command(args["--size"] + " -A '" + elf + "'", size_status);
  const std::string tools = "Measured with " +
                            first_line(run_command(args["--qemu"] + " --version", status)) +
                            " (`-M mps2-an385 -icount shift=0`), firmware built by " +
                            first_line(run_command("arm-none-eabi-g++ --version", status)) +
                            " with -O2 -mcpu=cortex-m3 -mfloat-abi=soft.";
  const std::string md = table(target, size, tools);
  std::printf("\n%s", md.c_str());
  if (args.count("--report"))
    write_file_atomically(args["--report"],
                          "# Embedded target: instructions per operation\n\nGenerated by "
                          "`bash scripts/embedded.sh`; do not edit.\n\n" +
                              md);
  if (args.count("--results")) replace_section(args["--results"], md);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return check(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "embedded_check: %s\n", e.what());
    return 2;
  }
}
