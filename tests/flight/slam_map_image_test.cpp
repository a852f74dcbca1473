// The compact SLAM's map as map.pgm: cropped to what the laser touched, the right way up, each
// cell classed as wall, free or unknown, and placed where the world puts it.
#include "kestrel/flight/slam_map_image.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace kestrel::flight {
namespace {

TEST(SlamMapImage, CropsToTheDrawnCellsAndKeepsTheWorldsFrame) {
  auto map = std::make_unique<slam::SlamMap>();
  ASSERT_EQ(map->reset(0.05f, 10.0f, 20.0f), Status::kOk);
  EXPECT_EQ(slam_map_image(*map).width, 0);  // nothing drawn yet
  // One wall return 2 m north of the sensor, drawn until it settles.
  const slam::SubPoint sensor = map->to_sub(10.0f, 20.0f), hit = map->to_sub(10.0f, 22.0f);
  for (int i = 0; i < 30; ++i) map->draw_return(sensor, hit, 4 * slam::kSub, 60 * slam::kSub, 128);
  const output::GridImage g = slam_map_image(*map);
  ASSERT_GT(g.width, 0);
  EXPECT_NEAR(g.resolution_m, 0.05, 1e-7);
  // A metre (20 cells) of margin around a column of drawn cells from the sensor to past the wall.
  EXPECT_GE(g.width, 41);
  EXPECT_LE(g.width, 43);
  EXPECT_GE(g.height, 2 * 20 + 40);
  ASSERT_EQ(g.cells.size(), static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height));
  // The wall (y = 22 m) is black, the ray before it white, the margin unknown; rows go up in y.
  const auto at = [&](double x, double y) {
    const int cx = static_cast<int>((x - g.origin_x_m) / g.resolution_m);
    const int cy = static_cast<int>((y - g.origin_y_m) / g.resolution_m);
    return g.cells[static_cast<std::size_t>(cy) * static_cast<std::size_t>(g.width) + static_cast<std::size_t>(cx)];
  };
  EXPECT_EQ(at(10.01, 22.01), output::kPgmOccupied);
  EXPECT_EQ(at(10.01, 21.0), output::kPgmFree);
  EXPECT_EQ(at(9.5, 21.0), output::kPgmUnknown);
  EXPECT_LT(g.origin_x_m, 10.0 - 0.9);
  EXPECT_GT(g.origin_x_m, 10.0 - 1.2);
}

}  // namespace
}  // namespace kestrel::flight
