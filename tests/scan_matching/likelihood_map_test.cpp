#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <vector>

#include "kestrel/scan_matching/likelihood_map.hpp"

namespace kestrel::scan_matching {
namespace {

using SmallMap = LikelihoodMapStorage<128, 64>;

// The drawing primitive equals a brute-force map (every cell, every segment, max of values).
TEST(LikelihoodMap, DrawingPrimitiveEqualsBruteForce) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coord(0, 127 * kSub);
  auto map = std::make_unique<SmallMap>();
  Params p;
  ASSERT_EQ(map->configure(p), Status::kOk);
  for (int round = 0; round < 5; ++round) {
    map->begin(0, 0);
    std::vector<MapSegment> segs;
    for (int i = 0; i < 12; ++i) {
      MapSegment s{static_cast<int16_t>(coord(rng)), static_cast<int16_t>(coord(rng)), 0, 0};
      const int kind = i % 4;  // long, short, point, axis-aligned
      s.bx = static_cast<int16_t>(
          kind == 2 ? s.ax : std::clamp(s.ax + (kind == 1 ? 40 : 900) * ((i & 1) ? 1 : -1), 0, 127 * kSub));
      s.by = static_cast<int16_t>(kind == 3 || kind == 2 ? s.ay
                                                         : std::clamp(s.ay + (kind == 1 ? -25 : 500), 0, 127 * kSub));
      segs.push_back(s);
      ASSERT_EQ(map->draw(s), Status::kOk);
    }
    map->finish();
    std::size_t nonzero = 0;
    for (int y = 0; y < 128; ++y) {
      for (int x = 0; x < 128; ++x) {
        uint8_t ref = 0;
        for (const MapSegment& s : segs) {
          ref = std::max(ref,
                         map->kernel().value(SegmentGeometry(s).distance2(x * kSub + kSub / 2, y * kSub + kSub / 2)));
        }
        ASSERT_EQ(map->at(x, y), ref) << "cell " << x << "," << y << " round " << round;
        nonzero += ref != 0;
      }
    }
    EXPECT_GT(nonzero, 100u);
    // Coarse levels bound every fine cell they cover.
    for (int l = 1; l <= 3; ++l) {
      const int s = 1 << l, d = level_dim(128, l);
      for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x)
          for (int k = 0; k < s; ++k) {
            const int qx = x - k;  // a point in fine cell qx reaches x with offset k
            const int ix = (qx + s) >> l, iy = (y + s) >> l;
            if (ix < 0 || ix >= d || iy >= d) continue;
            ASSERT_GE(map->level(l)[iy * d + ix], map->at(x, y));
          }
    }
  }
  // Clearing redraws only what was drawn: afterwards the map is empty.
  map->begin(0, 0);
  map->finish();
  EXPECT_EQ(map->nonzero_cells(), 0u);
}

TEST(LikelihoodMap, RejectsBadConfigurationAndFullSegmentList) {
  auto map = std::make_unique<SmallMap>();
  Params p;
  p.resolution_m = 0;
  EXPECT_EQ(map->configure(p), Status::kInvalidArgument);
  p = Params{};
  ASSERT_EQ(map->configure(p), Status::kOk);
  map->begin(0, 0);
  for (int i = 0; i < 64; ++i) ASSERT_EQ(map->draw({100, 100, 200, 200}), Status::kOk);
  EXPECT_EQ(map->draw({100, 100, 200, 200}), Status::kCapacityExceeded);
}

}  // namespace
}  // namespace kestrel::scan_matching
