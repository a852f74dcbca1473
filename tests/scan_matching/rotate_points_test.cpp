#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "kestrel/scan_matching/rotate_points.hpp"

namespace kestrel::scan_matching {
namespace {

constexpr int kN = 203;  // not a multiple of four: the SIMD forms leave a scalar tail

RotationQ rotation(double theta, int f, int32_t cx, int32_t cy, int32_t fx, int32_t fy) {
  RotationQ r;
  r.c = trig_q15(std::cos(theta));
  r.s = trig_q15(std::sin(theta));
  r.cx = cx;
  r.cy = cy;
  r.fx = fx;
  r.fy = fy;
  r.shift = f + kTrigBits;
  return r;
}

// The SIMD transform (SSE2 on the host, NEON on Overo, scalar on Verdex) gives exactly the
// scalar formula, on random points over the whole int16 range (the extremes included), every
// point precision, signs of the products and centre fractions.
TEST(RotatePoints, LanesEqualScalar) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> coord(-32767, 32767), cell(-5000, 5000);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::array<int16_t, 2 * kN> pxy{};
  for (int trial = 0; trial < 40; ++trial) {
    for (auto& v : pxy) v = static_cast<int16_t>(coord(rng));
    pxy[0] = 32767;
    pxy[1] = -32767;
    const int f = trial % 9;
    std::uniform_int_distribution<int32_t> frac(0, (1 << (f + kTrigBits)) - 1);
    // Exact quarter turns put cos or sin at +-32767, the largest magnitude.
    const double theta = trial < 4 ? trial * M_PI / 2 : angle(rng);
    const RotationQ r = rotation(theta, f, cell(rng), cell(rng), frac(rng), frac(rng));
    std::array<int32_t, kN> x{}, y{}, xs{}, ys{};
    rotate_points(pxy.data(), kN, r, x.data(), y.data());
    rotate_points_scalar(pxy.data(), 0, kN, r, xs.data(), ys.data());
    EXPECT_EQ(x, xs) << trial;
    EXPECT_EQ(y, ys) << trial;
  }
}

// The integer transform is the rotation to within its quantisation: Q15 cos and sin, points
// in 1/2^F cell, floor to the cell.
TEST(RotatePoints, MatchesTheRotationWithinQuantisation) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), pos(-3800, 3800);
  const int f = 3;  // a UTM-30LX point at 29 m on 7.5 mm cells
  std::array<int16_t, 2 * kN> pxy{};
  std::array<double, 2 * kN> exact{};
  for (int i = 0; i < 2 * kN; ++i) {
    exact[static_cast<std::size_t>(i)] = pos(rng);
    pxy[static_cast<std::size_t>(i)] = static_cast<int16_t>(std::lround(exact[static_cast<std::size_t>(i)] * (1 << f)));
  }
  for (int trial = 0; trial < 24; ++trial) {
    // Near 0 and a quarter turn cos or sin saturates at 32767 (1 - 2^-15): the worst cases.
    const double th = trial < 4 ? trial * M_PI / 2 + 1e-6 : angle(rng);
    const RotationQ r = rotation(th, f, 700, -300, 0, 0);
    std::array<int32_t, kN> x{}, y{};
    rotate_points(pxy.data(), kN, r, x.data(), y.data());
    for (int i = 0; i < kN; ++i) {
      const double px = exact[static_cast<std::size_t>(2 * i)], py = exact[static_cast<std::size_t>(2 * i + 1)];
      const double ex = 700 + std::cos(th) * px - std::sin(th) * py, ey = -300 + std::sin(th) * px + std::cos(th) * py;
      // From the true value: the point's rounding (1/16 cell per axis, sqrt 2 / 16 rotated)
      // plus cos and sin within 2^-15 each (saturation included) on |px| + |py| <= 7600
      // cells: 0.09 + 0.23 cells, then the floor.
      EXPECT_NEAR(x[static_cast<std::size_t>(i)] + 0.5, ex, 0.5 + 0.33) << i;
      EXPECT_NEAR(y[static_cast<std::size_t>(i)] + 0.5, ey, 0.5 + 0.33) << i;
    }
  }
}

}  // namespace
}  // namespace kestrel::scan_matching
