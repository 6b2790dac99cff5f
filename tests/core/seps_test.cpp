#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "intgrid/core/seps.hpp"

using namespace intgrid::core;

namespace intgrid {
namespace {

const SepsCodec kCodecs[] = {SepsCodec(8, 0.02), SepsCodec(8, 0.2), SepsCodec(4, 0.1),
                             SepsCodec(16, 0.001), SepsCodec(12, 0.4)};

TEST(Seps, QuantizingAnElementGivesItsIndex) {
  for (const SepsCodec& codec : kCodecs)
    for (int n = -codec.max_index(); n <= codec.max_index(); ++n) {
      // Past log-odds 30 a double cannot tell p_n from p_n+1 near 1, and past
      // -700 p_n underflows.
      if (n * codec.lambda() > 30.0 || n * codec.lambda() < -700.0) continue;
      // p_-n is a double with all its precision, so it comes back exactly; p_n
      // near 1 rounds, perhaps just below the real p_n, and then must give n - 1.
      const int conservative = codec.quantize_conservative(codec.probability(n));
      if (n <= 0) {
        ASSERT_EQ(conservative, n) << codec.bits();
      } else {
        ASSERT_TRUE(conservative == n || conservative == n - 1) << codec.bits() << " " << n;
      }
      ASSERT_EQ(codec.quantize_nearest(codec.probability(n)), n) << codec.bits();
    }
}

TEST(Seps, ConservativeQuantizationIsSymmetric) {
  // p and 1 - p are both exact for p = k / 2^20.
  for (const SepsCodec& codec : kCodecs)
    for (int k = 1; k < (1 << 20); k += 97) {
      const double p = std::ldexp(static_cast<double>(k), -20);
      ASSERT_EQ(codec.quantize_conservative(p), -codec.quantize_conservative(1.0 - p)) << p;
    }
}

TEST(Seps, ElementsAreSymmetricAndStartAtOneHalf) {
  const SepsCodec codec(8, 0.05);
  EXPECT_DOUBLE_EQ(codec.probability(0), 0.5);
  EXPECT_NEAR(codec.probability(1), 0.55, 1e-15);
  for (int n = 1; n <= codec.max_index(); ++n)
    EXPECT_NEAR(codec.probability(-n), 1.0 - codec.probability(n), 1e-15);
  EXPECT_EQ(codec.max_index(), 127);
  EXPECT_EQ(SepsCodec(16, 0.05).max_index(), 32767);
}

TEST(Seps, IndexAdditionIsBayesianFusionOfTheElements) {
  for (const SepsCodec& codec : kCodecs) {
    // Only indices whose probabilities a double holds apart from 0 and 1.
    const int m = std::min(codec.max_index(), static_cast<int>(15.0 / codec.lambda()));
    for (int i = -m; i <= m; i += 1 + m / 50)
      for (int j = -m; j <= m; j += 1 + m / 50) {
        const double fused = fuse_probabilities(codec.probability(i), codec.probability(j));
        const int sum = codec.fuse(i, j);
        if (std::abs(i + j) <= codec.max_index()) {
          // Not closer: 1 - p loses digits as p nears 1 in the floating-point fusion.
          ASSERT_NEAR(codec.probability(sum), fused, 1e-9) << i << "+" << j;
        } else {
          ASSERT_EQ(sum, i + j > 0 ? codec.max_index() : -codec.max_index());
        }
      }
  }
}

TEST(Seps, GridFusionSaturatesAtTheSymmetricBound) {
  const std::vector<std::int8_t> a = {100, -100, 127, -127, 5, 0};
  const std::vector<std::int8_t> b = {100, -100, 1, -1, -9, 0};
  std::vector<std::int8_t> out(a.size());
  fuse_indices<std::int8_t>(a, b, out, 127);
  EXPECT_EQ(out, (std::vector<std::int8_t>{127, -127, 127, -127, -4, 0}));
}

TEST(Seps, ConservativeQuantizationIsNeverMoreConfidentAndLosesLessThanOneStep) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> log_odds(-40.0, 40.0);
  for (const SepsCodec& codec : kCodecs)
    for (int trial = 0; trial < 20000; ++trial) {
      const double l = log_odds(rng);
      const double p = logistic(l);
      const int n = codec.quantize_conservative(p);
      const double ln = n * codec.lambda();
      ASSERT_LE(std::abs(ln), std::abs(logit(p)) + 1e-9) << p;  // never more confident
      ASSERT_TRUE(n == 0 || (n > 0) == (p > 0.5));
      if (std::abs(n) < codec.max_index()) {
        ASSERT_LT(std::abs(logit(p)) - std::abs(ln), codec.lambda());
      }
      const int nearest = codec.quantize_nearest(p);
      if (std::abs(nearest) < codec.max_index()) {
        ASSERT_LE(std::abs(logit(p) - nearest * codec.lambda()), 0.5 * codec.lambda() + 1e-9);
      }
    }
}

TEST(Seps, KFusionsStayWithinKStepsOfTheFloatingPointPipeline) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.02, 0.98);
  const SepsCodec codec(16, 0.01);
  for (int trial = 0; trial < 2000; ++trial) {
    const int k = 1 + trial % 40;
    double fused = 0.5;
    int index = 0;
    for (int i = 0; i < k; ++i) {
      const double p = unit(rng);
      fused = fuse_probabilities(fused, p);
      index = codec.fuse(index, codec.quantize_conservative(p));
    }
    ASSERT_LT(std::abs(index), codec.max_index());
    ASSERT_LT(std::abs(logit(fused) - index * codec.lambda()), k * codec.lambda());
  }
}

TEST(Seps, EpsChoices) {
  const SepsCodec confident = SepsCodec::for_confidence(8, 0.999);
  EXPECT_NEAR(confident.probability(confident.max_index()), 0.999, 1e-12);
  const SepsCodec levels = SepsCodec::for_levels(8, 0.9, 10);
  EXPECT_NEAR(levels.probability(10), 0.9, 1e-12);
  EXPECT_EQ(levels.quantize_nearest(0.9), 10);
}

TEST(Seps, ExtremesAndBadArguments) {
  const SepsCodec codec(8, 0.05);
  EXPECT_EQ(codec.quantize_conservative(0.0), -127);
  EXPECT_EQ(codec.quantize_conservative(1.0), 127);
  EXPECT_EQ(codec.quantize_conservative(1e-300), -127);
  EXPECT_EQ(codec.quantize_conservative(std::nan("")), 0);
  EXPECT_EQ(codec.quantize_conservative(0.5), 0);
  // Small probabilities keep their precision: p = 1e-20 is -46 in log-odds.
  const SepsCodec fine(16, 0.01);
  EXPECT_EQ(fine.quantize_conservative(1e-20),
            static_cast<int>(std::trunc(logit(1e-20) / fine.lambda())));
  EXPECT_THROW(SepsCodec(1, 0.1), std::invalid_argument);
  EXPECT_THROW(SepsCodec(17, 0.1), std::invalid_argument);
  EXPECT_THROW(SepsCodec(8, 0.5), std::invalid_argument);
  EXPECT_THROW(SepsCodec(8, -0.1), std::invalid_argument);
  // 1/2 + eps rounds to 1/2, or the indices' probabilities to fewer doubles than indices.
  EXPECT_THROW(SepsCodec(8, 1e-300), std::invalid_argument);
  EXPECT_THROW(SepsCodec(8, 1e-17), std::invalid_argument);
  // Far above that: every index its own probability, which quantizes back to it.
  const SepsCodec tiny(8, 1e-12);
  for (int n = -tiny.max_index(); n <= tiny.max_index(); ++n) {
    if (n <= 0) {
      EXPECT_EQ(tiny.quantize_conservative(tiny.probability(n)), n) << n;
    }
    EXPECT_EQ(tiny.quantize_nearest(tiny.probability(n)), n) << n;
  }
  EXPECT_THROW(SepsCodec::for_confidence(8, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace intgrid
