#include "cli/commands.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include "cli/globloc_sweeps.hpp"
#include "cli/slam_sweeps.hpp"
#include "intgrid/figures/thesis_figures.hpp"

namespace intgrid::cli {

namespace {

// A figure's --out: a PNG file.
CLI::Validator png_file() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (std::filesystem::path(text).extension() != ".png")
          return "must be a file name ending in .png, got '" + text + "'";
        return {};
      },
      "");
}

void print_figure_files(const figures::FigureFiles& files) {
  std::printf("wrote %s and %s\n", files.image.string().c_str(), files.data.string().c_str());
}

}  // namespace

void add_figure_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "figure", "the thesis's figures and experiment sweeps: PNGs with their numbers beside them");
  cmd->footer(
      "The thesis's experiment sweeps are these subcommands, and no other subcommand runs one: "
      "ns-sweep (figure 2.12), fusion (figure 2.13), slam-sweeps (section 3.6), globloc-sweeps "
      "(section 4.5). `intgrid demo` draws the first two's figures with their defaults.");
  cmd->require_subcommand(1);

  struct SweepArgs {
    std::filesystem::path out = "ns_sweep.png";
    double z = figures::kNsSweepReading;
  };
  auto sweep = std::make_shared<SweepArgs>();
  CLI::App* ns_sweep = cmd->add_subcommand(
      "ns-sweep", "figure 2.12: the large-FOV ISM against the number of sectors Ns");
  ns_sweep->footer(
      "The large-FOV ISM exact (Ns = A) and with Ns = 1, 3, 5, 10 sectors; CSV ns,ring,bin,p "
      "beside the PNG (same name, .csv).");
  ns_sweep->add_option("--out", sweep->out, "PNG file")->check(png_file())->capture_default_str();
  ns_sweep->add_option("--z", sweep->z, "the reading (m)")
      ->check(non_negative())
      ->capture_default_str();
  ns_sweep->callback([sweep] {
    check_reading_option(sweep->z);
    print_figure_files(figures::write_ns_sweep_figure(sweep->out, sweep->z));
  });

  auto fusion_out = std::make_shared<std::filesystem::path>("fusion.png");
  CLI::App* fusion = cmd->add_subcommand(
      "fusion", "figure 2.13: a narrow and a cone sensor fused, in double and S_eps");
  fusion->footer(
      "A narrow and a cone sensor, their ISMs, mono-sensor grids and their fusion in double and "
      "S_eps; a JSON summary of the grids beside the PNG (same name, .json).");
  fusion->add_option("--out", *fusion_out, "PNG file")->check(png_file())->capture_default_str();
  fusion->callback([fusion_out] { print_figure_files(figures::write_fusion_figure(*fusion_out)); });

  add_slam_sweeps_figure(*cmd);
  add_globloc_sweeps_figure(*cmd);
}

}  // namespace intgrid::cli
