// The frontier explorer's grid as map.pgm: cropped to the drawn cells with a metre of margin,
// the right way up, each cell classed as the grid classes it, and placed where the world puts it.
#include "kestrel/flight/grid_map_image.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "synthetic_world.hpp"

namespace kestrel::flight {
namespace {

TEST(GridMapImage, CropsToTheDrawnCellsAndKeepsTheWorldsFrame) {
  const test::LaserModel urg = test::LaserModel::urg04lx();
  auto grid = std::make_unique<planning::OccupancyGrid>();
  ASSERT_EQ(grid->configure({}, {10.0f, 20.0f}, urg.beams, static_cast<float>(urg.first_angle()),
                            static_cast<float>(urg.step())),
            Status::kOk);
  EXPECT_EQ(grid_map_image(*grid).width, 0);  // nothing drawn yet
  test::SegmentWorld w;
  w.add(12.0, 15.0, 12.0, 25.0);  // a wall 2 m east of the sensor
  ASSERT_EQ(grid->draw(w.scan(urg, 10.0, 20.0, 0.0), {10.0f, 20.0f, 0.0f}), Status::kOk);
  const output::GridImage g = grid_map_image(*grid);
  ASSERT_GT(g.width, 0);
  EXPECT_NEAR(g.resolution_m, 0.12, 1e-6);
  ASSERT_EQ(g.cells.size(), static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height));
  const auto at = [&](double x, double y) {
    const int cx = static_cast<int>((x - g.origin_x_m) / g.resolution_m);
    const int cy = static_cast<int>((y - g.origin_y_m) / g.resolution_m);
    return g.cells[static_cast<std::size_t>(cy) * static_cast<std::size_t>(g.width) + static_cast<std::size_t>(cx)];
  };
  EXPECT_EQ(at(12.0, 20.05), output::kPgmOccupied);
  EXPECT_EQ(at(11.0, 20.05), output::kPgmFree);
  EXPECT_EQ(at(13.0, 20.05), output::kPgmUnknown);  // behind the wall
  // The drawn box and a metre: westwards the fan's last beams (120 degrees off the nose) find
  // nothing within 4 m and free their rays to 2 m west of the sensor.
  EXPECT_LT(g.origin_x_m, 10.0 - 2.9);
  EXPECT_GT(g.origin_x_m, 10.0 - 3.2);
  EXPECT_GT(g.origin_x_m + g.width * g.resolution_m, 12.0 + 0.9);
}

}  // namespace
}  // namespace kestrel::flight
