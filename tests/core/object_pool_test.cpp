#include "kestrel/core/object_pool.hpp"

#include <gtest/gtest.h>

namespace kestrel {
namespace {

struct Node {
  explicit Node(int v) : value(v) { ++alive; }
  ~Node() { --alive; }
  int value;
  static inline int alive = 0;
};

TEST(ObjectPool, AcquiresUntilExhaustedAndReusesReleasedSlots) {
  ObjectPool<Node, 3> pool;
  Node* a = pool.acquire(1);
  Node* b = pool.acquire(2);
  Node* c = pool.acquire(3);
  ASSERT_NE(a, nullptr);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(pool.acquire(4), nullptr);
  EXPECT_EQ(Node::alive, 3);
  pool.release(b);
  EXPECT_EQ(Node::alive, 2);
  EXPECT_FALSE(pool.owns(b));
  Node* d = pool.acquire(5);
  EXPECT_EQ(d, b);  // the freed slot is reused
  EXPECT_EQ(d->value, 5);
  EXPECT_EQ(pool.in_use(), 3u);
  pool.clear();
  EXPECT_EQ(Node::alive, 0);
  EXPECT_EQ(pool.available(), 3u);
}

TEST(ObjectPoolDeathTest, DoubleReleaseAborts) {
  ObjectPool<Node, 2> pool;
  Node* a = pool.acquire(1);
  pool.release(a);
  EXPECT_DEATH(pool.release(a), "");
}

}  // namespace
}  // namespace kestrel
