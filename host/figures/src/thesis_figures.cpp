#include "intgrid/figures/thesis_figures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "intgrid/core/footprint.hpp"
#include "intgrid/core/mapping.hpp"
#include "intgrid/core/narrow_ism.hpp"
#include "intgrid/core/polar_mapping.hpp"
#include "intgrid/core/sectoral_ism.hpp"
#include "intgrid/figures/bitmap_font.hpp"
#include "intgrid/figures/figure_layout.hpp"
#include "intgrid/figures/polar_render.hpp"
#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/image_io.hpp"
#include "intgrid/io/text_io.hpp"
#include "intgrid/kernel/ism_kernel.hpp"

namespace intgrid::figures {
namespace {

namespace fs = std::filesystem;

constexpr io::Rgb kInk{0, 0, 0};
constexpr io::ProbabilityScale kScale = io::ProbabilityScale::diverging;

std::string scale_caption() {
  return io::printed(
      "colour: P(occupied) on a linear diverging scale, white = 1/2, blue = free, red = "
      "occupied, saturated at |P - 1/2| >= %g",
      io::kDivergingSaturation);
}

FigureFiles figure_files(const fs::path& png, const char* data_extension) {
  if (png.extension() != ".png")
    throw std::invalid_argument("the figure's file name must end in .png: " + png.string());
  return {png, fs::path(png).replace_extension(data_extension)};
}

// Three pixels wide: the polyline drawn again one pixel off in each direction.
void draw_thick_polyline(io::RgbImage& image, const core::GridGeometry& geometry,
                         const std::vector<core::Pose2>& points, io::Rgb color) {
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      std::vector<core::Pose2> shifted = points;
      for (core::Pose2& p : shifted) {
        p.x += dx * geometry.resolution;
        p.y += dy * geometry.resolution;
      }
      io::draw_polyline_world(image, geometry, shifted, color);
    }
  }
}

// Points on the circle of radius around centre, from angle `from` to `to` off its heading.
std::vector<core::Pose2> arc(const core::Pose2& centre, double radius, double from, double to) {
  constexpr int kSteps = 64;
  std::vector<core::Pose2> points;
  for (int i = 0; i <= kSteps; ++i) {
    const core::Vec2 u = core::unit_vector(centre.theta + from + (to - from) * i / kSteps);
    points.push_back({centre.x + radius * u.x, centre.y + radius * u.y, 0.0});
  }
  return points;
}

// --- Figure 2.12: the sectoral decomposition -------------------------------------------

constexpr double kSweepFovDegrees = 30.0;
constexpr int kSweepRings = 40;
constexpr int kSweepBins = 30;  // divisible by every Ns shown
constexpr double kSweepCell = 0.05;
constexpr std::array<int, 5> kSweepSectors{kSweepBins, 1, 3, 5, 10};
constexpr double kSweepMetresPerPixel = kSweepCell / 10.0;

core::SectoralGrid sweep_grid(int sectors) {
  return {radians(kSweepFovDegrees), kSweepRings, kSweepBins, sectors, kSweepCell};
}

// The cone, the sensor at its apex and an obstacle across the middle third of the FOV at z.
io::RgbImage sweep_scene(const PolarFrame& frame, const core::SectoralGrid& grid, double z) {
  const std::vector<double> unknown(grid.cells(), 0.5);
  io::RgbImage scene = render_polar(frame, grid, unknown, kScale);
  draw_thick_polyline(scene, frame.geometry, arc(frame.sensor, z, -grid.fov / 6, grid.fov / 6),
                      kInk);
  io::draw_marker_world(scene, frame.geometry, frame.sensor.x, frame.sensor.y, 3, kInk);
  return scene;
}

// --- Figure 2.13: multi-sensor fusion ----------------------------------------------------

constexpr double kWorldCell = 0.05;
const core::GridGeometry kWorld{60, 60, kWorldCell, 0.0, 0.0};  // 3 m x 3 m
constexpr int kWorldPixelsPerCell = 5;
constexpr double kPolarMetresPerPixel = kWorldCell / 8.0;
constexpr double kBeamWidthDegrees = 2.0;
constexpr core::GaussianBeamModel kBeamModel{0.02, 0.0};

// The geometry of a grid's picture at pixels_per_cell, for drawing over it in world
// coordinates.
core::GridGeometry picture_geometry(const core::GridGeometry& g, int pixels_per_cell) {
  return {g.width * pixels_per_cell, g.height * pixels_per_cell, g.resolution / pixels_per_cell,
          g.origin_x, g.origin_y};
}

struct Segment {
  core::Vec2 a;
  core::Vec2 b;
};
const Segment kWall{{1.1, 1.5}, {1.6, 1.5}};

// Cuts [low, high] down to the t where the linear f(t) = f0 + t (f1 - f0) is >= 0.
void clip_to_non_negative(double f0, double f1, double& low, double& high) {
  if (f0 >= 0.0 && f1 >= 0.0) return;
  if (f0 < 0.0 && f1 < 0.0) {
    high = low - 1.0;
    return;
  }
  const double root = f0 / (f0 - f1);
  if (f0 < 0.0)
    low = std::max(low, root);
  else
    high = std::min(high, root);
}

// The reading of a nearest-target sensor: the distance to the nearest point of the segment
// inside its FOV (a wedge narrower than pi about its heading), if any.
std::optional<double> nearest_in_fov(const core::Pose2& sensor, double fov, const Segment& s) {
  const core::Vec2 from = core::unit_vector(sensor.theta - 0.5 * fov),
                   to = core::unit_vector(sensor.theta + 0.5 * fov);
  const core::Vec2 a{s.a.x - sensor.x, s.a.y - sensor.y}, b{s.b.x - sensor.x, s.b.y - sensor.y};
  double low = 0.0, high = 1.0;
  clip_to_non_negative(core::cross(from, a), core::cross(from, b), low, high);
  clip_to_non_negative(-core::cross(to, a), -core::cross(to, b), low, high);
  if (low > high) return std::nullopt;
  const core::Vec2 d{b.x - a.x, b.y - a.y};
  const double t = std::clamp(-core::dot(a, d) / core::dot(d, d), low, high);
  return std::hypot(a.x + t * d.x, a.y + t * d.y);
}

// A sensor of the scene and what it makes of its reading of the wall.
struct FusionSensor {
  std::string name;
  io::Rgb color;
  core::Pose2 pose;
  core::SectoralGrid polar;
  double reading = 0.0;  // metres
  nlohmann::json description;
  std::vector<double> ism;            // P(occupied), ring-major
  std::vector<std::int16_t> indices;  // S_eps, ring-major

  FusionSensor(std::string sensor_name, io::Rgb sensor_color, const core::Pose2& sensor_pose,
               const core::SectoralGrid& sensor_polar, const Segment& wall)
      : name(std::move(sensor_name)), color(sensor_color), pose(sensor_pose), polar(sensor_polar) {
    const std::optional<double> z = nearest_in_fov(pose, polar.fov, wall);
    if (!z) throw std::logic_error("fusion figure: sensor " + name + " does not see the wall");
    reading = *z;
    description = {{"pose", {pose.x, pose.y, pose.theta}},
                   {"polar_grid", polar_grid_json(polar)},
                   {"reading_m", reading}};
  }
};

// Sensor A: a narrow Gaussian beam on a column of cell centres (narrower than a cell, it maps
// onto that column only), looking straight at the wall; its indices quantize its ISM
// conservatively.
FusionSensor narrow_sensor(const core::SepsCodec& codec) {
  const core::GaussianBeamModel& model = kBeamModel;
  FusionSensor s("A", {230, 120, 0}, {1.325, 0.3, 0.5 * std::numbers::pi},
                 core::SectoralGrid{radians(kBeamWidthDegrees), 40, 1, 1, kWorldCell}, kWall);
  s.description["model"] = {
      {"kind", "gaussian beam"}, {"sigma0", model.sigma0}, {"k_d", model.k_d}};
  s.ism = core::narrow_ism(model, s.reading, s.polar.cell, static_cast<std::size_t>(s.polar.rings));
  for (const double p : s.ism)
    s.indices.push_back(static_cast<std::int16_t>(codec.quantize_conservative(p)));
  return s;
}

// Sensor B: the default cone 0.4 m to A's side, looking at the wall's centre; its indices
// come from the integer ISM kernel.
FusionSensor cone_sensor(const core::SepsCodec& codec) {
  const core::ConeSensorModel model;
  const core::Vec2 at{1.725, 0.3};
  const double heading =
      std::atan2(0.5 * (kWall.a.y + kWall.b.y) - at.y, 0.5 * (kWall.a.x + kWall.b.x) - at.x);
  FusionSensor s("B", {110, 50, 160}, {at.x, at.y, heading}, core::SectoralGrid{}, kWall);
  s.description["model"] = {{"kind", "cone"},
                            {"sigma0", model.sigma0},
                            {"k_d", model.k_d},
                            {"k_theta", model.k_theta},
                            {"k_size", model.k_size}};
  s.ism = core::sectoral_ism(model, s.polar, s.reading);
  const kernel::IsmKernelTables kernel = kernel::make_ism_kernel(model, s.polar, codec);
  const std::uint32_t reading = kernel::quantize_reading(kernel, s.reading);
  s.indices = kernel::ism_kernel_indices(kernel, reading);
  s.description["kernel_reading_m"] = kernel::reading_metres(kernel, reading);
  return s;
}

// The world and both sensors: FOV edges out to the last ring, the point each one reads.
io::RgbImage fusion_scene(const std::vector<FusionSensor>& sensors) {
  const core::GridGeometry g = picture_geometry(kWorld, kWorldPixelsPerCell);
  io::RgbImage scene(g.width, g.height);
  // Half-metre lines, for scale.
  const double left = kWorld.origin_x, bottom = kWorld.origin_y;
  const double right = left + kWorld.width * kWorld.resolution;
  const double top = bottom + kWorld.height * kWorld.resolution;
  for (double x = left + 0.5; x < right; x += 0.5)
    io::draw_polyline_world(scene, g, {{x, bottom, 0.0}, {x, top, 0.0}}, {225, 225, 225});
  for (double y = bottom + 0.5; y < top; y += 0.5)
    io::draw_polyline_world(scene, g, {{left, y, 0.0}, {right, y, 0.0}}, {225, 225, 225});
  draw_thick_polyline(scene, g, {{kWall.a.x, kWall.a.y, 0.0}, {kWall.b.x, kWall.b.y, 0.0}}, kInk);
  for (const FusionSensor& s : sensors) {
    const double reach = (s.polar.rings + 0.5) * s.polar.cell;
    for (const double side : {-0.5, 0.5}) {
      const core::Vec2 u = core::unit_vector(s.pose.theta + side * s.polar.fov);
      io::draw_polyline_world(
          scene, g, {s.pose, {s.pose.x + reach * u.x, s.pose.y + reach * u.y, 0.0}}, s.color);
    }
    io::draw_polyline_world(scene, g, arc(s.pose, s.reading, -0.5 * s.polar.fov, 0.5 * s.polar.fov),
                            s.color);
    io::draw_marker_world(scene, g, s.pose.x, s.pose.y, 4, s.color);
    draw_text(scene, g.cell_x(s.pose.x) + 8, g.height - 1 - g.cell_y(s.pose.y), s.name, s.color, 2);
  }
  return scene;
}

io::RgbImage world_panel(const core::ProbabilityGrid& grid,
                         const std::vector<FusionSensor>& sensors) {
  io::RgbImage image = io::render_probability_grid(grid, kScale, kWorldPixelsPerCell);
  const core::GridGeometry pixels = picture_geometry(kWorld, kWorldPixelsPerCell);
  for (const FusionSensor& s : sensors)
    io::draw_marker_world(image, pixels, s.pose.x, s.pose.y, 3, s.color);
  return image;
}

nlohmann::json grid_summary(const core::ProbabilityGrid& grid) {
  std::size_t above = 0, below = 0;
  for (const double p : grid.cells) {
    above += p > 0.5 ? 1 : 0;
    below += p < 0.5 ? 1 : 0;
  }
  const auto [low, high] = std::minmax_element(grid.cells.begin(), grid.cells.end());
  return {{"cells", grid.cells.size()},
          {"informed", above + below},
          {"above_one_half", above},
          {"below_one_half", below},
          {"min_p", *low},
          {"max_p", *high}};
}

nlohmann::json index_grid_summary(const core::Grid<std::int16_t>& grid,
                                  const core::SepsCodec& codec) {
  nlohmann::json summary = grid_summary(core::to_probabilities(grid, codec));
  const auto [low, high] = std::minmax_element(grid.cells.begin(), grid.cells.end());
  summary["min_index"] = *low;
  summary["max_index"] = *high;
  return summary;
}

}  // namespace

FigureFiles write_ns_sweep_figure(const fs::path& png, double z) {
  const FigureFiles files = figure_files(png, ".csv");
  const core::ConeSensorModel model;
  const PolarFrame frame = polar_frame(sweep_grid(1), kSweepMetresPerPixel);
  std::vector<Panel> panels;
  panels.push_back(
      {io::printed("(a) scene:\nobstacle at %g m", z), sweep_scene(frame, sweep_grid(1), z)});
  std::vector<std::vector<double>> isms;
  for (const int sectors : kSweepSectors) {
    const core::SectoralGrid grid = sweep_grid(sectors);
    isms.push_back(core::sectoral_ism(model, grid, z));
    const char letter = static_cast<char>('a' + panels.size());
    panels.push_back({sectors == kSweepBins
                          ? io::printed("(%c) exact\n(Ns = A = %d)", letter, kSweepBins)
                          : io::printed("(%c) Ns = %d", letter, sectors),
                      render_polar(frame, grid, isms.back(), kScale)});
  }
  const io::RgbImage figure = compose_figure(
      "Large-FOV ISM with sectoral decomposition (thesis figure 2.12)", {panels}, kScale,
      {io::printed(
           "FOV %g deg, A = %d bins, R = %d rings of %g cm, cone model sigma0 %g cm, k_d %g, "
           "k_theta %g, k_size %g; reading z = %g m",
           kSweepFovDegrees, kSweepBins, kSweepRings, 100 * kSweepCell, 100 * model.sigma0,
           model.k_d, model.k_theta, model.k_size, z),
       scale_caption(),
       io::printed(
           "With prior 1/2 and %d cells a ring, no cell rises visibly above 1/2: the sensor",
           kSweepBins),
       "tells the free space before the obstacle, and Ns how finely across the FOV."});
  io::write_png(files.image, figure);
  io::write_file_atomically(files.data, [&](std::ostream& csv) {
    csv << "ns,ring,bin,p\n";
    for (std::size_t i = 0; i < kSweepSectors.size(); ++i)
      write_polar_csv_rows(csv, std::to_string(kSweepSectors[i]) + ",",
                           sweep_grid(kSweepSectors[i]), isms[i]);
  });
  return files;
}

FigureFiles write_fusion_figure(const fs::path& png) {
  const FigureFiles files = figure_files(png, ".json");
  const core::SepsCodec codec(8, 0.05);
  const std::vector<FusionSensor> sensors{narrow_sensor(codec), cone_sensor(codec)};
  const FusionSensor &a = sensors[0], &b = sensors[1];
  std::vector<Panel> polar_panels{{"(I) scene", fusion_scene(sensors)}};
  std::vector<Panel> world_panels;
  std::vector<core::ProbabilityGrid> grids;
  std::vector<core::Grid<std::int16_t>> index_grids;
  nlohmann::json summary = {
      {"world",
       {{"width", kWorld.width}, {"height", kWorld.height}, {"resolution", kWorld.resolution}}},
      {"codec", {{"bits", codec.bits()}, {"eps", codec.eps()}}}};
  for (const FusionSensor& s : sensors) {
    polar_panels.push_back(
        {"(II) ISM of " + s.name,
         render_polar(polar_frame(s.polar, kPolarMetresPerPixel), s.polar, s.ism, kScale)});
    grids.push_back(core::map_polar<double>(kWorld, s.pose, s.polar, s.ism, 0.5));
    index_grids.push_back(core::map_polar<std::int16_t>(kWorld, s.pose, s.polar, s.indices, 0));
    world_panels.push_back({"(III) grid of " + s.name, world_panel(grids.back(), sensors)});
    summary["sensors"][s.name] = s.description;
    summary["grids"][s.name + "_double"] = grid_summary(grids.back());
    summary["grids"][s.name + "_seps"] = index_grid_summary(index_grids.back(), codec);
  }
  const core::ProbabilityGrid fused = core::fuse_grids(grids[0], grids[1]);
  const core::Grid<std::int16_t> fused_indices =
      core::fuse_grids(index_grids[0], index_grids[1], codec.max_index());
  world_panels.push_back({"(IV) fused,\ndouble", world_panel(fused, sensors)});
  world_panels.push_back({io::printed("(IV) fused,\nS_eps %d bits", codec.bits()),
                          world_panel(core::to_probabilities(fused_indices, codec), sensors)});
  summary["grids"]["fused_double"] = grid_summary(fused);
  summary["grids"]["fused_seps"] = index_grid_summary(fused_indices, codec);

  const io::RgbImage figure = compose_figure(
      "Multi-sensor fusion (thesis figure 2.13): a wall seen by a narrow and a cone sensor",
      {polar_panels, world_panels}, kScale,
      {io::printed("A: %g-degree Gaussian beam, sigma %g cm, reads %.3f m; B: the default cone "
                   "(FOV %g deg, A %d, Ns %d), reads %.3f m",
                   kBeamWidthDegrees, 100 * kBeamModel.sigma0, a.reading, degrees(b.polar.fov),
                   b.polar.bins, b.polar.sectors, b.reading),
       io::printed("(II) each ISM in its polar grid of %g cm rings; (III) range-mapped onto %g cm "
                   "world cells",
                   100 * kWorldCell, 100 * kWorldCell),
       io::printed("(IV) Bayes F(p, q) in double; %d-bit S_eps (eps %g) index addition, A's "
                   "indices quantized from its ISM, B's from the integer kernel",
                   codec.bits(), codec.eps()),
       scale_caption()});
  io::write_png(files.image, figure);
  io::write_file_atomically(files.data, summary.dump(2) + "\n");
  return files;
}

}  // namespace intgrid::figures
