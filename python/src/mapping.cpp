// Mapping with known poses in Python.
#include "bindings.hpp"

namespace intgrid::python {
namespace {

std::vector<core::Scan> scans_of(const py::object& scans) {
  if (py::isinstance<core::Log>(scans)) return scans.cast<const core::Log&>().scans;
  return scans.cast<std::vector<core::Scan>>();
}

struct MapSettings {
  core::GaussianBeamModel model;
  double cell;
  int bits;
  int levels;
  std::optional<double> eps;
  core::VetoBound veto;
  core::GridGeometry geometry;
};

MapSettings map_settings(const std::vector<core::Scan>& scans, double cell, double sigma,
                         double k_d, int bits, int levels, std::optional<double> eps,
                         const std::string& veto, double margin,
                         const std::optional<core::GridGeometry>& geometry) {
  const core::GaussianBeamModel model{sigma, k_d};
  core::check_model(model);
  check_positive(cell, "cell");
  core::GridGeometry g;
  if (geometry) {
    g = *geometry;
    core::check_geometry(g);
    if (g.resolution != cell)
      value_error("geometry.resolution (" + number(g.resolution) + ") differs from cell (" +
                  number(cell) + ")");
  } else {
    check_finite(margin, "margin");
    g = core::geometry_covering(scans, cell, margin);
  }
  return {model, cell, bits, levels, eps, veto_of(veto), g};
}

// The codec of `intgrid map`: eps given, or p_levels = Pmax of the ISM.
core::SepsCodec map_codec(const MapSettings& s) {
  if (s.eps) return core::SepsCodec(s.bits, *s.eps);
  return core::SepsCodec::for_levels(s.bits, core::narrow_pmax(s.cell, s.model.sigma0), s.levels);
}

template <class Index>
core::Grid<Index> map_with_indices(const std::vector<core::Scan>& scans, const MapSettings& s,
                                   const core::SepsCodec& codec) {
  core::IndexScanInserter<Index> inserter(s.model, s.cell, codec, s.veto);
  core::InsertionStats stats;
  return core::map_indices(scans, inserter, s.geometry, stats);
}

}  // namespace

void bind_mapping(py::module_& m) {
  m.def(
      "geometry_covering",
      [](const py::object& scans, double resolution, double margin) {
        return core::geometry_covering(scans_of(scans), resolution, margin);
      },
      "A grid covering every sensor position and valid reading's end point, plus margin (m).",
      "scans"_a, "resolution"_a, "margin"_a = 1.0);

  m.def(
      "map_from_scans",
      [](const py::object& scans_or_log, double cell, const py::object& arithmetic, double sigma,
         double k_d, int bits, int levels, std::optional<double> eps, const std::string& veto,
         double margin, const std::optional<core::GridGeometry>& geometry) {
        const std::vector<core::Scan> scans = scans_of(scans_or_log);
        const core::Arithmetic a = arithmetic_of(arithmetic);
        const MapSettings s =
            map_settings(scans, cell, sigma, k_d, bits, levels, eps, veto, margin, geometry);
        core::ProbabilityGrid grid;
        {
          py::gil_scoped_release release;
          if (a == core::Arithmetic::integer) {
            const core::SepsCodec codec = map_codec(s);
            grid = bits <= 8 ? core::to_probabilities(
                                   map_with_indices<std::int8_t>(scans, s, codec), codec)
                             : core::to_probabilities(
                                   map_with_indices<std::int16_t>(scans, s, codec), codec);
          } else {
            core::InsertionStats stats;
            grid = core::map_probabilities(scans, s.model, s.geometry, stats);
          }
        }
        return py::make_tuple(to_numpy(grid), grid.geometry);
      },
      "Maps scans (a list or a Log) with their own poses, as `intgrid map` does: returns "
      "(P(occupied) float64 array (height, width), row 0 = bottom; GridGeometry). 'int': S_eps "
      "indices of `bits` bits (eps from `levels`, or `eps`), veto 'claim' or 'none'; 'float': "
      "Bayesian fusion in double.",
      "scans"_a, "cell"_a = 0.05, "arithmetic"_a = "int", "sigma"_a = 0.05, "k_d"_a = 0.0,
      "bits"_a = 8, "levels"_a = 16, "eps"_a = py::none(), "veto"_a = "claim", "margin"_a = 1.0,
      "geometry"_a = py::none());

  m.def(
      "map_indices",
      [](const py::object& scans_or_log, double cell, double sigma, double k_d, int bits,
         int levels, std::optional<double> eps, const std::string& veto, double margin,
         const std::optional<core::GridGeometry>& geometry) {
        const std::vector<core::Scan> scans = scans_of(scans_or_log);
        const MapSettings s =
            map_settings(scans, cell, sigma, k_d, bits, levels, eps, veto, margin, geometry);
        const core::SepsCodec codec = map_codec(s);
        py::object cells;
        if (bits <= 8) {
          core::Grid<std::int8_t> grid;
          {
            py::gil_scoped_release release;
            grid = map_with_indices<std::int8_t>(scans, s, codec);
          }
          cells = to_numpy(grid);
        } else {
          core::Grid<std::int16_t> grid;
          {
            py::gil_scoped_release release;
            grid = map_with_indices<std::int16_t>(scans, s, codec);
          }
          cells = to_numpy(grid);
        }
        return py::make_tuple(cells, s.geometry, codec);
      },
      "The integer map itself: (S_eps index array (height, width), int8 for bits <= 8 else "
      "int16, row 0 = bottom; GridGeometry; SepsCodec).",
      "scans"_a, "cell"_a = 0.05, "sigma"_a = 0.05, "k_d"_a = 0.0, "bits"_a = 8, "levels"_a = 16,
      "eps"_a = py::none(), "veto"_a = "claim", "margin"_a = 1.0, "geometry"_a = py::none());
}

}  // namespace intgrid::python
