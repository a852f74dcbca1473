// The compact SLAM's map: reset, the V drawn for each return, the bilinear sample.
#include "kestrel/slam/slam_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace kestrel::slam {
namespace {

TEST(SlamMap, ResetRefusesABadCellOrCentre) {
  auto map = std::make_unique<SlamMap>();
  EXPECT_EQ(map->reset(0.0f, 0, 0), Status::kInvalidArgument);
  EXPECT_EQ(map->reset(0.005f, 0, 0), Status::kInvalidArgument);
  EXPECT_EQ(map->reset(NAN, 0, 0), Status::kInvalidArgument);
  EXPECT_EQ(map->reset(0.05f, INFINITY, 0), Status::kInvalidArgument);
  ASSERT_EQ(map->reset(0.05f, 3.0f, -2.0f), Status::kOk);
  EXPECT_EQ(map->known_cells(), 0u);
  // The centre lands in the middle cell.
  const SubPoint c = map->to_sub(3.0f, -2.0f);
  EXPECT_EQ(c.x, kMapSide / 2 * kSub);
  EXPECT_EQ(c.y, kMapSide / 2 * kSub);
  EXPECT_NEAR(map->sub_to_x_m(c.x), 3.0f, 1e-4f);
  EXPECT_NEAR(map->sub_to_y_m(c.y), -2.0f, 1e-4f);
}

TEST(SlamMap, AReturnDrawsAWallAtTheHitAndClearsTheRayBeforeIt) {
  auto map = std::make_unique<SlamMap>();
  ASSERT_EQ(map->reset(0.05f, 0, 0), Status::kOk);
  const SubPoint sensor = map->to_sub(0.0f, 0.0f), hit = map->to_sub(2.0f, 0.0f);
  const int32_t hole_half = 4 * kSub, clear = 30 * kSub;  // 0.2 m and 1.5 m
  for (int i = 0; i < 20; ++i) map->draw_return(sensor, hit, hole_half, clear, 100);
  const int row = kMapSide / 2, at_sensor = kMapSide / 2;
  // The hit lies on the boundary of cells 39 and 40 from the sensor's: both are wall.
  EXPECT_LT(map->at(at_sensor + 39, row), 40);
  EXPECT_LT(map->at(at_sensor + 40, row), 40);
  EXPECT_GT(map->at(at_sensor + 20, row), 235);       // 1 m: cleared
  EXPECT_LT(map->at(at_sensor + 37, row), map->at(at_sensor + 36, row));  // the V's slope
  EXPECT_EQ(map->at(at_sensor + 5, row), kUnknown);   // before the clearing reach
  EXPECT_EQ(map->at(at_sensor + 50, row), kUnknown);  // behind the wall, beyond the V
  EXPECT_EQ(map->at(at_sensor + 40, row + 3), kUnknown);  // beside the ray
}

TEST(SlamMap, SampleIsBilinearAndUnknownOffTheMap) {
  auto map = std::make_unique<SlamMap>();
  ASSERT_EQ(map->reset(0.05f, 0, 0), Status::kOk);
  const SubPoint sensor = map->to_sub(0.0f, 0.0f), hit = map->to_sub(1.0f, 0.0f);
  for (int i = 0; i < 40; ++i) map->draw_return(sensor, hit, 4 * kSub, 30 * kSub, 128);
  const int cx = kMapSide / 2 + 18, cy = kMapSide / 2;
  const SubPoint corner{cx * kSub + kSub / 2, cy * kSub + kSub / 2};  // the cell's centre
  EXPECT_EQ(map->sample(corner), uint32_t{map->at(cx, cy)} * kSub);
  const SubPoint half{cx * kSub + kSub, cy * kSub + kSub / 2};
  const uint32_t lo = std::min(map->at(cx, cy), map->at(cx + 1, cy)) * uint32_t{kSub};
  const uint32_t hi = std::max(map->at(cx, cy), map->at(cx + 1, cy)) * uint32_t{kSub};
  EXPECT_GE(map->sample(half), lo);
  EXPECT_LE(map->sample(half), hi);
  EXPECT_EQ(map->sample({-5, 100}), uint32_t{kUnknown} * kSub);
  EXPECT_EQ(map->sample({kMapSide * kSub, 100}), uint32_t{kUnknown} * kSub);
}

TEST(SlamMap, ReturnsReachingOffTheMapDrawOnlyWhatIsOnIt) {
  auto map = std::make_unique<SlamMap>();
  ASSERT_EQ(map->reset(0.05f, 0, 0), Status::kOk);
  const float edge = 0.5f * kMapSide * 0.05f;
  const SubPoint sensor = map->to_sub(edge - 1.0f, 0.0f), hit = map->to_sub(edge + 1.0f, 0.0f);
  map->draw_return(sensor, hit, 4 * kSub, 60 * kSub, 128);
  EXPECT_GT(map->known_cells(), 15u);
  EXPECT_LT(map->known_cells(), 25u);
  const std::size_t before = map->known_cells();
  // Sensor and hit far outside: nothing on the map changes, nothing crashes.
  map->draw_return({-100 * kSub, -100 * kSub}, {-300 * kSub, -100 * kSub}, 4 * kSub, 60 * kSub, 128);
  EXPECT_EQ(map->known_cells(), before);
  // Degenerate inputs: a zero-length return, a zero weight, a zero hole.
  map->draw_return(sensor, sensor, 4 * kSub, 60 * kSub, 128);
  map->draw_return(sensor, hit, 4 * kSub, 60 * kSub, 0);
  map->draw_return(sensor, hit, 0, 60 * kSub, 128);
  EXPECT_EQ(map->known_cells(), before);
}

}  // namespace
}  // namespace kestrel::slam
