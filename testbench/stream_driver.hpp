// Simulator-independent pieces of the kernels' stream testbenches (Verilator C++ and SystemC):
// seeds, random traffic (input valid gaps, output back-pressure), the AXI4-Stream rules a
// source obeys and a sink checks, bit vectors of any width up to 512 bits with Verilator port
// conversions, and small statistics / JSON helpers.
//
// Seeds: every run is random but reproducible. The master seed comes from INTGRID_TB_SEED
// (decimal or 0x hex) if set, else from std::random_device; each test derives its own seed from
// the master seed and its name, and prints both.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <string_view>
#include <type_traits>

namespace intgrid::tb {

// ---------------------------------------------------------------------------------------------
// Seeds

inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// The master seed of this process: INTGRID_TB_SEED, else random. Computed once.
inline std::uint64_t master_seed() {
  static const std::uint64_t seed = [] {
    if (const char* env = std::getenv("INTGRID_TB_SEED"); env != nullptr && *env != '\0')
      return static_cast<std::uint64_t>(std::strtoull(env, nullptr, 0));
    std::random_device rd;
    return (std::uint64_t{rd()} << 32) ^ rd();
  }();
  return seed;
}

// A test's own seed, derived from the master seed and the test's name; printed with the way to
// reproduce the run.
inline std::uint64_t test_seed(std::string_view name) {
  std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a of the name
  for (char c : name) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
  const std::uint64_t seed = splitmix64(master_seed() ^ h);
  std::printf("[seed] %.*s: seed %llu (rerun with INTGRID_TB_SEED=%llu)\n",
              static_cast<int>(name.size()), name.data(), static_cast<unsigned long long>(seed),
              static_cast<unsigned long long>(master_seed()));
  std::fflush(stdout);
  return seed;
}

using Rng = std::mt19937_64;

inline bool chance(Rng& rng, double p) {
  if (p >= 1.0) return true;
  if (p <= 0.0) return false;
  return std::uniform_real_distribution<double>(0.0, 1.0)(rng) < p;
}

// ---------------------------------------------------------------------------------------------
// Traffic: how often sources offer a beat and how often the sink is ready.

// Fixed probabilities for the whole run (1.0 = no gaps / no back-pressure).
struct TrafficRates {
  double valid = 1.0;  // per input stream, per cycle, when the source has no beat pending
  double ready = 1.0;  // per cycle at the output
};

// Random traffic: the run is cut into segments of random length (1..max_segment cycles), each
// with its own rates drawn from a mix of full rate, light, heavy and uniform random, so that
// streaming at full rate, long stalls and everything between are all exercised.
class TrafficShaper {
 public:
  explicit TrafficShaper(std::uint64_t seed, int max_segment = 2000)
      : rng_(seed), max_segment_(max_segment) {}
  // A shaper that never changes: fixed rates.
  static TrafficShaper fixed(TrafficRates rates) {
    TrafficShaper t(0);
    t.fixed_ = true;
    t.rates_ = rates;
    return t;
  }

  // Rates for the next cycle.
  const TrafficRates& next() {
    if (!fixed_ && left_ <= 0) {
      left_ = std::uniform_int_distribution<int>(1, max_segment_)(rng_);
      rates_ = TrafficRates{pick(), pick()};
    }
    --left_;
    return rates_;
  }
  bool is_fixed() const { return fixed_; }

 private:
  double pick() {
    static constexpr std::array<double, 6> kRates{1.0, 1.0, 0.9, 0.5, 0.1, 0.02};
    const auto i = std::uniform_int_distribution<std::size_t>(0, kRates.size())(rng_);
    if (i == kRates.size()) return std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
    return kRates[i];
  }
  Rng rng_;
  int max_segment_;
  bool fixed_ = false;
  int left_ = 0;
  TrafficRates rates_{};
};

// The valid side of one AXI4-Stream source: once valid is raised it stays up (with the same
// beat) until the beat is taken; a new beat may follow in the very next cycle.
class ValidGate {
 public:
  // Call once per clock edge: `fired` = valid && ready were both high before the edge;
  // `has_beat` = the source has a beat to offer after the edge.
  void step(bool fired, bool has_beat, double rate, Rng& rng) {
    if (fired) valid_ = false;
    if (!valid_ && has_beat) valid_ = chance(rng, rate);
  }
  bool valid() const { return valid_; }
  void reset() { valid_ = false; }

 private:
  bool valid_ = false;
};

// The AXI4-Stream rule a sink checks: while valid && !ready, valid, data and last must hold until
// the next edge. Call once per cycle with the values settled before the clock edge.
template <class Payload>
class StabilityMonitor {
 public:
  // Returns false on a violation (valid dropped, or the payload changed, while stalled).
  bool check(bool valid, bool ready, const Payload& payload) {
    bool ok = true;
    if (stalled_) ok = valid && payload == held_;
    stalled_ = valid && !ready;
    if (stalled_) held_ = payload;
    return ok;
  }
  void reset() { stalled_ = false; }

 private:
  bool stalled_ = false;
  Payload held_{};
};

// ---------------------------------------------------------------------------------------------
// Bit vectors up to 512 bits, and their conversion to and from Verilator ports (CData, SData,
// IData, QData, VlWide<N>) and B-bit lanes.

struct Bits {
  static constexpr int kMaxWidth = 512;
  std::array<std::uint32_t, kMaxWidth / 32> w{};

  // Bits [lsb + width - 1 : lsb], width <= 32.
  std::uint32_t field(int lsb, int width) const {
    const auto i = static_cast<std::size_t>(lsb / 32);
    const int s = lsb % 32;
    std::uint64_t v = w[i] >> s;
    if (s + width > 32) v |= std::uint64_t{w[i + 1]} << (32 - s);
    const std::uint64_t mask = (std::uint64_t{1} << width) - 1u;
    return static_cast<std::uint32_t>(v & mask);
  }
  void set_field(int lsb, int width, std::uint32_t value) {
    const std::uint64_t mask = (std::uint64_t{1} << width) - 1u;
    const std::uint64_t v = value & mask;
    const auto i = static_cast<std::size_t>(lsb / 32);
    const int s = lsb % 32;
    w[i] = static_cast<std::uint32_t>((w[i] & ~(mask << s)) | (v << s));
    if (s + width > 32) {
      w[i + 1] = static_cast<std::uint32_t>((w[i + 1] & ~(mask >> (32 - s))) | (v >> (32 - s)));
    }
  }
  bool operator==(const Bits&) const = default;
};

// Sign extension of a `width`-bit pattern.
inline std::int32_t sign_extend(std::uint32_t pattern, int width) {
  const std::uint32_t sign = std::uint32_t{1} << (width - 1);
  const std::uint32_t low = pattern & ((sign << 1) - 1u);
  return static_cast<std::int32_t>(low ^ sign) - static_cast<std::int32_t>(sign);
}

// Verilator port <-> Bits. Narrow ports are unsigned integers; wide ones are VlWide<N>, whose
// m_storage holds 32-bit words, least significant first.
template <class Port>
void to_port(Port& port, const Bits& bits) {
  if constexpr (std::is_integral_v<Port>) {
    if constexpr (sizeof(Port) <= 4) {
      port = static_cast<Port>(bits.w[0]);
    } else {
      port = static_cast<Port>((std::uint64_t{bits.w[1]} << 32) | bits.w[0]);
    }
  } else {
    constexpr std::size_t n = sizeof(port.m_storage) / sizeof(port.m_storage[0]);
    for (std::size_t i = 0; i < n; ++i) port.m_storage[i] = bits.w[i];
  }
}
template <class Port>
Bits from_port(const Port& port) {
  Bits bits;
  if constexpr (std::is_integral_v<Port>) {
    const auto v = static_cast<std::uint64_t>(port);
    bits.w[0] = static_cast<std::uint32_t>(v);
    bits.w[1] = static_cast<std::uint32_t>(v >> 32);
  } else {
    constexpr std::size_t n = sizeof(port.m_storage) / sizeof(port.m_storage[0]);
    for (std::size_t i = 0; i < n; ++i) bits.w[i] = port.m_storage[i];
  }
  return bits;
}

// ---------------------------------------------------------------------------------------------
// Statistics and JSON

struct Stats {
  std::uint64_t n = 0;
  std::int64_t min = std::numeric_limits<std::int64_t>::max();
  std::int64_t max = std::numeric_limits<std::int64_t>::min();
  double sum = 0.0;
  void add(std::int64_t v) {
    ++n;
    min = std::min(min, v);
    max = std::max(max, v);
    sum += static_cast<double>(v);
  }
  double mean() const { return n == 0 ? 0.0 : sum / static_cast<double>(n); }
  // {"min":..,"mean":..,"max":..}
  std::string json() const {
    char buf[160];
    std::snprintf(buf, sizeof buf, "{\"min\":%lld,\"mean\":%.4f,\"max\":%lld}",
                  static_cast<long long>(n == 0 ? 0 : min), mean(),
                  static_cast<long long>(n == 0 ? 0 : max));
    return buf;
  }
};

}  // namespace intgrid::tb
