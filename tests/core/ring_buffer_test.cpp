#include "kestrel/core/ring_buffer.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace kestrel {
namespace {

TEST(RingBuffer, FifoOrderAndCapacity) {
  RingBuffer<int, 4> q;
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(q.push(i));
  EXPECT_FALSE(q.push(99));
  EXPECT_EQ(q.size(), 4u);
  int out = -1;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(q.pop(out));
    EXPECT_EQ(out, i);
  }
  EXPECT_FALSE(q.pop(out));
  EXPECT_EQ(q.peek(), nullptr);
}

TEST(RingBuffer, WrapsAroundManyTimes) {
  RingBuffer<int, 8> q;
  int next_in = 0, next_out = 0, out = 0;
  for (int round = 0; round < 1000; ++round) {
    for (int k = 0; k < 5; ++k) ASSERT_TRUE(q.push(next_in++));
    ASSERT_NE(q.peek(), nullptr);
    EXPECT_EQ(*q.peek(), next_out);
    for (int k = 0; k < 5; ++k) {
      ASSERT_TRUE(q.pop(out));
      EXPECT_EQ(out, next_out++);
    }
  }
  EXPECT_TRUE(q.empty());
}

TEST(RingBuffer, OneProducerOneConsumerThreadsLoseNothing) {
  static RingBuffer<uint32_t, 64> q;
  constexpr uint32_t kCount = 20000;
  std::thread producer([] {
    for (uint32_t i = 0; i < kCount;)
      if (q.push(i)) ++i;
  });
  uint32_t expected = 0, v = 0;
  bool in_order = true;
  while (expected < kCount) {
    if (q.pop(v)) {
      in_order = in_order && (v == expected);
      ++expected;
    }
  }
  producer.join();
  EXPECT_TRUE(in_order);
  EXPECT_TRUE(q.empty());
}

}  // namespace
}  // namespace kestrel
