#include "kestrel/core/min_heap.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

namespace kestrel {
namespace {

TEST(MinHeap, PopsInKeyOrder) {
  MinHeap<int, 16> h;
  const int keys[] = {5, 3, 9, 1, 7, 2};
  for (uint16_t i = 0; i < 6; ++i) ASSERT_TRUE(h.push(i, keys[i]));
  int prev = -1;
  while (!h.empty()) {
    const int k = h.top_key();
    EXPECT_GE(k, prev);
    prev = k;
    h.pop();
  }
}

TEST(MinHeap, DecreaseKeyMovesItemUp) {
  MinHeap<float, 8> h;
  ASSERT_TRUE(h.push(0, 5.f));
  ASSERT_TRUE(h.push(1, 3.f));
  ASSERT_TRUE(h.push(2, 4.f));
  h.decrease_key(0, 1.f);
  EXPECT_EQ(h.pop(), 0);
  // push of a present id keeps the smaller key
  ASSERT_TRUE(h.push(2, 10.f));
  EXPECT_EQ(h.key(2), 4.f);
  ASSERT_TRUE(h.push(2, 2.f));
  EXPECT_EQ(h.pop(), 2);
  EXPECT_EQ(h.pop(), 1);
}

TEST(MinHeap, RejectsIdsOutsideCapacity) {
  MinHeap<int, 4> h;
  EXPECT_FALSE(h.push(4, 1));
  EXPECT_TRUE(h.empty());
}

TEST(MinHeap, RandomOperationsMatchAnOrderedReference) {
  MinHeap<int, 256> h;
  std::map<uint16_t, int> ref;
  uint32_t seed = 42;
  for (int step = 0; step < 20000; ++step) {
    seed = seed * 1664525u + 1013904223u;
    const uint16_t id = static_cast<uint16_t>((seed >> 8) % 256);
    const int key = static_cast<int>((seed >> 3) % 10000);
    switch ((seed >> 24) % 4) {
      case 0:
      case 1:
        ASSERT_TRUE(h.push(id, key));
        ref[id] = ref.count(id) ? std::min(ref[id], key) : key;
        break;
      case 2:
        h.erase(id);
        ref.erase(id);
        break;
      case 3:
        if (!ref.empty()) {
          const auto best = std::min_element(ref.begin(), ref.end(),
                                              [](auto& a, auto& b) { return a.second < b.second; });
          EXPECT_EQ(h.top_key(), best->second);
          ref.erase(h.pop());
        }
        break;
    }
    ASSERT_EQ(h.size(), ref.size());
  }
}

}  // namespace
}  // namespace kestrel
