#include "cli/commands.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "cli/globloc_job.hpp"
#include "cli/globloc_sweeps.hpp"
#include "cli/hardware_summary.hpp"
#include "cli/install_paths.hpp"
#include "cli/kernel_agreement.hpp"
#include "cli/log_input.hpp"
#include "cli/map_job.hpp"
#include "cli/slam_job.hpp"
#include "cli/slam_sweeps.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/figures/thesis_figures.hpp"
#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/map_io.hpp"
#include "intgrid/io/text_io.hpp"

namespace intgrid::cli {

void print_json(const nlohmann::json& j) {
  std::printf("%s\n", j.dump(2).c_str());
}

CLI::Option* add_arithmetic_option(CLI::App& cmd, core::Arithmetic& arithmetic,
                                   const std::string& help) {
  return add_choice_option(
      cmd, "--arith", arithmetic,
      {{"int", core::Arithmetic::integer}, {"float", core::Arithmetic::floating}}, help);
}

void check_reading_option(double z) {
  if (!(z >= 0.0) || !std::isfinite(z))
    bad_option("--z", "must be a finite distance >= 0 (m), got " + option_number(z));
}

namespace {

nlohmann::json stats_json(const core::InsertionStats& s) {
  return {{"scans", s.scans},
          {"readings", s.readings},
          {"inserted", s.inserted},
          {"skipped",
           {{"zero", s.zero},
            {"not_finite", s.not_finite},
            {"negative", s.negative},
            {"at_or_over_max_range", s.at_or_over_max}}},
          {"cells_updated", s.cells_updated}};
}

nlohmann::json agreement_json(const core::MapAgreement& a) {
  return {{"ours_occupied", a.ours_occupied},
          {"reference_occupied", a.reference_occupied},
          {"ours_near_reference", a.ours_near_reference},
          {"reference_near_ours", a.reference_near_ours}};
}

// Options shared by `map` and `demo`: the sensor model and the integer set.
void add_model_options(CLI::App& cmd, MapJobOptions& o) {
  cmd.add_option("--sigma", o.model.sigma0, "sensor standard deviation at distance 0 (m)")
      ->check(positive())
      ->capture_default_str();
  cmd.add_option("--k-d", o.model.k_d, "relative growth of sigma per metre")
      ->check(non_negative())
      ->capture_default_str();
  cmd.add_option("--bits", o.bits, "S_eps index width")
      ->transform(whole_range(2, 16))
      ->capture_default_str();
  cmd.add_option("--levels", o.levels, "eps such that the ISM's Pmax is this many index steps")
      ->transform(whole_at_least(1))
      ->capture_default_str();
  cmd.add_option("--eps", o.eps, "eps of S_eps (overrides --levels)")
      ->check(real_range(0.0, 0.5, true, true));
  add_choice_option(cmd, "--veto-bound", o.veto,
                    {{"claim", core::VetoBound::strongest_claim}, {"none", core::VetoBound::none}},
                    "bound each reading's empty indices by its strongest occupied index")
      ->default_str("claim");
}

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

void add_resolution_command(CLI::App& app) {
  struct Args {
    double sigma = 0.02, pmax = 0.9;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "resolution", "the smallest cell size whose ISM reaches a Pmax, and its worst case");
  cmd->footer(
      "Thesis 2.4.2: the smallest cell size s whose narrow-FOV ISM reaches --pmax with the "
      "reading on a cell centre, the worst-case Pmax at that s (the reading anywhere in a "
      "cell), and the s that reaches --pmax wherever the reading falls (only up to 2/3).");
  cmd->add_option("--sigma", a->sigma, "sensor standard deviation (m)")
      ->required()
      ->check(positive());
  cmd->add_option("--pmax", a->pmax, "wanted maximum occupancy probability")
      ->required()
      ->check(real_range(0.5, 1.0, true, true));
  cmd->add_flag("--json", a->json, "print JSON");
  cmd->callback([a] {
    static const FieldFlags kFlags = {{"Pmax", "--pmax"}, {"sigma", "--sigma"}};
    const double cell =
        naming_flags(kFlags, [&] { return core::smallest_cell_for_pmax(a->sigma, a->pmax); });
    const core::WorstCasePmax worst = core::narrow_pmax_worst_case(cell, a->sigma);
    std::optional<double> cell_worst;
    if (a->pmax <= 2.0 / 3.0)
      cell_worst = naming_flags(
          kFlags, [&] { return core::smallest_cell_for_pmax(a->sigma, a->pmax, true); });
    if (a->json) {
      print_json(
          {{"sigma", a->sigma},
           {"pmax", a->pmax},
           {"cell", cell},
           {"cell_over_sigma", cell / a->sigma},
           {"worst_case_pmax", worst.pmax},
           {"worst_case_offset_cells", worst.offset},
           {"cell_for_worst_case", cell_worst ? nlohmann::json(*cell_worst) : nlohmann::json()}});
      return;
    }
    std::printf("cell size for Pmax %.6g with z on a cell centre: %.6g m (s/sigma = %.4f)\n",
                a->pmax, cell, cell / a->sigma);
    std::printf("worst-case Pmax at that cell size: %.6g (z %.3f cells past a centre)\n",
                worst.pmax, worst.offset);
    if (cell_worst)
      std::printf("cell size for Pmax %.6g wherever z falls: %.6g m\n", a->pmax, *cell_worst);
    else
      std::printf(
          "no cell size reaches Pmax %.6g wherever z falls: the worst case never passes 2/3\n",
          a->pmax);
  });
}

void add_map_command(CLI::App& app) {
  auto o = std::make_shared<MapJobOptions>();
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("map", "map a log with its own poses into an occupancy grid");
  cmd->footer(
      "Writes DIR/map.yaml + map.pgm (ROS map_server) and map.png with the sensor's path in "
      "red. Readings that are 0, NaN, infinite, negative or at/over the scan's maximum range are "
      "not inserted, and are counted.");
  cmd->add_option("--log", o->log, "log file (project format or CARMEN)")->required();
  cmd->add_option("--out", o->out, "output folder: map.yaml, map.pgm, map.png")->required();
  cmd->add_option("--cell,--res", o->resolution, "cell size (m)")->required()->check(positive());
  add_arithmetic_option(*cmd, o->arithmetic, "int: S_eps indices; float: double-precision Bayes")
      ->default_str("int");
  add_model_options(*cmd, *o);
  cmd->add_option("--threads", o->threads,
                  "threads inserting the log, each into its own band of the grid's rows (0: every "
                  "core); the same map for any count")
      ->transform(whole_range(0, 256))
      ->capture_default_str();
  add_max_memory_option(*cmd, o->max_memory_bytes);
  cmd->add_flag("--json", *json, "print the run's figures as JSON");
  cmd->callback([o, json] {
    const MapJobResult r = run_map_job(*o);
    const nlohmann::json j = {
        {"out", o->out.string()},
        {"arith", o->arithmetic == core::Arithmetic::integer ? "int" : "float"},
        {"seconds", r.seconds},
        {"eps", r.codec ? nlohmann::json(r.codec->eps()) : nlohmann::json()},
        {"stats", stats_json(r.stats)},
        {"skipped_records", skipped_records_json(r.skipped_records)}};
    if (*json) return print_json(j);
    std::printf("wrote %s/map.yaml, map.pgm, map.png\n", o->out.string().c_str());
    std::printf(
        "%zu scans, %zu readings inserted, %zu skipped (zero %zu, NaN/inf %zu, negative %zu, "
        ">= max range %zu), %.3f s\n",
        r.stats.scans, r.stats.inserted, r.stats.skipped(), r.stats.zero, r.stats.not_finite,
        r.stats.negative, r.stats.at_or_over_max, r.seconds);
  });
}

void add_compare_command(CLI::App& app) {
  struct Args {
    std::filesystem::path map, reference;
    double tolerance_cells = 2.0;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd =
      app.add_subcommand("compare", "agreement of a map's occupied cells with a reference map's");
  cmd->add_option("--map", a->map, "map YAML")->required();
  cmd->add_option("--reference", a->reference, "reference map YAML")->required();
  cmd->add_option("--tolerance-cells", a->tolerance_cells,
                  "distance counted as near, in reference cells")
      ->check(non_negative())
      ->capture_default_str();
  cmd->add_flag("--json", a->json, "print JSON");
  cmd->callback([a] {
    const io::RosMap ours = io::read_ros_map(a->map), reference = io::read_ros_map(a->reference);
    const core::MapAgreement m = core::compare_occupied(
        ours.grid, ours.occupied_thresh, reference.grid, reference.occupied_thresh,
        a->tolerance_cells * reference.grid.geometry.resolution);
    if (a->json) return print_json(agreement_json(m));
    std::printf("occupied cells: %zu ours, %zu reference\n", m.ours_occupied, m.reference_occupied);
    std::printf("ours within %.3g cells of the reference's: %.1f%%\n", a->tolerance_cells,
                100.0 * m.ours_near_reference);
    std::printf("reference's within %.3g cells of ours: %.1f%%\n", a->tolerance_cells,
                100.0 * m.reference_near_ours);
  });
}

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

namespace {

nlohmann::json demo_map_section(const MapJobOptions& o, const MapJobResult& r,
                                const io::RosMap& reference) {
  const core::MapAgreement m =
      core::compare_occupied(r.map, 0.65, reference.grid, reference.occupied_thresh,
                             2.0 * reference.grid.geometry.resolution);
  std::printf("  %-5s %s: %zu scans in %.3f s (%.0f scans/s), %zu readings skipped\n",
              o.arithmetic == core::Arithmetic::integer ? "int" : "float",
              (o.out / "map.png").string().c_str(), r.stats.scans, r.seconds,
              static_cast<double>(r.stats.scans) / r.seconds, r.stats.skipped());
  std::printf(
      "        occupied cells within 2 cells of the reference map's: %.1f%%; reference's near "
      "ours: %.1f%%\n",
      100.0 * m.ours_near_reference, 100.0 * m.reference_near_ours);
  return {{"folder", o.out.string()},
          {"seconds", r.seconds},
          {"stats", stats_json(r.stats)},
          {"agreement_with_reference_map", agreement_json(m)}};
}

nlohmann::json demo_figures_section(const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  const figures::FigureFiles sweep = figures::write_ns_sweep_figure(folder / "ns_sweep.png");
  std::printf("  %s: the large-FOV ISM exact and with Ns = 1, 3, 5, 10 (numbers in %s)\n",
              sweep.image.string().c_str(), sweep.data.filename().string().c_str());
  const figures::FigureFiles fusion = figures::write_fusion_figure(folder / "fusion.png");
  std::printf("  %s: a narrow and a cone sensor fused in double and S_eps (summary in %s)\n",
              fusion.image.string().c_str(), fusion.data.filename().string().c_str());
  return {{"ns_sweep", {{"image", sweep.image.string()}, {"data", sweep.data.string()}}},
          {"fusion", {{"image", fusion.image.string()}, {"data", fusion.data.string()}}}};
}

nlohmann::json demo_kernel_section() {
  constexpr std::size_t kDrawnReadings = 2000;
  constexpr std::uint64_t kSeed = 1;
  const core::SectoralGrid grid;
  const KernelAgreementReport r = kernel_agreement_report(
      core::ConeSensorModel{}, grid, core::SepsCodec(8, 0.05), kDrawnReadings, kSeed);
  const kernel::KernelAgreement& a = r.agreement;
  std::printf(
      "  integer ISM kernel, default cone (R %d, A %d, Ns %d), %zu readings: %.3f%% of %zu cells "
      "equal to the quantized double ISM, %zu one step off, %zu further\n",
      grid.rings, grid.bins, grid.sectors, a.readings, 100.0 * a.equal_share(), a.cells, a.one_step,
      a.more);
  return kernel_agreement_json(r);
}

// The kernels' measured figures from docs/hardware_report.json, or one line saying how to
// generate it: the demo never fails for want of the report.
nlohmann::json demo_hardware_section(const std::filesystem::path& data) {
  const HardwareSummary h = read_hardware_summary(hardware_report_path(data));
  for (const std::string& line : h.lines) std::printf("%s\n", line.c_str());
  return h.json;
}

}  // namespace

// Both SLAM engines on the real log in both arithmetics, scored against the reference trajectory:
// the default (submaps, chosen on the Freiburg logs) beside the thesis's event-driven grid SLAM
// (chosen on this log), so that the demo shows which one holds here.
static nlohmann::json demo_slam_section(const std::filesystem::path& data,
                                        const std::filesystem::path& out) {
  nlohmann::json section;
  for (const SlamEngine engine : {SlamEngine::submaps, SlamEngine::grid}) {
    const bool grid = engine == SlamEngine::grid;
    const char* name = grid ? "grid" : "submaps";
    SlamJobOptions defaults;
    std::printf("%s of the raw log (%s), %g cm cells, default settings:\n",
                grid ? "event-driven grid SLAM (--engine grid)"
                     : "submap SLAM with loop closure (the default engine)",
                (data / "malaga_telecom_loop.log").string().c_str(),
                (grid ? defaults.grid_config.cell : defaults.submap_config.cell) * 100.0);
    double seconds[2] = {0.0, 0.0};
    for (const core::Arithmetic arithmetic :
         {core::Arithmetic::integer, core::Arithmetic::floating}) {
      const bool integer = arithmetic == core::Arithmetic::integer;
      SlamJobOptions o;
      o.engine = engine;
      o.log = data / "malaga_telecom_loop.log";
      o.reference = data / "malaga_telecom_loop_reference.log";
      o.out = out / (std::string(name) + (integer ? "-int" : "-float"));
      o.arithmetic = arithmetic;
      const SlamJobResult r = run_slam_job(o);
      seconds[integer ? 0 : 1] = r.seconds;
      std::printf("  %-6s %s -> %s\n", integer ? "int" : "float", slam_summary(r).c_str(),
                  (o.out / "map.png").string().c_str());
      section[name][integer ? "int" : "float"] = r.metrics;
    }
    section[name]["int_over_float_time"] = seconds[0] / seconds[1];
    std::printf("  integer / double run time: %.2f\n", seconds[0] / seconds[1]);
  }
  return section;
}

// Global localization of every 10th raw scan in the bundled map, each from no prior, scored
// against the reference trajectory.
static nlohmann::json demo_globloc_section(const std::filesystem::path& data,
                                           const std::filesystem::path& out) {
  GlobLocJobOptions o;
  o.map = data / "malaga_telecom_map.yaml";
  o.log = data / "malaga_telecom_loop.log";
  o.reference = data / "malaga_telecom_loop_reference.log";
  o.out = out;
  o.every = 10;
  std::printf(
      "global localization of every %zuth raw scan (%s) in %s, each from no prior, pose "
      "occupancy grid %g m x %d headings, %d readings a scan:\n",
      o.every, o.log.filename().string().c_str(), o.map.filename().string().c_str(),
      o.config.pose_res, o.config.headings, o.beams);
  const GlobLocJobResult r = run_globloc_job(o);
  std::printf(
      "  %zu of %zu scans at the reference's time within 0.5 m and 15 degrees of its pose "
      "(%.0f%%); map prepared in %.2f s, %.2f s a scan -> %s\n",
      r.found, r.matched,
      r.matched ? 100.0 * static_cast<double>(r.found) / static_cast<double>(r.matched) : 0.0,
      r.map_seconds, r.seconds / static_cast<double>(r.scans.size()),
      (o.out / "pose_grid.png").string().c_str());
  return r.metrics;
}

void add_demo_command(CLI::App& app) {
  struct Args {
    std::filesystem::path out = "intgrid-demo";
    std::filesystem::path data = bundled_data_dir();
    MapJobOptions map;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("demo", "the full host pipeline on the bundled real log");
  cmd->footer(
      "Maps of the bundled log in both arithmetics, the SLAM of the raw log, global localization "
      "of every 10th scan, the two ISM figures (those of `intgrid figure ns-sweep` and `figure "
      "fusion`), the integer kernel's agreement and the hardware kernels' summary; "
      "DIR/summary.json.");
  cmd->add_option("--out", a->out, "output folder")->capture_default_str();
  cmd->add_option("--data", a->data,
                  "folder of the bundled data (default: share/intgrid/data beside the command)");
  add_model_options(*cmd, a->map);
  add_max_memory_option(*cmd, a->map.max_memory_bytes);
  cmd->callback([a] {
    const std::filesystem::path out = std::filesystem::absolute(a->out);
    // Read before anything is printed: a wrong --data is one error line.
    const io::RosMap reference = io::read_ros_map(a->data / "malaga_telecom_map.yaml");
    std::printf("intgrid demo: writing to %s\n", out.string().c_str());
    nlohmann::json summary;
    std::printf(
        "mapping the reference run's scans with its poses (%s), 5 cm cells, sigma %.3g m:\n",
        (a->data / "malaga_telecom_loop_reference.log").string().c_str(), a->map.model.sigma0);
    for (const core::Arithmetic arithmetic :
         {core::Arithmetic::integer, core::Arithmetic::floating}) {
      MapJobOptions o = a->map;
      o.log = a->data / "malaga_telecom_loop_reference.log";
      o.resolution = 0.05;
      o.arithmetic = arithmetic;
      o.out = out / (arithmetic == core::Arithmetic::integer ? "map_int" : "map_float");
      const MapJobResult r = run_map_job(o);
      summary[arithmetic == core::Arithmetic::integer ? "map_int" : "map_float"] =
          demo_map_section(o, r, reference);
      if (r.codec) summary["map_int"]["eps"] = r.codec->eps();
    }
    summary["slam"] = demo_slam_section(a->data, out / "slam");
    summary["globloc"] = demo_globloc_section(a->data, out / "globloc");
    std::printf("the large-FOV ISM (8-bit S_eps, eps 0.05 for the integer parts):\n");
    summary["figures"] = demo_figures_section(out / "figures");
    summary["ism_kernel"] = demo_kernel_section();
    summary["hardware"] = demo_hardware_section(a->data);
    io::write_file_atomically(out / "summary.json", summary.dump(2) + "\n");
    std::printf("wrote %s\n", (out / "summary.json").string().c_str());
  });
}

}  // namespace intgrid::cli
