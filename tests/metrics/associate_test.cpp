#include "kestrel/metrics/associate.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace kestrel::metrics {
namespace {

std::vector<TimeUs> us(std::initializer_list<int64_t> v) {
  std::vector<TimeUs> out;
  for (int64_t x : v) out.push_back(TimeUs::from_us(x));
  return out;
}

TEST(Associate, NearestWithinToleranceEachReferenceOnce) {
  const auto a = us({100, 200, 205, 400, 1000});
  const auto b = us({98, 203, 390, 500});
  const auto p = associate_by_stamp(a, b, Duration::from_us(10));
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0].i, 0u);
  EXPECT_EQ(p[0].j, 0u);
  EXPECT_EQ(p[1].i, 1u);  // 200 claims 203 first; 205 then finds nothing unused within 10 us
  EXPECT_EQ(p[1].j, 1u);
  EXPECT_EQ(p[2].i, 3u);  // 400 takes 390, exactly at the tolerance; 1000 has no partner
  EXPECT_EQ(p[2].j, 2u);
}

TEST(Associate, UnsortedReferenceAndEmptyInputs) {
  // Like intel.log.gz, the reference steps back in time.
  const auto b = us({100, 300, 250, 400});
  const auto a = us({251, 99, 401, 299});
  const auto p = associate_by_stamp(a, b, Duration::from_us(5));
  ASSERT_EQ(p.size(), 4u);
  EXPECT_EQ(p[0].j, 2u);
  EXPECT_EQ(p[1].j, 0u);
  EXPECT_EQ(p[2].j, 3u);
  EXPECT_EQ(p[3].j, 1u);
  EXPECT_TRUE(associate_by_stamp({}, b, Duration::from_us(5)).empty());
  EXPECT_TRUE(associate_by_stamp(a, {}, Duration::from_us(5)).empty());
}

}  // namespace
}  // namespace kestrel::metrics
