#include "kestrel/core/alloc_guard.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace kestrel {
namespace {

// The guard must see allocations, or every "no heap in the loop" test would pass vacuously.
TEST(AllocGuard, CatchesMallocNewAndContainerGrowth) {
  {
    alloc_guard::Scope guard;
    void* p = std::malloc(64);
    // Stop the optimiser from eliding the pair (it may, for a malloc whose result is unused).
    volatile char* c = static_cast<char*>(p);
    c[0] = 1;
    std::free(p);
    EXPECT_GE(guard.allocations(), 1u);
  }
  {
    alloc_guard::Scope guard;
    auto q = std::make_unique<std::string>(100, 'x');
    EXPECT_GE(guard.allocations(), 1u);
  }
  {
    std::vector<int> v;
    alloc_guard::Scope guard;
    for (int i = 0; i < 100; ++i) v.push_back(i);
    EXPECT_GE(guard.allocations(), 1u);
  }
}

TEST(AllocGuard, CountsNothingWhenDisarmedOrWhenNothingAllocates) {
  alloc_guard::disarm();
  const uint64_t before = alloc_guard::count();
  auto p = std::make_unique<int>(3);
  EXPECT_EQ(alloc_guard::count(), before);
  alloc_guard::Scope guard;
  int sum = 0;
  for (int i = 0; i < 100; ++i) sum += i;
  EXPECT_EQ(sum, 4950);
  EXPECT_EQ(guard.allocations(), 0u);
}

}  // namespace
}  // namespace kestrel
