// The thesis's figures 2.12 (the large-FOV ISM with sectoral decomposition) and 2.13
// (multi-sensor fusion), each one PNG of labelled panels with the numbers behind it beside it.
#pragma once

#include <filesystem>

namespace intgrid::figures {

struct FigureFiles {
  std::filesystem::path image;
  std::filesystem::path data;  // the numbers behind the picture, same stem
};

inline constexpr double kNsSweepReading = 1.0;  // metres, the default z of figure 2.12

// Figure 2.12: the ISM of the reading z (metres, finite) over a 30-degree FOV of A = 30 bins
// and R = 40 rings of 5 cm with the default cone model, exact (Ns = A) and with Ns = 1, 3, 5,
// 10 sectors, beside a drawing of the scene. Writes png and the CSV ns,ring,bin,p (ring and
// bin 1-based) beside it. Throws std::invalid_argument unless png ends in ".png".
FigureFiles write_ns_sweep_figure(const std::filesystem::path& png, double z = kNsSweepReading);

// Figure 2.13: one wall seen by a narrow sensor A (2-degree beam) and a cone sensor B (the
// default cone model and polar grid) beside it: the scene, each ISM in its polar grid, each
// mono-sensor grid on a common world grid, and their fusion in double precision (Bayes) and
// in 8-bit S_eps indices (B's from the integer ISM kernel). Writes png and a JSON summary of
// the grids beside it. Throws std::invalid_argument unless png ends in ".png".
FigureFiles write_fusion_figure(const std::filesystem::path& png);

}  // namespace intgrid::figures
