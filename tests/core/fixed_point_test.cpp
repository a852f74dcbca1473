#include "kestrel/core/fixed_point.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace kestrel {
namespace {

TEST(Fixed, ConversionRoundsToNearest) {
  EXPECT_EQ(Q16::from_double(1.0).raw(), 65536);
  EXPECT_EQ(Q16::from_double(0.5 / 65536.0).raw(), 1);     // half an LSB rounds away from zero
  EXPECT_EQ(Q16::from_double(-0.5 / 65536.0).raw(), -1);
  EXPECT_EQ(Q16::from_double(0.49 / 65536.0).raw(), 0);
  EXPECT_EQ(Q16::from_double(std::nan("")).raw(), 0);
  EXPECT_EQ(Q16::from_double(2.5).round_to_int(), 3);
  EXPECT_EQ(Q16::from_double(-2.5).round_to_int(), -3);
  EXPECT_EQ(Q16::from_double(-2.4).round_to_int(), -2);
}

TEST(Fixed, SaturatesInsteadOfWrapping) {
  EXPECT_EQ(Q16::from_double(1e9), Q16::max());
  EXPECT_EQ(Q16::from_double(-1e9), Q16::min());
  EXPECT_EQ(Q16::max() + Q16::from_int(1), Q16::max());
  EXPECT_EQ(Q16::min() - Q16::from_int(1), Q16::min());
  EXPECT_EQ(Q16::from_int(30000) * Q16::from_int(30000), Q16::max());
  EXPECT_EQ(Q16::from_int(-30000) * Q16::from_int(30000), Q16::min());
  EXPECT_EQ(-Q16::min(), Q16::max());
  EXPECT_EQ(Q16::from_int(1) / Q16{}, Q16::max());
  EXPECT_EQ(Q16::from_int(-1) / Q16{}, Q16::min());
  EXPECT_EQ(Q16{} / Q16{}, Q16{});
  EXPECT_EQ(Q16::from_int(100000), Q16::max());
}

TEST(Fixed, ArithmeticAgreesWithDoubleWithinHalfAnLsb) {
  uint32_t seed = 11;
  auto rnd = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return (static_cast<double>(seed >> 8) / static_cast<double>(1u << 24) - 0.5) * 200.0;
  };
  const double lsb = 1.0 / 65536.0;
  for (int i = 0; i < 10000; ++i) {
    const Q16 a = Q16::from_double(rnd()), b = Q16::from_double(rnd());
    const double da = a.to_double(), db = b.to_double();
    EXPECT_NEAR((a + b).to_double(), da + db, 1e-12);
    EXPECT_NEAR((a - b).to_double(), da - db, 1e-12);
    EXPECT_NEAR((a * b).to_double(), da * db, 0.5 * lsb + 1e-12);
    if (std::fabs(db) > 0.01) {
      const double q = da / db;
      if (std::fabs(q) < 30000) {
        EXPECT_NEAR((a / b).to_double(), q, 0.5 * lsb + 1e-9);
      }
    }
  }
}

TEST(Fixed, Q24HoldsGainsPrecisely) {
  const Q24 k = Q24::from_double(0.123456789);
  EXPECT_NEAR(k.to_double(), 0.123456789, 1.0 / (1 << 25));
  EXPECT_NEAR((k * Q24::from_double(-2.0)).to_double(), -0.246913578, 1.0 / (1 << 24));
}

}  // namespace
}  // namespace kestrel
