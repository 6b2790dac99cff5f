#include "cli/globloc_job.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "cli/commands.hpp"
#include "cli/log_input.hpp"
#include "cli/options.hpp"
#include "cli/output_folder_option.hpp"
#include "cli/progress.hpp"
#include "intgrid/core/parallel.hpp"
#include "intgrid/core/trajectory.hpp"
#include "intgrid/figures/bitmap_font.hpp"
#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/image_io.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/log_io.hpp"
#include "intgrid/io/map_io.hpp"
#include "intgrid/io/relations_io.hpp"
#include "intgrid/io/text_io.hpp"

namespace intgrid::cli {
namespace {

constexpr double kTimeMatch = 1e-4;  // s: a reference scan at the same time as a log scan
constexpr int kPictureSide = 1200;   // pose_grid.png: at most this many pixels a side, about
constexpr io::Rgb kEstimateColor{0, 200, 0};
constexpr io::Rgb kReferenceColor{30, 90, 255};

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// "FIRST:LAST" (either side may be empty: the log's first or last scan), 0-based, inclusive.
std::pair<std::size_t, std::size_t> scan_range(const std::string& text, std::size_t scans,
                                               const std::filesystem::path& log) {
  if (text.empty()) return {0, scans - 1};
  const auto bad = [&](const std::string& why) {
    return io::InputError(log, 0, "--scans", "'" + text + "': " + why);
  };
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos || text.find(':', colon + 1) != std::string::npos)
    throw bad("expected FIRST:LAST, scan indices from 0");
  const auto number = [&](std::string_view part, std::size_t fallback) {
    if (part.empty()) return fallback;
    std::size_t value = 0;
    const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
    if (error != std::errc() || end != part.data() + part.size())
      throw bad("'" + std::string(part) + "' is not a scan index (0, 1, 2, ...)");
    return value;
  };
  const std::size_t first = number(std::string_view(text).substr(0, colon), 0);
  const std::size_t last = number(std::string_view(text).substr(colon + 1), scans - 1);
  if (first > last) throw bad("FIRST is after LAST");
  if (last >= scans)
    throw bad("the log holds " + std::to_string(scans) + " scans, 0 to " +
              std::to_string(scans - 1));
  return {first, last};
}

void check_map(const io::RosMap& map, const std::filesystem::path& file,
               const localization::GlobalLocConfig& c) {
  const bool any_free = std::any_of(map.grid.cells.begin(), map.grid.cells.end(),
                                    [&](double p) { return p < map.free_thresh; });
  if (!any_free)
    throw io::InputError(file, 0, "image",
                         "the map has no free cell (P < free_thresh " +
                             io::format_number(map.free_thresh) + "), so no pose to find");
  if (c.pose_res < map.grid.geometry.resolution)
    throw io::InputError(file, 0, "resolution",
                         "the pose-grid step --pose-cell " + io::format_number(c.pose_res) +
                             " m is finer than the map's " +
                             io::format_number(map.grid.geometry.resolution) + " m");
}

// The reference pose at time t, if the reference has one then.
std::optional<core::Pose2> reference_at(const std::vector<core::TimedPose>& reference, double t) {
  const auto it =
      std::lower_bound(reference.begin(), reference.end(), t - kTimeMatch,
                       [](const core::TimedPose& p, double time) { return p.t < time; });
  if (it != reference.end() && std::abs(it->t - t) <= kTimeMatch) return it->pose;
  return std::nullopt;
}

void write_poses(const std::filesystem::path& file, const std::vector<GlobLocScan>& scans,
                 localization::GlobalMethod method, bool track) {
  io::write_file_atomically(file, [&](std::ostream& out) {
    const bool pose_grid = method == localization::GlobalMethod::pose_grid;
    out << (track ? "# t x y theta score ambiguous scans t_first (s, m, m, rad, -, 0/1, -, s): the "
                    "robot pose at the last scan fused, from no prior at scan time t_first, by "
                  : "# t x y theta score ambiguous (s, m, m, rad, -, 0/1): the robot pose of each "
                    "localized scan, from no prior, by ")
        << global_method_name(method) << "; score: "
        << (pose_grid ? "the best hypothesis's S_eps index sum over the whole scan; ambiguous: a "
                        "second hypothesis nearly as good; then x y theta score of the next "
                        "hypotheses (--hypotheses)"
                      : "the best cell's posterior; ambiguous: 0 (the baselines do not tell)")
        << (track ? "; scans: how many were fused" : "") << '\n';
    const auto pose = [&](std::ostream& o, const core::Pose2& p, double score) {
      o << io::format_number(p.x) << ' ' << io::format_number(p.y) << ' '
        << io::format_number(p.theta) << ' ' << io::format_number(score);
    };
    for (const GlobLocScan& s : scans) {
      out << io::format_number(s.t) << ' ';
      pose(out, s.estimate.robot, s.estimate.score);
      out << ' ' << (s.ambiguous ? 1 : 0);
      if (track) out << ' ' << s.scans_fused << ' ' << io::format_number(s.first_t);
      for (std::size_t h = 1; h < s.hypotheses.size(); ++h) {
        out << ' ';
        pose(out, s.hypotheses[h].robot, s.hypotheses[h].score);
      }
      out << '\n';
    }
  });
}

// A colour from dark blue (0) through red to pale yellow (1).
io::Rgb heat_color(double v) {
  static constexpr io::Rgb kStops[] = {
      {20, 20, 90}, {110, 30, 150}, {210, 40, 80}, {250, 140, 30}, {255, 245, 160}};
  constexpr int kLast = 4;
  v = std::clamp(v, 0.0, 1.0) * kLast;
  const int i = std::min(static_cast<int>(v), kLast - 1);
  const double f = v - i;
  const auto mix = [&](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a + f * (b - a)));
  };
  return {mix(kStops[i].r, kStops[i + 1].r), mix(kStops[i].g, kStops[i + 1].g),
          mix(kStops[i].b, kStops[i + 1].b)};
}

// Faint map colours behind the pose grid: walls light grey, unknown a paler grey, free white.
io::Rgb faint_map_color(const io::RosMap& map, double x, double y) {
  const core::GridGeometry& g = map.grid.geometry;
  const int ix = g.cell_x(x), iy = g.cell_y(y);
  if (!g.contains(ix, iy)) return {255, 255, 255};
  const double p = map.grid.at(ix, iy);
  if (p >= map.occupied_thresh) return {175, 175, 175};
  if (p < map.free_thresh) return {255, 255, 255};
  return {232, 232, 232};
}

// The pose grid's best score over headings at every position, as colours over the map.
void write_pose_grid_png(const std::filesystem::path& file,
                         const localization::LocalizationMap& lmap,
                         const localization::PoseScores& scores, const io::RosMap& map,
                         const GlobLocScan& scan) {
  const int w = lmap.width(), h = lmap.height(), headings = lmap.headings();
  const bool integer = scores.method == localization::GlobalMethod::pose_grid;
  // Per position: the best over headings, as a double; -inf where no heading is a candidate.
  const double none = -std::numeric_limits<double>::infinity();
  std::vector<double> best(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), none);
  for (int k = 0; k < headings; ++k)
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const std::size_t q = lmap.index(i, j, k);
        double v = none;
        if (integer) {
          if (q < scores.index_sum.size() &&
              scores.index_sum[q] != std::numeric_limits<std::int32_t>::min())
            v = scores.index_sum[q];
        } else if (q < scores.posterior.size() && scores.posterior[q] > 0.0) {
          v = std::log(scores.posterior[q]);
        }
        double& b = best[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + i];
        b = std::max(b, v);
      }
  double hi = none, lo = std::numeric_limits<double>::infinity();
  for (const double v : best)
    if (v > none) hi = std::max(hi, v), lo = std::min(lo, v);
  // Posteriors span hundreds of orders of magnitude: show the top 30 nepers of log posterior.
  if (!integer) lo = std::max(lo, hi - 30.0);

  const int ppc = std::clamp(kPictureSide / std::max(w, h), 1, 8);
  const core::Pose2 corner = lmap.pose_of(0, 0, 0);
  const double res = lmap.config().pose_res;
  const core::GridGeometry pixels{w * ppc, h * ppc, res / ppc, corner.x - 0.5 * res,
                                  corner.y - 0.5 * res};
  constexpr int kCaptionLines = 3;
  io::RgbImage image(pixels.width, pixels.height + kCaptionLines * figures::kLineAdvance + 8);
  for (int py = 0; py < pixels.height; ++py)
    for (int px = 0; px < pixels.width; ++px) {
      const int i = px / ppc, j = h - 1 - py / ppc;
      const double v = best[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + i];
      if (v > none) {
        image.set(px, py, heat_color(hi > lo ? (v - lo) / (hi - lo) : 1.0));
      } else {
        const double x = pixels.origin_x + (px + 0.5) * pixels.resolution;
        const double y = pixels.origin_y + (pixels.height - py - 0.5) * pixels.resolution;
        image.set(px, py, faint_map_color(map, x, y));
      }
    }
  const auto mark = [&](const core::Pose2& p, io::Rgb color) {
    const double length = std::max(1.0, 3.0 * res);
    io::draw_polyline_world(
        image, pixels, {p, {p.x + length * std::cos(p.theta), p.y + length * std::sin(p.theta), 0}},
        color);
    io::draw_marker_world(image, pixels, p.x, p.y, std::max(5, 2 * ppc), color);
  };
  if (scan.reference) mark(*scan.reference, kReferenceColor);
  mark(scan.estimate.robot, kEstimateColor);

  char line[3][200];
  std::snprintf(line[0], sizeof line[0],
                "scan %zu (t %.3f s), %zu readings, %s: best over %d "
                "headings of each %.3g m cell",
                scan.index, scan.t, scan.readings, global_method_name(scores.method), headings,
                res);
  std::snprintf(line[1], sizeof line[1],
                integer ? "dark blue: index sum %.0f ... pale yellow: %.0f; grey: the map, "
                          "no candidate pose"
                        : "dark blue: log posterior %.1f ... pale yellow: %.1f; grey: the map, "
                          "no candidate pose",
                lo, hi);
  std::snprintf(line[2], sizeof line[2], "green: estimate (robot, heading line)%s",
                scan.reference ? "; blue: reference pose" : "");
  for (int n = 0; n < kCaptionLines; ++n)
    figures::draw_text(image, 4, pixels.height + 4 + n * figures::kLineAdvance, line[n], {0, 0, 0});
  io::write_png(file, image);
}

// The share of a scan's usable readings whose endpoint, seen from the robot pose `robot`, lies
// within kFitCells map cells of an occupied map cell: a check of a pose against the map that no
// localizer's score enters, so that a miss can be told apart from a reference the map disagrees
// with.
constexpr double kFitCells = 1.5;

double endpoint_fit(const localization::LocalizationMap& map, const core::Scan& scan,
                    const core::Pose2& robot, double cell, double max_range) {
  const std::vector<localization::RangeReading> readings =
      localization::readings_of(scan, 0, max_range);
  const core::Pose2 sensor = core::compose(robot, scan.sensor_mount);
  std::size_t near = 0;
  for (const localization::RangeReading& r : readings) {
    const double a = sensor.theta + r.bearing;
    near += map.distance_to_occupied(sensor.x + r.range * std::cos(a),
                                     sensor.y + r.range * std::sin(a)) <= kFitCells * cell
                ? 1
                : 0;
  }
  return readings.empty() ? 0.0 : double(near) / double(readings.size());
}

struct TrackResult {
  localization::PoseSearchResult found;
  std::size_t last = 0;   // the last scan fused
  std::size_t scans = 0;  // scans fused
};

// Localization from a sequence: scan `first` and the scans after it, as SequenceLocalizer takes
// them, until the answer is unambiguous or o.track are fused.
TrackResult track_from(const localization::LocalizationMap& map, const core::Log& log,
                       std::size_t first, const localization::PoseSearchOptions& search,
                       const GlobLocJobOptions& o, localization::PoseScores* scores) {
  localization::SequenceOptions sequence = o.sequence;
  sequence.max_scans = o.track;
  std::optional<localization::SequenceLocalizer> localizer;
  naming_flags(global_loc_flags(), [&] { localizer.emplace(map, search, sequence); });
  TrackResult r;
  for (std::size_t j = first; !localizer->done() && j < log.scans.size(); ++j)
    if (std::optional<localization::PoseSearchResult> found = localizer->offer(log.scans[j])) {
      r.found = std::move(*found);
      r.last = j;
    }
  r.scans = localizer->scans();
  if (scores) *scores = localizer->fused_scores();
  return r;
}

}  // namespace

const char* global_method_name(localization::GlobalMethod method) {
  switch (method) {
    case localization::GlobalMethod::pose_grid:
      return "pog";
    case localization::GlobalMethod::markov:
      return "markov";
    case localization::GlobalMethod::markov_mixture:
      return "markov-mixture";
    case localization::GlobalMethod::likelihood_field:
      return "likelihood-field";
  }
  return "?";
}

GlobLocJobResult run_globloc_job(const GlobLocJobOptions& o) {
  check_global_loc_options(o.config);
  if (o.every == 0) bad_option("--every", "must be at least 1");
  const io::RosMap map = io::read_ros_map(o.map);
  const LogInput input = read_log_input(o.log);
  const core::Log& log = input.log;
  if (log.scans.empty()) throw io::InputError(o.log, 0, "scans", "the log holds no scan");
  if (o.reference && o.reference_trajectory)
    bad_option("--reference-trajectory", "is given with --reference: one reference a run");
  if (!(o.position_tolerance > 0.0) || !(o.heading_tolerance > 0.0))
    bad_option("--tolerance", "must be positive");
  if (o.track > 0 && o.method != localization::GlobalMethod::pose_grid)
    bad_option("--track", "fuses scans with the pose grid only (--method pog)");
  naming_flags(global_loc_flags(), [&] { localization::check_sequence_options(o.sequence); });
  std::optional<std::vector<core::TimedPose>> reference;
  const std::optional<std::filesystem::path>& reference_file =
      o.reference ? o.reference : o.reference_trajectory;
  if (o.reference) {
    const core::Log log_reference = io::read_log(*o.reference);
    if (log_reference.scans.empty())
      throw io::InputError(*o.reference, 0, "scans", "the reference log holds no scan");
    reference.emplace();
    for (const core::Scan& scan : log_reference.scans) reference->push_back({scan.t, scan.robot});
    std::stable_sort(reference->begin(), reference->end(),
                     [](const core::TimedPose& a, const core::TimedPose& b) { return a.t < b.t; });
  } else if (o.reference_trajectory) {
    reference = io::read_trajectory(*o.reference_trajectory);
  }
  const auto [first, last] = scan_range(o.scans, log.scans.size(), o.log);
  check_map(map, o.map, o.config);
  io::OutputFolder out = open_output_folder(o.out);

  // The selected scans' readings, before any work on the map.
  struct Job {
    std::size_t index;
    std::vector<localization::RangeReading> readings, verification;
  };
  std::vector<Job> jobs;
  GlobLocJobResult r;
  for (std::size_t i = first; i <= last; i += o.every) {
    std::vector<localization::RangeReading> readings =
        localization::readings_of(log.scans[i], o.sequence.beams, o.config.sensor.max_range);
    if (readings.empty())
      ++r.skipped_scans;
    else  // the verification readings are the pose grid's alone
      jobs.push_back({i, std::move(readings),
                      o.method == localization::GlobalMethod::pose_grid
                          ? localization::readings_of(log.scans[i], o.sequence.verify_beams,
                                                      o.config.sensor.max_range)
                          : std::vector<localization::RangeReading>{}});
  }
  if (jobs.empty())
    throw io::InputError(
        o.log, 0, "ranges",
        "no selected scan holds a valid reading (finite, > 0, below the scan's and "
        "the --max-range " +
            io::format_number(o.config.sensor.max_range) + " m maximum range)");

  localization::PoseSearchOptions search = o.search;
  search.threads = core::threads_or_every_core(search.threads);
  naming_flags(pose_search_flags(), [&] { localization::check_pose_search_options(search); });

  const auto map_start = Clock::now();
  std::optional<localization::LocalizationMap> lmap;
  try {
    lmap.emplace(map.grid, map.occupied_thresh, map.free_thresh, o.config);
  } catch (const std::invalid_argument& e) {
    // The pose grid's options (a lattice too big for the map: --pose-cell), else the map's.
    if (std::string_view(e.what()).starts_with("pose_res") ||
        std::string_view(e.what()).starts_with("memory_limit"))
      rethrow_naming_flags(e, global_loc_flags());
    throw io::InputError(o.map, 0, "image", e.what());
  }
  r.map_seconds = seconds_since(map_start);

  localization::PoseScores first_scores;
  {
    TerminalProgress progress(std::string("globloc (") + global_method_name(o.method) + ")");
    for (std::size_t n = 0; n < jobs.size(); ++n) {
      const core::Scan& scan = log.scans[jobs[n].index];
      GlobLocScan s;
      s.index = s.first_index = jobs[n].index;
      s.t = s.first_t = scan.t;
      s.readings = jobs[n].readings.size();
      const auto start = Clock::now();
      localization::PoseScores* scores = n == 0 ? &first_scores : nullptr;
      if (o.method == localization::GlobalMethod::pose_grid && o.track > 0) {
        const TrackResult tracked = track_from(*lmap, log, jobs[n].index, search, o, scores);
        s.index = tracked.last;
        s.t = log.scans[tracked.last].t;
        s.scans_fused = tracked.scans;
        s.estimate = tracked.found.estimate;
        s.hypotheses = tracked.found.hypotheses;
        s.ambiguous = tracked.found.ambiguous;
        r.ambiguous += s.ambiguous ? 1 : 0;
      } else if (o.method == localization::GlobalMethod::pose_grid) {
        localization::PoseSearchResult found = localization::search_pose_grid(
            *lmap, jobs[n].readings, jobs[n].verification, scan.sensor_mount, search, scores);
        s.estimate = found.estimate;
        s.hypotheses = std::move(found.hypotheses);
        s.ambiguous = found.ambiguous;
        r.ambiguous += found.ambiguous ? 1 : 0;
      } else {
        s.estimate = naming_flags(global_loc_flags(), [&] {
          return localization::localize_global(*lmap, jobs[n].readings, scan.sensor_mount, o.method,
                                               scores);
        });
      }
      s.seconds = seconds_since(start);
      r.seconds += s.seconds;
      if (reference) {
        s.reference = reference_at(*reference, s.t);
        if (s.reference) {
          ++r.matched;
          const double dx = s.estimate.robot.x - s.reference->x;
          const double dy = s.estimate.robot.y - s.reference->y;
          s.found = std::hypot(dx, dy) <= o.position_tolerance &&
                    std::abs(core::wrap_angle(s.estimate.robot.theta - s.reference->theta)) <=
                        o.heading_tolerance;
          r.found += s.found ? 1 : 0;
          if (!s.found) {
            const double cell = map.grid.geometry.resolution;
            s.endpoint_fit = {endpoint_fit(*lmap, log.scans[s.index], s.estimate.robot, cell,
                                           o.config.sensor.max_range),
                              endpoint_fit(*lmap, log.scans[s.index], *s.reference, cell,
                                           o.config.sensor.max_range)};
          }
          if (!s.found && o.method == localization::GlobalMethod::pose_grid && o.track == 0 &&
              o.config.refine_levels > 0)
            s.reference_score =
                localization::refine_pose(*lmap, jobs[n].readings, jobs[n].verification,
                                          core::compose(*s.reference, scan.sensor_mount),
                                          scan.sensor_mount)
                    .score;
        }
      }
      r.scans.push_back(s);
      if (o.progress) progress(n + 1, jobs.size());
    }
  }

  const localization::GlobalLocConfig& c = o.config;
  std::size_t readings = 0;
  for (const GlobLocScan& s : r.scans) readings += s.readings;
  r.metrics = {
      {"map", o.map.string()},
      {"log", o.log.string()},
      {"skipped_records", skipped_records_json(input.skipped)},
      {"method", global_method_name(o.method)},
      {"settings",
       {{"pose_res", c.pose_res},
        {"headings", c.headings},
        {"beams", o.sequence.beams},
        {"sigma", c.sensor.sigma},
        {"max_range", c.sensor.max_range},
        {"seps_bits", c.seps_bits},
        {"seps_levels", c.seps_levels},
        {"veto_levels", c.veto_levels},
        {"scans", std::to_string(first) + ":" + std::to_string(last)},
        {"every", o.every},
        {"verify_beams", o.sequence.verify_beams},
        {"hypotheses", search.hypotheses},
        {"verified", search.verified},
        {"ambiguity_levels", search.ambiguity_levels},
        {"threads", search.threads},
        {"refine_levels", c.refine_levels},
        {"grazing_hits", c.grazing_hits},
        {"track", o.track},
        {"track_step",
         {o.sequence.step_position, o.sequence.step_heading * 180.0 / std::numbers::pi}},
        {"max_memory_mb", static_cast<double>(c.memory_limit) / 1e6}}},
      {"pose_grid",
       {{"width", lmap->width()},
        {"height", lmap->height()},
        {"headings", lmap->headings()},
        {"pose_cells", lmap->pose_cells()},
        {"candidate_cells", lmap->candidate_cells()},
        {"bytes_per_candidate_pose_cell",
         localization::LocalizationMap::kBytesPerCandidatePoseCell},
        {"memory_mb", static_cast<double>(lmap->memory_bytes()) / 1e6}}},
      {"scans", r.scans.size()},
      {"skipped_scans", r.skipped_scans},
      {"ambiguous_scans", r.ambiguous},
      {"mean_readings", static_cast<double>(readings) / static_cast<double>(r.scans.size())},
      {"map_seconds", r.map_seconds},
      {"seconds", r.seconds},
      {"seconds_per_scan", r.seconds / static_cast<double>(r.scans.size())}};
  if (o.track > 0) {
    // How many scans the answers took: a user's robot waits that long.
    std::vector<std::size_t> fused;
    std::size_t unambiguous_scans = 0;
    for (const GlobLocScan& s : r.scans) {
      fused.push_back(s.scans_fused);
      unambiguous_scans += s.ambiguous ? 0 : 1;
    }
    std::sort(fused.begin(), fused.end());
    double total = 0.0;
    for (const std::size_t f : fused) total += double(f);
    r.metrics["track"] = {{"localizations", fused.size()},
                          {"unambiguous", unambiguous_scans},
                          {"mean_scans", total / double(fused.size())},
                          {"median_scans", fused[fused.size() / 2]},
                          {"most_scans", fused.back()}};
    r.metrics["seconds_per_localization"] = r.metrics["seconds_per_scan"];
  }
  if (reference) {
    std::vector<double> position_errors;
    for (const GlobLocScan& s : r.scans)
      if (s.reference)
        position_errors.push_back(
            std::hypot(s.estimate.robot.x - s.reference->x, s.estimate.robot.y - s.reference->y));
    std::sort(position_errors.begin(), position_errors.end());
    nlohmann::json ref = {
        {"file", reference_file->string()},
        {"position_tolerance_m", o.position_tolerance},
        {"heading_tolerance_deg", o.heading_tolerance * 180.0 / std::numbers::pi},
        {"matched", r.matched},
        {"within", r.found},
        {"share",
         r.matched ? nlohmann::json(static_cast<double>(r.found) / static_cast<double>(r.matched))
                   : nlohmann::json()},
        {"median_position_error_m",
         position_errors.empty() ? nlohmann::json()
                                 : nlohmann::json(position_errors[position_errors.size() / 2])}};
    // The scans not found, with what the pose grid said of them: a user checks whether the
    // misses were flagged.
    nlohmann::json misses = nlohmann::json::array();
    for (const GlobLocScan& s : r.scans)
      if (s.reference && !s.found)
        misses.push_back(
            {{"scan", s.index},
             {"first_scan", s.first_index},
             {"scans_fused", s.scans_fused},
             {"t", s.t},
             {"position_error_m",
              std::hypot(s.estimate.robot.x - s.reference->x, s.estimate.robot.y - s.reference->y)},
             {"heading_error_deg",
              std::abs(core::wrap_angle(s.estimate.robot.theta - s.reference->theta)) * 180.0 /
                  std::numbers::pi},
             {"ambiguous", s.ambiguous},
             {"endpoints_near_occupied",
              {{"answer", s.endpoint_fit->first}, {"reference", s.endpoint_fit->second}}}});
    std::size_t reference_fits_better = 0;
    for (const GlobLocScan& s : r.scans)
      if (s.endpoint_fit) reference_fits_better += s.endpoint_fit->second > s.endpoint_fit->first;
    ref["misses_where_the_endpoints_fit_the_reference_better"] = reference_fits_better;
    std::size_t scores_answer_higher = 0;
    for (std::size_t m = 0, i = 0; i < r.scans.size(); ++i) {
      const GlobLocScan& s = r.scans[i];
      if (!s.reference || s.found) continue;
      if (s.reference_score) {
        misses[m]["score"] = s.estimate.score;
        misses[m]["reference_score"] = *s.reference_score;
        scores_answer_higher += s.estimate.score > double(*s.reference_score) ? 1 : 0;
      }
      ++m;
    }
    ref["misses"] = misses;
    if (o.method == localization::GlobalMethod::pose_grid && o.track == 0 &&
        o.config.refine_levels > 0)
      ref["misses_where_the_pose_grid_scores_the_answer_higher"] = scores_answer_higher;
    std::size_t ambiguous_matched = 0, ambiguous_found = 0;
    for (const GlobLocScan& s : r.scans)
      if (s.reference && s.ambiguous) ++ambiguous_matched, ambiguous_found += s.found ? 1 : 0;
    ref["ambiguous_matched"] = ambiguous_matched;
    ref["ambiguous_within"] = ambiguous_found;
    r.metrics["reference"] = ref;
  }

  write_poses(out.file("poses.txt"), r.scans, o.method, o.track > 0);
  write_pose_grid_png(out.file("pose_grid.png"), *lmap, first_scores, map, r.scans.front());
  io::write_file_atomically(out.file("metrics.json"), r.metrics.dump(2) + "\n");
  out.commit();
  return r;
}

}  // namespace intgrid::cli
