#include "kestrel/core/path_halving.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "kestrel/core/static_vector.hpp"

namespace kestrel {
namespace {

std::vector<int> halved(int n) {
  StaticVector<int, 16> v;
  for (int i = 0; i < n; ++i) EXPECT_TRUE(v.push_back(i));
  halve_keeping_ends(v);
  return {v.begin(), v.end()};
}

TEST(PathHalving, OddCountKeepsEveryOtherPointWithBothEnds) {
  EXPECT_EQ(halved(7), (std::vector<int>{0, 2, 4, 6}));
}

TEST(PathHalving, EvenCountAlsoKeepsTheNewestPoint) {
  // The stride from the first ends one short of the newest, which the path must still end at.
  EXPECT_EQ(halved(8), (std::vector<int>{0, 2, 4, 6, 7}));
  EXPECT_EQ(halved(16), (std::vector<int>{0, 2, 4, 6, 8, 10, 12, 14, 15}));
}

TEST(PathHalving, ShortPathsAreLeftAsTheyAre) {
  EXPECT_EQ(halved(0), std::vector<int>{});
  EXPECT_EQ(halved(1), std::vector<int>{0});
  EXPECT_EQ(halved(2), (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace kestrel
