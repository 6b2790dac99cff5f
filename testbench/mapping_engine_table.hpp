// Golden's ISM table (core::NarrowIsmTable: every range bin's line-of-sight cells written out) in
// the mapping engine's form (hls/mapping_engine.hpp): per bin its cell count, the core of cells
// that take the first cell's index, and where its tail starts in one tail memory, in which bins
// of the same tail share one copy. The host side of loading the engine; no hardware here.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "intgrid/core/ray_insertion.hpp"

namespace intgrid::hw {

struct PackedIsmBin {
  std::uint32_t cells = 0;  // line-of-sight cells 1..cells
  std::uint32_t core = 0;   // cells 1..core take `constant`
  std::int8_t constant = 0;
  std::uint32_t tail = 0;  // cell core + 1 + i is tail memory entry tail + i
};

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
