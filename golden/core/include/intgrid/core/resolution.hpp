// The choice of grid resolution for a sensor precision (thesis 2.4.2): the
// largest probability Pmax the narrow ISM can reach depends on s/sigma, so a
// wanted Pmax fixes the smallest cell size.
#pragma once

namespace intgrid::core {

// Pmax of the narrow ISM for cell size `cell` and a Gaussian of constant sigma,
// with the reading at `offset` cells past a cell centre (offset in [0, 1)):
// offset 0 is the thesis's case, z on a cell centre.
double narrow_pmax(double cell, double sigma, double offset = 0.0);

// The smallest Pmax over every position of the reading inside a cell, and where.
struct WorstCasePmax {
  double pmax;
  double offset;  // cells past the centre
};
WorstCasePmax narrow_pmax_worst_case(double cell, double sigma);

// The smallest cell size whose ISM reaches `pmax` with the reading on a cell
// centre (worst_case = false) or wherever it falls in the cell (worst_case = true).
// Throws std::invalid_argument unless sigma > 0 and 1/2 < pmax < 1.
double smallest_cell_for_pmax(double sigma, double pmax, bool worst_case = false);

}  // namespace intgrid::core
