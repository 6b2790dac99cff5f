// Running gnuplot (or any helper program) from the figure commands, and quoting for its scripts.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "intgrid/io/atomic_file.hpp"

namespace intgrid::figures {

// Runs program with args, stdout and stderr to /dev/null if quiet. The exit status, or nullopt
// if the program could not be started (not installed).
std::optional<int> run_program(const std::string& program, const std::vector<std::string>& args,
                               bool quiet);

// A string in gnuplot's single quotes.
std::string gp_quoted(const std::string& text);

// The `set terminal` line of a PNG of width x height pixels: pngcairo when cairo, else png.
std::string gp_terminal_line(bool cairo, int width, int height);

// Whether gnuplot can be started, and if so whether it has the pngcairo terminal.
struct GnuplotProbe {
  bool found = false;
  bool cairo = false;
};
GnuplotProbe probe_gnuplot(const std::string& program);

// Runs gnuplot on script (kept in a temporary file at script_path, never committed), which draws
// into the temporary files of pngs, then commits each PNG. False, and nothing written, if gnuplot
// cannot be started; throws if it fails or leaves a PNG empty.
bool draw_pngs(const std::string& gnuplot, const std::string& script,
               const std::filesystem::path& script_path,
               std::initializer_list<io::AtomicFile*> pngs);

// The note a figure prints when draw_pngs could not start gnuplot.
void print_plots_skipped(const std::string& gnuplot);

}  // namespace intgrid::figures
