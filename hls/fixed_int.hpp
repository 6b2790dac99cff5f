// Fixed-width integers for the kernels in hls/: sint<W> (W-bit two's complement) and uint<W>
// (W-bit unsigned), the subset of Vitis HLS's ap_int/ap_uint and Catapult's ac_int the kernels
// need, in standard C++ only, constexpr throughout.
//
// Semantics are ap_int's:
//   - storing a value into a sint<W>/uint<W> keeps its low W bits (wraps), as a W-bit register;
//   - the result of + - * and unary - is exact: its width is the one the operands imply
//     (max(A, B) + 1 for a sum or difference, A + B for a product; an unsigned operand of a
//     signed result counts one bit more), so only a store into a declared width can lose bits;
//   - comparisons compare values; shifts by a constant are shl<K> (W + K bits) and shr<K>
//     (W - K bits, arithmetic for sint).
// Built-in integers convert to sint/uint implicitly (wrapping), and sint/uint convert implicitly
// to the smallest built-in type that holds W bits (int8_t ... int64_t, uint8_t ... uint64_t), so
// code written for built-in integers keeps compiling. An HLS user may replace this header by
// `template <int W> using sint = ap_int<W>; template <int W> using uint = ap_uint<W>;` plus shl,
// shr and magnitude (docs/hardware.md).
//
// Width checking: with INTGRID_HLS_WIDTH_CHECK defined, every value stored into a declared width
// or formed by an operator is recorded in width_log(): a value that does not fit its width counts
// as an overflow (and is still wrapped, as the hardware would); an operator's exact result always
// fits. Per (signedness, width) the log keeps the extreme values seen, which the tests report
// against the declared widths. The checked mode needs C++20 (std::is_constant_evaluated: values
// formed at compile time are not logged); without it the header is C++17.
#pragma once

#include <cstdint>
#include <type_traits>

namespace intgrid::hls {

#if defined(INTGRID_HLS_WIDTH_CHECK)
// What the checked mode saw, per signedness (0 unsigned, 1 signed) and declared width.
struct WidthLog {
  std::uint64_t stores = 0;     // values stored into a declared width
  std::uint64_t overflows = 0;  // of them, values that did not fit
  std::int64_t lowest[2][64] = {};
  std::int64_t highest[2][64] = {};
  std::uint64_t stores_of[2][64] = {};
  std::uint64_t overflows_of[2][64] = {};
  void record(bool is_signed, int width, std::int64_t value, bool fits) {
    const int s = is_signed ? 1 : 0;
    if (stores_of[s][width] == 0 || value < lowest[s][width]) lowest[s][width] = value;
    if (stores_of[s][width] == 0 || value > highest[s][width]) highest[s][width] = value;
    ++stores;
    ++stores_of[s][width];
    if (!fits) {
      ++overflows;
      ++overflows_of[s][width];
    }
  }
};
inline WidthLog& width_log() {
  static WidthLog log;
  return log;
}
#endif

template <bool Signed, int W>
class fixed_int;
template <int W>
using sint = fixed_int<true, W>;
template <int W>
using uint = fixed_int<false, W>;

namespace detail {

// The smallest built-in integer type of a signedness holding W bits.
template <bool Signed, int W>
using builtin_for = std::conditional_t<
    Signed,
    std::conditional_t<W <= 8, std::int8_t,
                       std::conditional_t<W <= 16, std::int16_t,
                                          std::conditional_t<W <= 32, std::int32_t, std::int64_t>>>,
    std::conditional_t<
        W <= 8, std::uint8_t,
        std::conditional_t<W <= 16, std::uint16_t,
                           std::conditional_t<W <= 32, std::uint32_t, std::uint64_t>>>>;

constexpr int max_int(int a, int b) {
  return a > b ? a : b;
}

// Width of an operand of signedness S and width W inside a result of signedness R.
constexpr int operand_width(bool result_signed, bool S, int W) {
  return W + (result_signed && !S ? 1 : 0);
}

}  // namespace detail

template <bool Signed, int W>
class fixed_int {
  static_assert(W >= 1 && W <= (Signed ? 63 : 62), "fixed_int holds at most 63 signed bits");

 public:
  static constexpr bool is_signed = Signed;
  static constexpr int width = W;
  static constexpr std::int64_t min = Signed ? -(std::int64_t{1} << (W - 1)) : 0;
  static constexpr std::int64_t max =
      Signed ? (std::int64_t{1} << (W - 1)) - 1 : (std::int64_t{1} << W) - 1;
  using builtin = detail::builtin_for<Signed, W>;

  constexpr fixed_int() = default;
  // A built-in integer, wrapped to W bits (checked in the checked mode).
  template <class T, std::enable_if_t<std::is_integral_v<T>, int> = 0>
  constexpr fixed_int(T x)  // NOLINT(google-explicit-constructor): ap_int converts implicitly
      : v_(store(static_cast<std::int64_t>(x),
                 std::is_unsigned_v<T> && sizeof(T) == 8 &&
                     static_cast<std::uint64_t>(x) > std::uint64_t{INT64_MAX})) {}
  // Another width or signedness, wrapped to W bits (checked in the checked mode).
  template <bool S2, int W2>
  constexpr fixed_int(fixed_int<S2, W2> x)  // NOLINT(google-explicit-constructor)
      : v_(store(x.value(), false)) {}

  // An exact result: the caller guarantees that v fits (the operators below). Logged in the
  // checked mode like a store, so the log's extremes cover every value held in a W-bit word.
  static constexpr fixed_int exact(std::int64_t v) {
    fixed_int r;
    r.v_ = store(v, false);
    return r;
  }

  constexpr std::int64_t value() const { return v_; }
  constexpr operator builtin() const {  // NOLINT(google-explicit-constructor)
    return static_cast<builtin>(v_);
  }

 private:
  static constexpr std::int64_t wrap(std::int64_t x) {
    const std::uint64_t mask = (std::uint64_t{1} << W) - 1u;
    std::uint64_t u = static_cast<std::uint64_t>(x) & mask;
    if (Signed && (u >> (W - 1)) != 0u) u |= ~mask;  // sign extension
    return static_cast<std::int64_t>(u);
  }
  static constexpr std::int64_t store(std::int64_t x, bool beyond_int64) {
    const std::int64_t wrapped = wrap(x);
#if defined(INTGRID_HLS_WIDTH_CHECK)
    if (!std::is_constant_evaluated())
      width_log().record(Signed, W, x, wrapped == x && !beyond_int64);
#else
    (void)beyond_int64;
#endif
    return wrapped;
  }

  std::int64_t v_ = 0;
};

// ---- exact arithmetic ----------------------------------------------------------------------

template <bool S1, int W1, bool S2, int W2>
constexpr auto operator+(fixed_int<S1, W1> a, fixed_int<S2, W2> b) {
  constexpr bool S = S1 || S2;
  constexpr int Wr =
      detail::max_int(detail::operand_width(S, S1, W1), detail::operand_width(S, S2, W2)) + 1;
  return fixed_int<S, Wr>::exact(a.value() + b.value());
}

// A difference is signed whatever its operands.
template <bool S1, int W1, bool S2, int W2>
constexpr auto operator-(fixed_int<S1, W1> a, fixed_int<S2, W2> b) {
  constexpr int Wr =
      detail::max_int(detail::operand_width(true, S1, W1), detail::operand_width(true, S2, W2)) + 1;
  return sint<Wr>::exact(a.value() - b.value());
}

template <bool S, int W>
constexpr auto operator-(fixed_int<S, W> a) {
  return sint<W + 1>::exact(-a.value());
}

template <bool S1, int W1, bool S2, int W2>
constexpr auto operator*(fixed_int<S1, W1> a, fixed_int<S2, W2> b) {
  constexpr bool S = S1 || S2;
  constexpr int Wr = detail::operand_width(S, S1, W1) + detail::operand_width(S, S2, W2);
  return fixed_int<S, Wr>::exact(a.value() * b.value());
}

// x * 2^K, exact.
template <int K, bool S, int W>
constexpr auto shl(fixed_int<S, W> a) {
  return fixed_int<S, W + K>::exact(a.value() * (std::int64_t{1} << K));
}

// floor(x / 2^K): an arithmetic shift for sint.
template <int K, bool S, int W>
constexpr auto shr(fixed_int<S, W> a) {
  constexpr int Wr = W - K > 1 ? W - K : 1;
  return fixed_int<S, Wr>::exact(a.value() >> K);
}

// |x|: a W-bit sint's magnitude fits a W-bit uint (2^(W-1) included).
template <bool S, int W>
constexpr uint<W> magnitude(fixed_int<S, W> a) {
  return uint<W>::exact(a.value() < 0 ? -a.value() : a.value());
}

// ---- comparisons -----------------------------------------------------------------------------

namespace detail {
template <class T>
struct is_fixed : std::false_type {};
template <bool S, int W>
struct is_fixed<fixed_int<S, W>> : std::true_type {};
// The value of an operand: a fixed_int's, or a built-in integer's.
template <class T>
constexpr std::int64_t value_of(const T& x) {
  if constexpr (is_fixed<T>::value)
    return x.value();
  else
    return static_cast<std::int64_t>(x);
}
// At least one side a fixed_int, the other a fixed_int or a built-in integer (not bool).
template <class A, class B>
constexpr bool comparable = (is_fixed<A>::value || is_fixed<B>::value) &&
                            (is_fixed<A>::value ||
                             (std::is_integral_v<A> && !std::is_same_v<A, bool>)) &&
                            (is_fixed<B>::value ||
                             (std::is_integral_v<B> && !std::is_same_v<B, bool>));
}  // namespace detail

#define INTGRID_FIXED_INT_COMPARISON(op)                                           \
  template <class A, class B, std::enable_if_t<detail::comparable<A, B>, int> = 0> \
  constexpr bool operator op(const A& a, const B& b) {                             \
    return detail::value_of(a) op detail::value_of(b);                             \
  }
INTGRID_FIXED_INT_COMPARISON(==)
INTGRID_FIXED_INT_COMPARISON(!=)
INTGRID_FIXED_INT_COMPARISON(<)
INTGRID_FIXED_INT_COMPARISON(<=)
INTGRID_FIXED_INT_COMPARISON(>)
INTGRID_FIXED_INT_COMPARISON(>=)
#undef INTGRID_FIXED_INT_COMPARISON

// ---- widths of constant tables -----------------------------------------------------------------

// Bits of an unsigned word holding 0..v.
constexpr int unsigned_bits(std::int64_t v) {
  int bits = 1;
  while (bits < 62 && (std::int64_t{1} << bits) <= v) ++bits;
  return bits;
}
// Bits of a two's-complement word holding lo..hi (lo <= 0 <= hi).
constexpr int signed_bits(std::int64_t lo, std::int64_t hi) {
  int bits = 1;
  while (bits < 63 &&
         (lo < -(std::int64_t{1} << (bits - 1)) || hi > (std::int64_t{1} << (bits - 1)) - 1))
    ++bits;
  return bits;
}

}  // namespace intgrid::hls
