// Unit tests of U_gamma (intgrid/core/ugamma.hpp, docs/algorithms.md 5) with long double as the
// oracle.
//
// Error bounds, in index steps. One step is a factor gamma = 2^(-1/steps_per_halving), so an
// error of e steps is a relative error of about e ln 2 / steps_per_halving.
// - multiply, divide: exact (integer index addition and subtraction). A result past the zero
//   code is the zero code (underflow to 0); one below the smallest index is the smallest index.
// - add: one rounding of Phi_plus: |add(i, j) - log_gamma(u_i + u_j)| <= 0.5. Past the
//   table (Phi_plus rounds to 0) the result is min(i, j), also within 0.5.
// - complement: one rounding of Phi_minus: |complement(i) - log_gamma(1 - u_i)| <= 0.5, and a
//   result past the zero code is the zero code.
// - fuse: F = a - (a (+) b) = max(x, 0) + Phi_plus(|x|) with x = a - b, a = i + j exact and
//   b = Phi_minus(i) + Phi_minus(j) off by at most 0.5 + 0.5 = 1 step. The exact
//   f(a, b) = a - log_gamma(gamma^a + gamma^b) has df/db = gamma^b / (gamma^a + gamma^b) = 1 - F,
//   in [0, 1], so the error of b moves f by at most 1 step, and the rounding of Phi_plus adds
//   0.5: |fuse(i, j) - log_gamma(F)| <= 1.5 (a result that reaches the zero code saturates).
//   Fusing with 1/2 (index steps_per_halving, whose Phi_minus is exact) rounds one Phi_minus
//   only: |fuse(i, steps_per_halving) - i| <= 1.
// - sum of n terms by n - 1 chained additions: each addition rounds by 0.5 and passes on its
//   operand's error with a weight below 1, so the total is within (n - 1) / 2 steps. Division
//   is exact, so the normalized probabilities sum to 1 within a factor gamma^(-+(n - 1) / 2).
// - conversions: from_log and from_probability round to the nearest index (0.5 step), and
//   from_probability(to_probability(i)) == i while u_i is a normal double.
// Each test prints its measured maximum error ("[ugamma] ...").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "intgrid/core/ugamma.hpp"

using namespace intgrid::core;

namespace intgrid {
namespace {

struct Setting {
  int bits;
  int steps;
};

// The default, a coarse and a fine set, and two whose Phi_plus table is longer than half the
// index range (so |i - j| reaches past zero()) and whose Phi_minus(1) is past the zero code.
constexpr Setting kSettings[] = {{16, 16}, {8, 1}, {24, 256}, {12, 4}, {8, 32}, {16, 4096}};

// Table values are rounded from doubles; the oracle is long double.
constexpr long double kSlack = 1e-6L;

// Exact operations on real indices (long double).
struct Oracle {
  explicit Oracle(const UGamma& u) : step(std::log(2.0L) / u.steps_per_halving()) {}
  long double step;  // -ln gamma

  // log_gamma(1 + gamma^d) with the sign of the table: -log_gamma(1 + gamma^d) >= 0.
  long double phi_plus(long double d) const { return std::log1p(std::exp(-step * d)) / step; }
  // log_gamma(1 - gamma^i), i > 0.
  long double phi_minus(long double i) const { return -std::log(-std::expm1(-step * i)) / step; }
  long double add(long double i, long double j) const {
    return std::min(i, j) - phi_plus(std::fabs(i - j));
  }
  // log_gamma of u_i u_j / (u_i u_j + (1 - u_i)(1 - u_j)), i, j > 0.
  long double fuse(long double i, long double j) const {
    const long double x = i + j - phi_minus(i) - phi_minus(j);
    return std::max(x, 0.0L) + phi_plus(std::fabs(x));
  }
  // log_gamma(sum of u_i).
  long double sum(const std::vector<UIndex>& indices) const {
    long double low = indices.front();
    for (UIndex i : indices) low = std::min<long double>(low, i);
    long double s = 0.0L;
    for (UIndex i : indices) s += std::exp(-step * (i - low));
    return low - std::log(s) / step;
  }
};

std::string name(const UGamma& u) {
  char text[32];
  std::snprintf(text, sizeof text, "(%d, %d)", u.bits(), u.steps_per_halving());
  return text;
}

void report(const char* what, const UGamma& u, long double error) {
  std::printf("[ugamma] %-28s %-11s max error %.4Lf steps\n", what, name(u).c_str(), error);
}

// lo..hi with a stride that keeps the count near `count`, always with lo and hi.
std::vector<UIndex> range(std::int64_t lo, std::int64_t hi, std::int64_t count) {
  std::vector<UIndex> out;
  const std::int64_t stride = std::max<std::int64_t>(1, (hi - lo + count) / count);
  for (std::int64_t i = lo; i < hi; i += stride) out.push_back(static_cast<UIndex>(i));
  out.push_back(static_cast<UIndex>(hi));
  return out;
}

// Indices of probabilities in [0, 1]: all of 0..dense, then about 200 log-spaced ones up to
// the zero code, and the last two.
std::vector<UIndex> probability_indices(const UGamma& u, std::int64_t dense) {
  dense = std::min<std::int64_t>(dense, u.zero());
  std::vector<UIndex> out = range(0, dense, 2000);
  for (double x = static_cast<double>(dense); x < u.zero(); x *= 1.05)
    out.push_back(static_cast<UIndex>(x));
  out.push_back(u.zero() - 1);
  out.push_back(u.zero());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// ---------------------------------------------------------------------------
// Construction and conversions.

TEST(UGamma, ConstructorSetsTheRangeAndRejectsBadWidthsAndSteps) {
  const UGamma u;
  EXPECT_EQ(u.bits(), 16);
  EXPECT_EQ(u.steps_per_halving(), 16);
  EXPECT_EQ(u.zero(), 32767);
  EXPECT_EQ(u.min_index(), -32768);
  EXPECT_NEAR(u.gamma(), std::pow(2.0, -1.0 / 16.0), 1e-15);
  EXPECT_TRUE(u.is_zero(u.zero()));
  EXPECT_FALSE(u.is_zero(u.zero() - 1));
  EXPECT_FALSE(u.is_zero(u.min_index()));
  EXPECT_EQ(UGamma(8, 1).zero(), 127);
  EXPECT_EQ(UGamma(8, 1).min_index(), -128);
  EXPECT_DOUBLE_EQ(UGamma(8, 1).gamma(), 0.5);
  EXPECT_EQ(UGamma(31, 4096).zero(), 1073741823);
  EXPECT_EQ(UGamma(31, 4096).min_index(), -1073741824);
  EXPECT_NO_THROW(UGamma(31, 1));
  for (int bits : {-5, 0, 7, 32, 64}) EXPECT_THROW(UGamma(bits, 16), std::invalid_argument);
  for (int steps : {-1, 0, 4097, 1 << 20}) EXPECT_THROW(UGamma(16, steps), std::invalid_argument);
}

TEST(UGamma, ConversionsRoundTrip) {
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    // Exactly, while u_i is a normal double (2^-1000 .. 2^1000).
    const std::int64_t lo = std::max<std::int64_t>(u.min_index(), -1000LL * steps);
    const std::int64_t hi = std::min<std::int64_t>(u.zero() - 1, 1000LL * steps);
    for (UIndex i : range(lo, hi, 1000000))
      ASSERT_EQ(u.from_probability(u.to_probability(i)), i) << name(u);
    for (UIndex i : range(u.min_index(), u.zero(), 2000000))
      ASSERT_EQ(u.from_log(u.to_log(i)), i) << name(u);
    // Nearest index: p between u_i and u_(i+1) goes to the nearer one (in the log).
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    long double worst = 0.0L;
    const Oracle o(u);
    for (int trial = 0; trial < 100000; ++trial) {
      const double p = std::exp(-unit(rng) * 40.0);
      const long double exact = -std::log(static_cast<long double>(p)) / o.step;
      if (exact >= u.zero() - 0.5L) {
        ASSERT_EQ(u.from_probability(p), u.zero());
        continue;
      }
      const long double error = std::fabs(u.from_probability(p) - exact);
      ASSERT_LE(error, 0.5L + kSlack) << name(u) << " " << p;
      worst = std::max(worst, error);
    }
    report("from_probability", u, worst);
  }
}

TEST(UGamma, ConversionsOfTheExtremes) {
  const UGamma u;
  EXPECT_EQ(u.from_probability(0.0), u.zero());
  EXPECT_EQ(u.from_probability(-0.0), u.zero());
  EXPECT_EQ(u.from_probability(1.0), 0);
  EXPECT_EQ(u.from_probability(0.5), 16);
  EXPECT_EQ(u.from_probability(2.0), -16);
  EXPECT_EQ(u.from_probability(std::numeric_limits<double>::infinity()), u.min_index());
  EXPECT_EQ(u.from_probability(std::numeric_limits<double>::denorm_min()), 1074 * 16);
  EXPECT_EQ(u.to_probability(u.zero()), 0.0);
  EXPECT_EQ(u.to_log(u.zero()), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(u.from_log(-std::numeric_limits<double>::infinity()), u.zero());
  EXPECT_EQ(u.from_log(1e300), u.min_index());
  EXPECT_EQ(u.from_log(-1e300), u.zero());
  EXPECT_DOUBLE_EQ(u.to_probability(-16), 2.0);
  EXPECT_DOUBLE_EQ(u.to_probability(32), 0.25);
  EXPECT_THROW(u.from_probability(std::nan("")), std::invalid_argument);
  EXPECT_THROW(u.from_probability(-1.0), std::invalid_argument);
  EXPECT_THROW(u.from_probability(-1e-300), std::invalid_argument);
  EXPECT_THROW(u.from_probability(-std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW(u.from_log(std::nan("")), std::invalid_argument);
  // (8, 1): 2^-126 is the smallest non-zero probability; 2^-126.6 rounds to the zero code.
  const UGamma coarse(8, 1);
  EXPECT_EQ(coarse.from_probability(std::ldexp(1.0, -126)), 126);
  EXPECT_EQ(coarse.from_probability(std::exp2(-126.4)), 126);
  EXPECT_EQ(coarse.from_probability(std::exp2(-126.6)), coarse.zero());
  EXPECT_EQ(coarse.from_probability(1e-300), coarse.zero());
  EXPECT_EQ(coarse.from_probability(1e300), coarse.min_index());
}

// ---------------------------------------------------------------------------
// Multiplication and division: index arithmetic.

TEST(UGamma, MultiplicationAndDivisionAreExactIndexArithmetic) {
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    const std::vector<UIndex> indices = range(u.min_index(), u.zero(), 600);
    for (UIndex i : indices)
      for (UIndex j : indices) {
        const std::int64_t sum = std::int64_t{i} + j, difference = std::int64_t{i} - j;
        const UIndex product = u.multiply(i, j), quotient = u.divide(i, j);
        ASSERT_EQ(product, u.multiply(j, i));
        if (u.is_zero(i) || u.is_zero(j)) {
          ASSERT_EQ(product, u.zero()) << name(u) << " " << i << " " << j;
        } else {
          ASSERT_EQ(product, std::clamp<std::int64_t>(sum, u.min_index(), u.zero()));
        }
        if (u.is_zero(j)) continue;  // dividing by 0 is outside the contract
        if (u.is_zero(i)) {
          ASSERT_EQ(quotient, u.zero());
        } else {
          ASSERT_EQ(quotient, std::clamp<std::int64_t>(difference, u.min_index(), u.zero()));
          if (sum > u.min_index() && sum < u.zero()) {
            ASSERT_EQ(u.divide(product, j), i);
          }
        }
        // The probabilities, where doubles hold them.
        if (!u.is_zero(i) && !u.is_zero(j) && std::abs(i) < 1000 * steps &&
            std::abs(j) < 1000 * steps && std::abs(sum) < 1000 * steps && sum < u.zero() &&
            sum > u.min_index()) {
          ASSERT_NEAR(u.to_probability(product) / (u.to_probability(i) * u.to_probability(j)), 1.0,
                      1e-12);
        }
      }
    EXPECT_EQ(u.divide(5, 5), 0);
  }
}

TEST(UGamma, MultiplicationAndDivisionSaturateAtBothEnds) {
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    const UIndex z = u.zero(), m = u.min_index();
    // Past the zero code: underflow to probability 0.
    EXPECT_EQ(u.multiply(z - 1, 1), z);
    EXPECT_EQ(u.multiply(z - 1, z - 1), z);
    EXPECT_EQ(u.multiply(z / 2 + 1, z / 2 + 1), z);
    EXPECT_EQ(u.divide(z - 1, -1), z);
    EXPECT_EQ(u.divide(0, m), z);
    // Below the smallest index: the largest representable value.
    EXPECT_EQ(u.multiply(m, -1), m);
    EXPECT_EQ(u.multiply(m, m), m);
    EXPECT_EQ(u.divide(m, 1), m);
    EXPECT_EQ(u.divide(m + 1, z - 1), m);
    EXPECT_EQ(u.divide(-1, z - 1), m + 1);
    // The zero code absorbs, even against the largest value.
    EXPECT_EQ(u.multiply(m, z), z);
    EXPECT_EQ(u.multiply(z, m), z);
    EXPECT_EQ(u.multiply(z, z), z);
    EXPECT_EQ(u.divide(z, m), z);
    EXPECT_EQ(u.divide(z, 1), z);
    // 1 is the identity.
    EXPECT_EQ(u.multiply(0, m), m);
    EXPECT_EQ(u.multiply(z - 1, 0), z - 1);
    EXPECT_EQ(u.divide(z - 1, 0), z - 1);
  }
}

// ---------------------------------------------------------------------------
// Addition (Zech logarithm Phi_plus).

TEST(UGamma, AdditionIsWithinHalfAStepOfTheExactSumAndCommutes) {
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    const Oracle o(u);
    const std::int64_t table = static_cast<std::int64_t>(u.phi_plus_size());
    // A range of both signs wider than the table: [-200, 2000] for the default.
    const std::int64_t lo =
        std::max<std::int64_t>(u.min_index(), -std::max<std::int64_t>(200, 2 * table));
    const std::int64_t hi =
        std::min<std::int64_t>(u.zero() - 1, lo + std::max<std::int64_t>(2200, 4 * table));
    const std::vector<UIndex> indices = range(lo, hi, 2400);
    // The exact Phi_plus of every difference in it.
    std::vector<long double> exact_phi(static_cast<std::size_t>(hi - lo + 1));
    for (std::size_t d = 0; d < exact_phi.size(); ++d) exact_phi[d] = o.phi_plus(d);
    long double worst = 0.0L;
    std::int64_t pairs = 0;
    for (UIndex i : indices)
      for (UIndex j : indices) {
        const UIndex sum = u.add(i, j);
        ASSERT_EQ(sum, u.add(j, i)) << name(u) << " " << i << " " << j;
        const long double exact =
            std::min(i, j) - exact_phi[static_cast<std::size_t>(std::abs(std::int64_t{i} - j))];
        if (exact < u.min_index() - 0.5L) {
          ASSERT_EQ(sum, u.min_index());
          continue;
        }
        const long double error = std::fabs(sum - exact);
        ASSERT_LE(error, 0.5L + kSlack) << name(u) << " " << i << " (+) " << j;
        worst = std::max(worst, error);
        ++pairs;
      }
    // Every difference the index range allows, from a few starting points.
    const std::int64_t widest = std::int64_t{u.zero()} - 1 - u.min_index();
    for (std::int64_t d = 0; d <= std::min<std::int64_t>(widest, table + 5000); ++d)
      for (std::int64_t low : {std::int64_t{u.min_index()}, std::int64_t{0}, u.zero() - 1 - d}) {
        if (low < u.min_index() || low + d > u.zero() - 1) continue;
        const UIndex i = static_cast<UIndex>(low), j = static_cast<UIndex>(low + d);
        const long double exact = o.add(i, j);
        const UIndex sum = u.add(i, j);
        if (exact < u.min_index() - 0.5L) {
          ASSERT_EQ(sum, u.min_index());
          continue;
        }
        const long double error = std::fabs(sum - exact);
        ASSERT_LE(error, 0.5L + kSlack) << name(u) << " " << i << " (+) " << j;
        worst = std::max(worst, error);
      }
    report("add", u, worst);
    EXPECT_GT(pairs, 50000);
  }
}

TEST(UGamma, AdditionWithTheZeroCodeIsTheIdentity) {
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    for (UIndex i : range(u.min_index(), u.zero(), 100000)) {
      ASSERT_EQ(u.add(u.zero(), i), i);
      ASSERT_EQ(u.add(i, u.zero()), i);
    }
    EXPECT_EQ(u.add(u.zero(), u.zero()), u.zero());
    // Doubling is one halving step down, exactly.
    EXPECT_EQ(u.add(3 * steps, 3 * steps), 2 * steps);
    // The largest values saturate.
    EXPECT_EQ(u.add(u.min_index(), u.min_index()), u.min_index());
  }
}

TEST(UGamma, PhiPlusTableEndsWhereItRoundsToZero) {
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    const Oracle o(u);
    const auto table = static_cast<UIndex>(u.phi_plus_size());
    ASSERT_GE(table, 1);
    EXPECT_EQ(u.phi_plus(0), steps);  // u + u = 2u
    EXPECT_EQ(u.phi_plus(-1), 0);
    for (UIndex d = 1; d < table; ++d) ASSERT_LE(u.phi_plus(d), u.phi_plus(d - 1));
    // The last entry is >= 1 and the first one past it is 0, as the exact values say.
    EXPECT_GE(u.phi_plus(table - 1), 1) << name(u);
    EXPECT_EQ(u.phi_plus(table), 0);
    EXPECT_GE(o.phi_plus(table - 1), 0.5L - kSlack);
    EXPECT_LT(o.phi_plus(table), 0.5L + kSlack);
    // From there on a sum is its larger term, min(i, j).
    for (std::int64_t d = table; d < table + 1000; ++d)
      for (std::int64_t low : {std::int64_t{u.min_index()}, std::int64_t{-1}, std::int64_t{0}}) {
        if (low + d > u.zero() - 1) continue;
        const UIndex i = static_cast<UIndex>(low), j = static_cast<UIndex>(low + d);
        ASSERT_EQ(u.add(i, j), i) << name(u);
        ASSERT_EQ(u.add(j, i), i) << name(u);
      }
    // The table covers every difference that needs it, even past half the index range.
    const std::int64_t widest = std::int64_t{u.zero()} - 1 - u.min_index();
    if (o.phi_plus(widest) >= 0.5L) {
      EXPECT_GT(static_cast<std::int64_t>(u.phi_plus_size()), widest) << name(u);
    }
  }
}

// ---------------------------------------------------------------------------
// Complement (Phi_minus).

TEST(UGamma, ComplementIsWithinHalfAStep) {
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    const Oracle o(u);
    const auto table = static_cast<std::int64_t>(u.phi_minus_size());
    // Every index of the table and 5000 past it, then a stride to the zero code.
    std::vector<UIndex> indices =
        range(1, std::min<std::int64_t>(u.zero() - 1, table + 5000), 100000);
    for (UIndex i : range(table, u.zero() - 1, 100000)) indices.push_back(i);
    long double worst = 0.0L;
    for (UIndex i : indices) {
      const long double exact = o.phi_minus(i);
      const UIndex c = u.complement(i);
      if (exact >= u.zero() - 0.5L) {
        ASSERT_EQ(c, u.zero()) << name(u) << " " << i;
        continue;
      }
      const long double error = std::fabs(c - exact);
      ASSERT_LE(error, 0.5L + kSlack) << name(u) << " " << i;
      worst = std::max(worst, error);
      if (i >= table) {
        ASSERT_EQ(c, 0) << name(u) << " " << i;
      }
    }
    report("complement", u, worst);
    // The edges: 1 - 1 = 0, 1 - 0 = 1, and a value above 1 is taken as 1.
    EXPECT_EQ(u.complement(0), u.zero());
    EXPECT_EQ(u.complement(u.zero()), 0);
    EXPECT_EQ(u.complement(-1), u.zero());
    EXPECT_EQ(u.complement(u.min_index()), u.zero());
    // The table ends where Phi_minus rounds to 0 (or at the zero code).
    ASSERT_GE(table, 2);
    EXPECT_GE(u.complement(static_cast<UIndex>(table - 1)), 1);
    if (table < u.zero()) {
      EXPECT_EQ(u.complement(static_cast<UIndex>(table)), 0);
      EXPECT_LT(o.phi_minus(table), 0.5L + kSlack);
    }
    // 1 - 1/2 = 1/2 exactly.
    if (steps < u.zero()) {
      EXPECT_EQ(u.complement(steps), steps);
    }
  }
}

// ---------------------------------------------------------------------------
// Fusion.

TEST(UGamma, FusionIsWithinOneAndAHalfStepsAndSymmetric) {
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    const Oracle o(u);
    const std::vector<UIndex> indices =
        probability_indices(u, 4 * static_cast<std::int64_t>(u.phi_minus_size()));
    std::vector<long double> exact_minus(indices.size());
    for (std::size_t k = 0; k < indices.size(); ++k) exact_minus[k] = o.phi_minus(indices[k]);
    long double worst = 0.0L;
    for (std::size_t a = 0; a < indices.size(); ++a)
      for (std::size_t b = 0; b <= a; ++b) {
        const UIndex i = indices[a], j = indices[b];
        const UIndex f = u.fuse(i, j);
        ASSERT_EQ(f, u.fuse(j, i)) << name(u) << " " << i << " " << j;
        if (i == 0 || j == 0 || u.is_zero(i) || u.is_zero(j)) continue;  // the edges, below
        const long double x = i + j - exact_minus[a] - exact_minus[b];
        const long double exact = std::max(x, 0.0L) + o.phi_plus(std::fabs(x));
        if (f == u.zero() && exact >= u.zero() - 1.5L - kSlack) continue;  // saturated
        const long double error = std::fabs(f - exact);
        ASSERT_LE(error, 1.5L + kSlack)
            << name(u) << " F(" << i << ", " << j << ") exact " << static_cast<double>(exact);
        worst = std::max(worst, error);
      }
    report("fuse", u, worst);
  }
}

TEST(UGamma, FusionWithOneHalfIsTheIdentityWithinOneStep) {
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    long double worst = 0.0L;
    for (UIndex i : probability_indices(u, 4 * static_cast<std::int64_t>(u.phi_minus_size()))) {
      const UIndex f = u.fuse(i, steps);
      if (u.is_zero(i) || i == 0) {
        ASSERT_EQ(f, i);
        continue;
      }
      if (f == u.zero() && i >= u.zero() - 1) continue;  // saturated
      const long double error = std::abs(f - i);
      ASSERT_LE(error, 1.0L) << name(u) << " " << i;
      worst = std::max(worst, error);
    }
    report("fuse with 1/2", u, worst);
  }
}

TEST(UGamma, FusionEdges) {
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    for (UIndex j : probability_indices(u, 1000)) {
      if (u.is_zero(j)) continue;
      // Certainty wins over anything but its contradiction; 0 absorbs.
      if (j > 0) {
        EXPECT_EQ(u.fuse(0, j), 0) << name(u) << " " << j;
      }
      EXPECT_EQ(u.fuse(u.zero(), j), u.zero()) << name(u) << " " << j;
    }
    EXPECT_EQ(u.fuse(0, 0), 0);
    EXPECT_EQ(u.fuse(0, u.zero()), u.zero());  // 1 against 0: no answer, the zero code
    EXPECT_EQ(u.fuse(u.zero(), u.zero()), u.zero());
    EXPECT_EQ(u.fuse(steps, steps), steps);  // 1/2 and 1/2
  }
}

TEST(UGamma, FusionOfATinyProbabilityWithANearlyCertainOneIsNotLostToUnderflow) {
  // u_1 u_(zero-1) is past the zero code, but its odds against (1 - u_1) are not: F is
  // about u_(zero-1) / (1 - u_1), inside the range.
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    const Oracle o(u);
    for (UIndex j : {u.zero() - 1, u.zero() - 2, u.zero() / 2 + 7})
      for (UIndex i : {1, 2, 3}) {
        const long double exact = o.fuse(i, j);
        if (exact >= u.zero() - 1.5L) continue;
        EXPECT_LE(std::fabs(u.fuse(i, j) - exact), 1.5L + kSlack)
            << name(u) << " F(" << i << ", " << j << ") exact " << static_cast<double>(exact);
      }
  }
}

TEST(UGamma, FusionMatchesTheDoubleFormula) {
  // The user's view: probabilities in, probability out, for p where doubles are accurate.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0.001, 0.999);
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    long double worst = 0.0L;
    for (int trial = 0; trial < 20000; ++trial) {
      const UIndex i = u.from_probability(unit(rng)), j = u.from_probability(unit(rng));
      if (u.is_zero(i) || u.is_zero(j) || i == 0 || j == 0) continue;
      const double p = u.to_probability(i), q = u.to_probability(j);
      const double fused = p * q / (p * q + (1.0 - p) * (1.0 - q));
      const long double exact = std::log(fused) / std::log(u.gamma());
      const UIndex f = u.fuse(i, j);
      if (f == u.zero() && exact >= u.zero() - 1.5L - 1e-6L) continue;  // saturated
      const long double error = std::fabs(f - exact);
      ASSERT_LE(error, 1.5L + 1e-6L) << name(u) << " " << p << " " << q;
      worst = std::max(worst, error);
    }
    report("fuse against double", u, worst);
  }
}

// ---------------------------------------------------------------------------
// Sums of many terms and normalization.

// Sum by a chain of additions, as a user would write it: n - 1 roundings in a row.
UIndex chain_sum(const UGamma& u, const std::vector<UIndex>& terms) {
  UIndex total = u.zero();
  for (UIndex t : terms) total = u.add(total, t);
  return total;
}

// Pairwise sum: ceil(log2 n) roundings on any path.
UIndex pairwise_sum(const UGamma& u, std::vector<UIndex> terms) {
  while (terms.size() > 1) {
    std::vector<UIndex> next((terms.size() + 1) / 2);
    for (std::size_t k = 0; k < next.size(); ++k)
      next[k] = 2 * k + 1 < terms.size() ? u.add(terms[2 * k], terms[2 * k + 1]) : terms[2 * k];
    terms = std::move(next);
  }
  return terms.front();
}

TEST(UGamma, NormalizedSumsOfManyTermsAreOneWithinHalfAStepPerAddition) {
  std::mt19937_64 rng(29);
  for (const auto [bits, steps] : kSettings) {
    const UGamma u(bits, steps);
    const Oracle o(u);
    // Probabilities from 1 down to 2^-10 (or half the index range).
    const UIndex top = std::min<UIndex>(u.zero() / 2, 10 * steps);
    std::uniform_int_distribution<UIndex> index(0, top);
    long double worst_per_addition = 0.0L;
    int checked = 0;
    for (int n : {2, 3, 16, 256, 4096}) {
      long double worst_chain = 0.0L, worst_pairwise = 0.0L, worst_sum = 0.0L;
      int trials = 0, normalized = 0;
      for (int trial = 0; trial < (n > 256 ? 10 : 50); ++trial) {
        std::vector<UIndex> terms(static_cast<std::size_t>(n));
        for (UIndex& t : terms) t = index(rng);
        const long double exact = o.sum(terms);
        const UIndex total = chain_sum(u, terms);
        // The partial sums only grow, so none saturated unless the total did.
        if (total == u.min_index() || exact < u.min_index() + 0.5L) continue;
        const long double bound = 0.5L * (n - 1);
        const long double error = std::fabs(total - exact);
        ASSERT_LE(error, bound + kSlack) << name(u) << " n " << n;
        worst_chain = std::max(worst_chain, error);
        worst_per_addition = std::max(worst_per_addition, error / (n - 1));
        const long double pairwise_bound = 0.5L * std::ceil(std::log2(static_cast<long double>(n)));
        const long double pairwise_error = std::fabs(pairwise_sum(u, terms) - exact);
        ASSERT_LE(pairwise_error, pairwise_bound + kSlack) << name(u) << " n " << n;
        worst_pairwise = std::max(worst_pairwise, pairwise_error);
        ++trials;
        // A normalized term past the zero code underflows to 0 (a range limit, not a rounding).
        if (std::any_of(terms.begin(), terms.end(),
                        [&](UIndex t) { return u.is_zero(u.divide(t, total)); })) {
          continue;
        }
        // Normalized: exact divisions, so the probabilities sum to gamma^(exact - total).
        long double sum = 0.0L;
        double reference_total = 0.0;
        for (UIndex t : terms) reference_total += u.to_probability(t);
        long double worst_term = 0.0L;
        for (UIndex t : terms) {
          const double p = u.to_probability(u.divide(t, total));
          sum += p;
          const double reference = u.to_probability(t) / reference_total;  // what doubles give
          worst_term = std::max(worst_term, std::fabs(std::log(p / reference)) / o.step);
        }
        const long double sum_error = std::fabs(std::log(sum)) / o.step;
        ASSERT_LE(sum_error, bound + kSlack) << name(u) << " n " << n;
        ASSERT_LE(std::fabs(sum_error - error), 1e-6L);
        ASSERT_LE(worst_term, bound + kSlack);
        EXPECT_NEAR(static_cast<double>(sum), 1.0,
                    std::pow(u.gamma(), -static_cast<double>(bound)) - 1.0);
        worst_sum = std::max(worst_sum, std::fabs(sum - 1.0L));
        ++checked;
        ++normalized;
      }
      if (trials == 0) {
        std::printf("[ugamma] sum of %4d terms          %-11s saturates, not checked\n", n,
                    name(u).c_str());
        continue;
      }
      std::printf(
          "[ugamma] sum of %4d terms          %-11s chain %.4Lf steps (bound %.1f), pairwise "
          "%.4Lf (bound %.1f), %d trials; |normalized sum - 1| <= %.3Lg (%d trials)\n",
          n, name(u).c_str(), worst_chain, 0.5 * (n - 1), worst_pairwise,
          0.5 * std::ceil(std::log2(n)), trials, worst_sum, normalized);
    }
    EXPECT_GE(checked, 100) << name(u);
    report("sum, error per addition", u, worst_per_addition);
  }
}

TEST(UGamma, AChainOfAdditionsDropsTermsPastTheTable) {
  // Once the partial sum exceeds a term by phi_plus_size() steps or more, adding it changes
  // nothing (2^5.5, about 45 times, for the default): the chain's error grows with n, which the
  // (n - 1) / 2 bound allows. Adding pairwise keeps it within ceil(log2 n) / 2.
  const UGamma u;
  const std::vector<UIndex> terms(4096, 100);  // 4096 u_100: exactly u_(100 - 12 * 16) = u_-92
  EXPECT_EQ(pairwise_sum(u, terms), -92);
  const UIndex chain = chain_sum(u, terms);
  EXPECT_GT(chain, 100 - static_cast<UIndex>(u.phi_plus_size()) - 1);
  EXPECT_EQ(u.add(chain, 100), chain);
}

}  // namespace
}  // namespace intgrid
