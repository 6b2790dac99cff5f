// Golden's sine and ISM tables in the mapping engine's form. The ISM table (core::NarrowIsmTable:
// every range bin's line-of-sight cells written out) in the mapping engine's form
// (hls/mapping_engine.hpp): per bin its cell count, the core of cells that take the first cell's
// index, and where its tail starts in one tail memory, in which bins of the same tail share one
// copy. The host side of loading the engine; no hardware here.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "hls/mapping_engine.hpp"
#include "intgrid/core/ray_insertion.hpp"

namespace intgrid::hw {

struct PackedIsmBin {
  std::uint32_t cells = 0;  // line-of-sight cells 1..cells
  std::uint32_t core = 0;   // cells 1..core take `constant`
  std::int8_t constant = 0;
  std::uint32_t tail = 0;  // cell core + 1 + i is tail memory entry tail + i
};

// Golden's quarter-wave sine (its first kQuarterTurn + 1 entries) in the engine's form: every
// 16th entry and the steps between them, 3 bits each. Throws std::invalid_argument if a step is
// not 0..7.
struct PackedSine {
  std::vector<std::uint32_t> coarse;  // S(16 j), j = 0 .. 1024
  std::vector<std::uint64_t> steps;   // steps 16 j + 1 .. 16 j + 15, 3 bits each from bit 0
};

inline PackedSine pack_quarter_sine(const std::vector<std::int32_t>& sine) {
  namespace m = hls::mapping;
  PackedSine packed;
  for (int j = 0; j < m::kSineCoarse; ++j)
    packed.coarse.push_back(
        static_cast<std::uint32_t>(sine[static_cast<std::size_t>(j * m::kSineBlock)]));
  for (int j = 0; j + 1 < m::kSineCoarse; ++j) {
    std::uint64_t word = 0;
    for (int i = 1; i < m::kSineBlock; ++i) {
      const auto a = static_cast<std::size_t>(j * m::kSineBlock + i);
      const std::int32_t step = sine[a] - sine[a - 1];
      if (step < 0 || step > 7)
        throw std::invalid_argument("the sine table rises by " + std::to_string(step) +
                                    " at entry " + std::to_string(a) + ", not 0..7");
      word |= static_cast<std::uint64_t>(step) << ((i - 1) * m::kSineStepBits);
    }
    packed.steps.push_back(word);
  }
  return packed;
}

struct PackedIsmTable {
  std::vector<PackedIsmBin> bins;
  std::vector<std::int8_t> tail;
};

inline PackedIsmTable pack_ism_table(const core::NarrowIsmTable& table) {
  PackedIsmTable packed;
  std::map<std::vector<std::int8_t>, std::uint32_t> tails;  // a tail -> where it is stored
  for (std::size_t bin = 0; bin + 1 < table.begin.size(); ++bin) {
    const std::int8_t* first = table.values.data() + table.begin[bin];
    const std::uint32_t cells = table.begin[bin + 1] - table.begin[bin];
    PackedIsmBin b;
    b.cells = cells;
    if (cells > 0) {
      b.constant = first[0];
      while (b.core < cells && first[b.core] == b.constant) ++b.core;
      std::vector<std::int8_t> tail(first + b.core, first + cells);
      const auto [at, added] =
          tails.try_emplace(tail, static_cast<std::uint32_t>(packed.tail.size()));
      if (added) packed.tail.insert(packed.tail.end(), tail.begin(), tail.end());
      b.tail = at->second;
    }
    packed.bins.push_back(b);
  }
  return packed;
}

}  // namespace intgrid::hw
