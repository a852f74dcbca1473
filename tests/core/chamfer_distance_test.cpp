#include "kestrel/core/chamfer_distance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <random>
#include <utility>

namespace kestrel::chamfer {
namespace {

// A 32 x 24 grid of whole-byte distances.
struct Grid {
  static constexpr int kW = 32, kH = 24;
  std::array<uint8_t, kW * kH> d{};
  int distance(int x, int y) const { return d[static_cast<std::size_t>(y * kW + x)]; }
  void lower(int x, int y, int v) { d[static_cast<std::size_t>(y * kW + x)] = static_cast<uint8_t>(v); }
};

// On an open grid the 3-4 chamfer distance of a step (dx, dy) is 3 max + min: the diagonal
// steps first, the straight ones after. The passes must give the nearest seed's, saturated.
int oracle(int dx, int dy) {
  dx = std::abs(dx);
  dy = std::abs(dy);
  return kPerCell * std::max(dx, dy) + (kDiagonal - kPerCell) * std::min(dx, dy);
}

TEST(ChamferDistance, IsTheNearestSeedsThreeFourDistanceForRandomSeeds) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    Grid g;
    g.d.fill(255);
    const int seeds = 1 + static_cast<int>(rng() % 6);
    std::array<std::pair<int, int>, 6> at{};
    for (int s = 0; s < seeds; ++s) {
      at[static_cast<std::size_t>(s)] = {static_cast<int>(rng() % Grid::kW), static_cast<int>(rng() % Grid::kH)};
      g.lower(at[static_cast<std::size_t>(s)].first, at[static_cast<std::size_t>(s)].second, 0);
    }
    propagate(g, 0, 0, Grid::kW - 1, Grid::kH - 1);
    for (int y = 0; y < Grid::kH; ++y) {
      for (int x = 0; x < Grid::kW; ++x) {
        int want = 255;
        double euclid = INFINITY;
        for (int s = 0; s < seeds; ++s) {
          const auto [sx, sy] = at[static_cast<std::size_t>(s)];
          want = std::min(want, oracle(x - sx, y - sy));
          euclid = std::min(euclid, std::hypot(x - sx, y - sy));
        }
        ASSERT_EQ(g.distance(x, y), want) << "trial " << trial << " cell " << x << "," << y;
        // Within 8 % of three times the Euclidean distance (Borgefors' bound for 3-4).
        if (want < 255) {
          EXPECT_NEAR(want, 3.0 * euclid, 0.24 * euclid + 1e-9);
        }
      }
    }
  }
}

// Cells outside the box are neither read (a seed there, touching every side, is not seen) nor
// written; distances inside saturate at the cap the cells held.
TEST(ChamferDistance, KeepsToItsBoxAndSaturatesAtTheCap) {
  Grid g;
  g.d.fill(40);
  for (const auto& [x, y] : {std::pair{4, 10}, {21, 10}, {12, 4}, {12, 16}, {4, 4}, {21, 16}}) g.lower(x, y, 0);
  g.lower(6, 6, 0);  // inside
  propagate(g, 5, 5, 20, 15);
  EXPECT_EQ(g.distance(4, 10), 0);   // untouched
  EXPECT_EQ(g.distance(4, 11), 40);
  EXPECT_EQ(g.distance(21, 11), 40);
  EXPECT_EQ(g.distance(5, 5), oracle(1, 1));  // from (6, 6), not (4, 4)
  EXPECT_EQ(g.distance(5, 10), oracle(1, 4));
  EXPECT_EQ(g.distance(12, 5), oracle(6, 1));
  EXPECT_EQ(g.distance(9, 6), 9);
  EXPECT_EQ(g.distance(12, 15), 33);  // 3 * 9 + 6, not 3 from (12, 16)
  EXPECT_EQ(g.distance(20, 10), 40);  // 3 * 14 + 4 = 46, saturated; not 3 from (21, 10)
  EXPECT_EQ(g.distance(20, 15), 40);  // 3 * 14 + 9 = 51, saturated
}

TEST(ChamferDistance, UnitsOfMetresRoundUpAndSaturate) {
  EXPECT_EQ(units_of(0.3f, 0.12f, 255), 8);   // 7.5 -> 8
  EXPECT_EQ(units_of(0.36f, 0.12f, 255), 9);  // float noise is not rounded up
  EXPECT_EQ(units_of(0.5f, 0.1f, 127), 15);
  EXPECT_EQ(units_of(0.0f, 0.1f, 127), 0);
  EXPECT_EQ(units_of(-1.0f, 0.1f, 127), 0);
  EXPECT_EQ(units_of(NAN, 0.1f, 127), 0);
  EXPECT_EQ(units_of(0.5f, 0.0f, 127), 0);
  EXPECT_EQ(units_of(100.0f, 0.1f, 127), 127);
  EXPECT_EQ(units_of(INFINITY, 0.1f, 127), 127);
  EXPECT_EQ(units_of(INFINITY, INFINITY, 127), 127);  // NaN on the way: no cast of it
  EXPECT_EQ(units_of(1e-7f, 0.1f, 127), 1);            // positive: never met on a seed
}

}  // namespace
}  // namespace kestrel::chamfer
