#include "intgrid/figures/polar_render.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "intgrid/core/polar_mapping.hpp"

namespace intgrid::figures {
namespace {

// 200 MB of RGB: far past any useful picture, short of exhausting memory.
constexpr double kMaxPolarPixels = double(1 << 26);

}  // namespace

nlohmann::json polar_grid_json(const core::SectoralGrid& grid) {
  return {{"fov_deg", degrees(grid.fov)},
          {"rings", grid.rings},
          {"bins", grid.bins},
          {"sectors", grid.sectors},
          {"cell", grid.cell}};
}

PolarFrame polar_frame(const core::SectoralGrid& grid, double metres_per_pixel) {
  if (!(metres_per_pixel > 0.0) || !std::isfinite(metres_per_pixel))
    throw std::invalid_argument("polar picture: metres per pixel must be positive and finite");
  const double reach = (grid.rings + 0.5) * grid.cell;
  const double margin = 4.0 * metres_per_pixel;
  const double width = 2.0 * (reach * std::sin(0.5 * grid.fov) + margin) / metres_per_pixel;
  const double height = (reach + 2.0 * margin) / metres_per_pixel;
  if (!(width * height < kMaxPolarPixels))
    throw std::invalid_argument("polar picture: more than 2^26 pixels");
  core::GridGeometry geometry{static_cast<int>(std::ceil(width)),
                              static_cast<int>(std::ceil(height)), metres_per_pixel, 0.0, -margin};
  geometry.origin_x = -0.5 * geometry.width * metres_per_pixel;
  return {geometry, {0.0, 0.0, 0.5 * std::numbers::pi}};
}

io::RgbImage render_polar(const PolarFrame& frame, const core::SectoralGrid& grid,
                          std::span<const double> values, io::ProbabilityScale scale) {
  const core::ProbabilityGrid picture = core::map_polar(frame.geometry, frame.sensor, grid, values,
                                                        std::numeric_limits<double>::quiet_NaN());
  return io::render_probability_grid(picture, scale);
}

void write_polar_csv_rows(std::ostream& csv, std::string_view prefix,
                          const core::SectoralGrid& grid, std::span<const double> p,
                          std::span<const std::int16_t> indices) {
  if (p.size() != grid.cells() || (!indices.empty() && indices.size() != grid.cells()))
    throw std::invalid_argument("polar CSV: values differ in size from the polar grid");
  char row[96];
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto bins = static_cast<std::size_t>(grid.bins);
    int length = std::snprintf(row, sizeof row, "%zu,%zu,%.17g", i / bins + 1, i % bins + 1, p[i]);
    if (!indices.empty())
      length += std::snprintf(row + length, sizeof row - static_cast<std::size_t>(length), ",%d",
                              int{indices[i]});
    csv << prefix;
    csv.write(row, length) << '\n';
  }
}

}  // namespace intgrid::figures
