// The exact Bayesian inverse sensor model of a large-FOV nearest-target sensor over its
// local polar grid, with sectoral decomposition (thesis 2.5, docs/algorithms.md 3), in linear
// time. The ring recursion is written once, for any log-domain arithmetic: double here,
// the bit-accurate integer kernel in intgrid/kernel/ism_kernel.hpp.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "intgrid/core/sensor_model.hpp"

namespace intgrid::core {

// Limits of the polar grid. Sectors: the pattern weights cost Ns^3 per grid and every
// ring sums Ns^2 pattern classes for each of 2 Ns + 1 conditions. Bins: the prior of an
// empty ring, 2^-A, must stay a normal double.
inline constexpr int kMaxSectors = 64;
inline constexpr int kMaxBins = 1000;
inline constexpr long long kMaxPolarCells = 100'000'000;

// The local polar grid of a cone sensor: ring r = 1..rings at distance r * cell, bins
// a = 0..bins-1 across the FOV (bin 0 on the clockwise edge), split into `sectors`
// contiguous sectors of bins / sectors bins each (bin a in sector a * sectors / bins).
// Equal sectors keep the decomposition symmetric about the axis.
struct SectoralGrid {
  double fov = 0.5235987755982988;  // 30 degrees, in radians
  int rings = 40;
  int bins = 16;
  int sectors = 4;
  double cell = 0.05;  // metres

  std::size_t cells() const {
    return static_cast<std::size_t>(rings) * static_cast<std::size_t>(bins);
  }
  int bins_per_sector() const { return bins / sectors; }
  int sector_of_bin(int bin) const { return bin * sectors / bins; }
  // Angle of a bin's or sector's centre from the axis, counter-clockwise positive.
  double bin_centre(int bin) const { return -0.5 * fov + (bin + 0.5) * fov / bins; }
  double sector_centre(int sector) const { return -0.5 * fov + (sector + 0.5) * fov / sectors; }
  // |sector_centre| / (FOV / 2), the off-axis measure of the sensor model.
  double sector_theta(int sector) const;
  double ring_distance(int ring) const { return ring * cell; }
};

// Throws std::invalid_argument naming the offending field: sizes must be positive, the
// FOV in (0, pi), sectors must divide bins, and the limits above hold.
void check_sectoral_grid(const SectoralGrid& grid);

// The classes of ring patterns S (the set of occupied sectors of the nearest occupied
// ring) that the sensor model tells apart: theta(S) and |S|. For each class c and each
// condition v, weight(v, c) = sum over the patterns S of class c of P(S | v), where
//   v = 0:               the prior (each sector occupied with probability 1 - 2^-n_j),
//   v = 1 + j:           sector j surely occupied (it holds the occupied cell i),
//   v = 1 + sectors + j: one cell of sector j surely empty (n_j - 1 cells left to occupy it).
// They depend on the grid only, not on the reading: a hardware kernel holds them in ROM.
struct PatternClasses {
  int sectors = 0;
  std::vector<double> theta;       // per class
  std::vector<int> size;           // per class: |S|
  std::vector<double> log_weight;  // [v * classes() + c], natural log, -inf if impossible

  std::size_t classes() const { return theta.size(); }
  int conditions() const { return 2 * sectors + 1; }
  double log_weight_of(int v, std::size_t c) const {
    return log_weight[static_cast<std::size_t>(v) * classes() + c];
  }
};
PatternClasses pattern_classes(const SectoralGrid& grid);

// The ring recursion of docs/algorithms.md 3 in a log-domain arithmetic. Arith provides
//   Value zero(); Value add(Value, Value) (the log of a sum); Value mul(Value, Value);
//   Value log_density(int ring, std::size_t c) for the reading at hand;
//   Value log_weight(int v, std::size_t c); Value ring_prior(int ring) (2^-M_r);
//   Value two(); Out output(Value log_num, Value log_den).
// Calls emit(ring, sector, output) for ring = 1..rings and sector = 0..sectors-1, in that
// order. Each sum runs over the classes in ascending order, the prefix over rings upward
// and the suffix downward: the order a bit-accurate integer kernel must follow.
template <class Arith, class Emit>
void sectoral_ism_rings(const Arith& arith, int rings, int sectors, std::size_t classes,
                        Emit&& emit) {
  using Value = decltype(arith.zero());
  const int conditions = 2 * sectors + 1;
  // Per ring: T_r = 2^-M_r * sum_S p(z|d_r,S) P_r(S), then the occupied and emptied sums.
  std::vector<Value> ring_term(static_cast<std::size_t>(rings) + 2, arith.zero());
  std::vector<Value> conditioned(static_cast<std::size_t>(rings) * 2 * sectors, arith.zero());
  std::vector<Value> density(classes);
  for (int r = 1; r <= rings; ++r) {
    for (std::size_t c = 0; c < classes; ++c) density[c] = arith.log_density(r, c);
    const Value prior = arith.ring_prior(r);
    for (int v = 0; v < conditions; ++v) {
      Value sum = arith.zero();
      for (std::size_t c = 0; c < classes; ++c)
        sum = arith.add(sum, arith.mul(density[c], arith.log_weight(v, c)));
      sum = arith.mul(sum, prior);
      if (v == 0)
        ring_term[static_cast<std::size_t>(r)] = sum;
      else
        conditioned[static_cast<std::size_t>(r - 1) * 2 * sectors + (v - 1)] = sum;
    }
  }
  // after[r] = sum of T over the rings past r.
  std::vector<Value> after(static_cast<std::size_t>(rings) + 2, arith.zero());
  for (int r = rings - 1; r >= 1; --r)
    after[static_cast<std::size_t>(r)] = arith.add(after[static_cast<std::size_t>(r) + 1],
                                                   ring_term[static_cast<std::size_t>(r) + 1]);
  Value before = arith.zero();  // sum of T over the rings before r
  for (int r = 1; r <= rings; ++r) {
    const Value* ring = &conditioned[static_cast<std::size_t>(r - 1) * 2 * sectors];
    const Value beyond = arith.mul(arith.two(), after[static_cast<std::size_t>(r)]);
    for (int j = 0; j < sectors; ++j) {
      const Value num = arith.add(before, ring[j]);
      const Value den = arith.add(arith.add(before, ring[sectors + j]), beyond);
      emit(r, j, arith.output(num, den));
    }
    before = arith.add(before, ring_term[static_cast<std::size_t>(r)]);
  }
}

// P(o_i | z) for every polar cell, ring-major: cell (ring r, bin a) at (r - 1) * bins + a.
// Double precision in the natural-log domain, rescaled at the ring nearest z, so any
// number of rings is stable. Requires a checked model and grid and a finite z.
std::vector<double> sectoral_ism(const ConeSensorModel& model, const SectoralGrid& grid, double z);
void sectoral_ism(const ConeSensorModel& model, const SectoralGrid& grid, double z,
                  std::span<double> out);

// The large-FOV configuration likelihood of eq. 2.7-2.10 for brute-force Bayes: bit
// (r - 1) * bins + a of g set = polar cell (r, a) occupied; p(z | d_{r_g}, S_g), with
// r_g the nearest ring holding an occupied cell and S_g its occupied sectors; nothing
// for the all-empty configuration.
long double sectoral_configuration_likelihood(const ConeSensorModel& model,
                                              const SectoralGrid& grid, double z,
                                              unsigned long long g);

}  // namespace intgrid::core
