#include "cli/commands.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include "cli/globloc_job.hpp"
#include "cli/hardware_summary.hpp"
#include "cli/install_paths.hpp"
#include "cli/kernel_agreement.hpp"
#include "cli/map_job.hpp"
#include "cli/slam_job.hpp"
#include "intgrid/core/map_compare.hpp"
#include "intgrid/figures/thesis_figures.hpp"
#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/map_io.hpp"

namespace intgrid::cli {

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

// Both SLAM engines on the real log in both arithmetics, scored against the reference trajectory:
// the default (submaps, chosen on the Freiburg logs) beside the thesis's event-driven grid SLAM
// (chosen on this log), so that the demo shows which one holds here.
nlohmann::json demo_slam_section(const std::filesystem::path& data,
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
nlohmann::json demo_globloc_section(const std::filesystem::path& data,
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
      o.config.pose_res, o.config.headings, o.sequence.beams);
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

}  // namespace

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
