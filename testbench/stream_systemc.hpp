// SystemC side of the stream testbenches (testbench/stream_driver.hpp): conversions between Bits
// and the value types of SystemC data signals, so one stimulus can drive a SystemC model (whose
// buses are sc_biguint<W>) and a Verilated --sc model (uint32_t / uint64_t up to 64 bits, sc_bv<W>
// beyond) with the same values.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include <systemc>

#include "testbench/stream_driver.hpp"

namespace intgrid::tb {

// Bits <-> the value of a data signal: an unsigned integer (Verilated ports up to 64 bits),
// sc_bv<W> (wider Verilated ports) or sc_biguint<W> (the SystemC model).
template <class T>
T to_value(const Bits& bits, int width) {
  if constexpr (std::is_integral_v<T>) {
    return static_cast<T>((std::uint64_t{bits.w[1]} << 32) | bits.w[0]);
  } else {
    T v = 0;
    for (int lo = 0; lo < width; lo += 32) {
      const int hi = std::min(width, lo + 32) - 1;
      v.range(hi, lo) = bits.w[static_cast<std::size_t>(lo / 32)];
    }
    return v;
  }
}
template <class T>
Bits from_value(const T& v, int width) {
  Bits bits;
  if constexpr (std::is_integral_v<T>) {
    bits.w[0] = static_cast<std::uint32_t>(v);
    bits.w[1] = static_cast<std::uint32_t>(static_cast<std::uint64_t>(v) >> 32);
  } else {
    for (int lo = 0; lo < width; lo += 32) {
      const int hi = std::min(width, lo + 32) - 1;
      bits.w[static_cast<std::size_t>(lo / 32)] =
          static_cast<std::uint32_t>(v.range(hi, lo).to_uint());
    }
  }
  return bits;
}

}  // namespace intgrid::tb
