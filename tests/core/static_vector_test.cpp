#include "kestrel/core/static_vector.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace kestrel {
namespace {

// Functions take the capacity-free interface.
int sum(const IVector<int>& v) {
  int s = 0;
  for (int x : v) s += x;
  return s;
}

TEST(StaticVector, PushUntilFullThenRefuses) {
  StaticVector<int, 3> v;
  EXPECT_TRUE(v.push_back(1));
  EXPECT_TRUE(v.push_back(2));
  EXPECT_TRUE(v.push_back(3));
  EXPECT_TRUE(v.full());
  EXPECT_FALSE(v.push_back(4));
  EXPECT_EQ(v.size(), 3u);
  EXPECT_EQ(sum(v), 6);
}

TEST(StaticVector, BehavesLikeStdVectorUnderRandomOperations) {
  StaticVector<int, 64> v;
  std::vector<int> ref;
  uint32_t seed = 7;
  for (int step = 0; step < 5000; ++step) {
    seed = seed * 1103515245u + 12345u;
    const int op = static_cast<int>((seed >> 16) % 4);
    if (op <= 1) {
      const bool pushed = v.push_back(step);
      EXPECT_EQ(pushed, ref.size() < 64);
      if (pushed) ref.push_back(step);
    } else if (op == 2 && !ref.empty()) {
      v.pop_back();
      ref.pop_back();
    } else if (op == 3 && !ref.empty()) {
      const std::size_t i = (seed >> 8) % ref.size();
      v.erase(i);
      ref.erase(ref.begin() + static_cast<long>(i));
    }
    ASSERT_EQ(v.size(), ref.size());
  }
  for (std::size_t i = 0; i < ref.size(); ++i) EXPECT_EQ(v[i], ref[i]);
}

TEST(StaticVector, SwapRemoveAndResize) {
  StaticVector<int, 8> v;
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(v.push_back(i));
  v.swap_remove(1);
  EXPECT_EQ(v.size(), 4u);
  EXPECT_EQ(v[1], 4);
  EXPECT_TRUE(v.resize(8));
  EXPECT_EQ(v[7], 0);
  EXPECT_FALSE(v.resize(9));
  EXPECT_TRUE(v.resize(2));
  EXPECT_EQ(v.size(), 2u);
}

TEST(StaticVector, AssignThatDoesNotFitLeavesItEmpty) {
  StaticVector<int, 2> v;
  const int src[] = {1, 2, 3};
  EXPECT_FALSE(v.assign(std::begin(src), std::end(src)));
  EXPECT_TRUE(v.empty());
}

TEST(StaticVector, CopyIsDeep) {
  StaticVector<int, 4> a;
  ASSERT_TRUE(a.push_back(5));
  StaticVector<int, 4> b = a;
  b[0] = 9;
  EXPECT_EQ(a[0], 5);
  a = b;
  EXPECT_EQ(a[0], 9);
}

TEST(StaticVectorDeathTest, IndexOutOfRangeAborts) {
  StaticVector<int, 2> v;
  ASSERT_TRUE(v.push_back(1));
  EXPECT_DEATH((void)v[1], "");
}

}  // namespace
}  // namespace kestrel
