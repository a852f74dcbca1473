#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "grid_fixture.hpp"
#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/planning/occupancy_grid.hpp"
#include "synthetic_world.hpp"

namespace kestrel::planning {
namespace {

using test::blank_grid;

TEST(GridGeometry, CellsRoundTripAndOffGridPointsAreRefused) {
  const Result<GridGeometry> g = GridGeometry::around({2.0f, 7.5f}, 0.12f);
  ASSERT_TRUE(g.ok());
  Cell c;
  ASSERT_TRUE(g.value().to_cell(2.0f, 7.5f, c));
  EXPECT_EQ(c.x, kGridSide / 2);
  EXPECT_EQ(c.y, kGridSide / 2);
  const Point2 p = g.value().centre_of(c);
  EXPECT_NEAR(p.x, 2.06f, 1e-4f);
  EXPECT_NEAR(p.y, 7.56f, 1e-4f);
  EXPECT_FALSE(g.value().to_cell(2.0f + 31.0f, 7.5f, c));  // 30.7 m is the edge
  EXPECT_FALSE(g.value().to_cell(NAN, 7.5f, c));
  EXPECT_FALSE(GridGeometry::around({0, 0}, 0.0f).ok());
  EXPECT_FALSE(GridGeometry::around({INFINITY, 0}, 0.12f).ok());
}

TEST(OccupancyGrid, RefusesBadParametersAndGeometry) {
  auto g = std::make_unique<OccupancyGrid>();
  GridParams p;
  EXPECT_EQ(g->configure(p, {0, 0}, 0, -1.0f, 0.01f), Status::kInvalidArgument);
  EXPECT_EQ(g->configure(p, {0, 0}, kMaxBeams + 1, -1.0f, 0.01f), Status::kInvalidArgument);
  EXPECT_EQ(g->configure(p, {0, 0}, 100, -1.0f, 0.0f), Status::kInvalidArgument);
  EXPECT_EQ(g->configure(p, {0, 0}, 100, NAN, 0.01f), Status::kInvalidArgument);
  p.reach_m = 0;
  EXPECT_EQ(g->configure(p, {0, 0}, 100, -1.0f, 0.01f), Status::kInvalidArgument);
  p = {};
  p.miss_step = 0;
  EXPECT_EQ(g->configure(p, {0, 0}, 100, -1.0f, 0.01f), Status::kInvalidArgument);
  p = {};
  p.footprint_m = -0.1f;
  EXPECT_EQ(g->configure(p, {0, 0}, 100, -1.0f, 0.01f), Status::kInvalidArgument);
  EXPECT_FALSE(g->configured());
  LaserScan s;
  EXPECT_EQ(g->draw(s, {}), Status::kNotFound);
}

// One wall 2 m ahead across the whole fan: the cells up to it are free, its own are occupied,
// the row just before it is known but not free evidence, and behind it all is unknown.
TEST(OccupancyGrid, ARayFreesItsCellsAndMarksItsReturn) {
  auto g = blank_grid();
  kestrel::test::SegmentWorld w;
  w.add(2.0, -10, 2.0, 10);
  const kestrel::test::LaserModel urg = kestrel::test::LaserModel::urg04lx();
  const LaserScan s = w.scan(urg, 0, 0, 0);
  ASSERT_EQ(g->draw(s, {0, 0, 0}), Status::kOk);
  const GridGeometry& geo = g->geometry();
  const auto at = [&](float x, float y) {
    Cell c;
    EXPECT_TRUE(geo.to_cell(x, y, c));
    return g->at(c);
  };
  for (float x = 0.1f; x < 1.7f; x += 0.1f) EXPECT_TRUE(occupancy::is_free(at(x, 0.05f))) << x;
  EXPECT_TRUE(occupancy::is_occupied(at(2.0f, 0.05f)));
  EXPECT_TRUE(occupancy::is_occupied(at(2.0f, 1.0f)));
  EXPECT_TRUE(occupancy::is_unknown(at(2.5f, 0.05f)));
  EXPECT_TRUE(occupancy::is_unknown(at(-1.0f, 0.05f)));  // behind: the laser's blind arc
  EXPECT_FALSE(occupancy::is_unknown(at(1.9f, 0.05f)));
  EXPECT_EQ(g->scans_drawn(), 1u);
  EXPECT_FALSE(g->drawn().empty());
}

// Nothing within the sensor's range frees the ray up to that range (or reach); with
// no_return_is_free off, as in paper 004's CoreSLAM, it draws nothing. The other codes never draw.
TEST(OccupancyGrid, BeamsWithoutAReturnAndFarReturnsFreeUpToReach) {
  const kestrel::test::LaserModel urg = kestrel::test::LaserModel::urg04lx();
  const auto state_at = [](const OccupancyGrid& g, float x, float y) {
    Cell c;
    EXPECT_TRUE(g.geometry().to_cell(x, y, c));
    return g.at(c);
  };
  auto g = blank_grid();
  ASSERT_EQ(g->draw(kestrel::test::uniform_scan(urg, range_code::kNoReturn), {0, 0, 0}), Status::kOk);
  EXPECT_TRUE(occupancy::is_free(state_at(*g, 3.8f, 0.0f)));
  EXPECT_TRUE(occupancy::is_unknown(state_at(*g, 4.3f, 0.0f)));
  GridParams off;
  off.no_return_is_free = false;
  g = blank_grid(off);
  ASSERT_EQ(g->draw(kestrel::test::uniform_scan(urg, range_code::kNoReturn), {0, 0, 0}), Status::kOk);
  EXPECT_TRUE(occupancy::is_unknown(state_at(*g, 1.0f, 0.0f)));
  for (uint16_t code : {range_code::kTooNear, range_code::kDropout, range_code::kDeflected}) {
    g = blank_grid();
    ASSERT_EQ(g->draw(kestrel::test::uniform_scan(urg, code), {0, 0, 0}), Status::kOk);
    EXPECT_TRUE(occupancy::is_unknown(state_at(*g, 1.0f, 0.0f))) << code;
  }
  // Every beam returns at 6 m, beyond the 4 m reach: free up to reach, no wall.
  g = blank_grid();
  ASSERT_EQ(g->draw(kestrel::test::uniform_scan(urg, 6000), {0, 0, 0}), Status::kOk);
  EXPECT_TRUE(occupancy::is_free(state_at(*g, 3.8f, 0.0f)));
  EXPECT_TRUE(occupancy::is_unknown(state_at(*g, 4.3f, 0.0f)));
}

// The vehicle's disc is free, the blind arc behind it beyond the disc unknown.
TEST(OccupancyGrid, TheVehiclesOwnDiscIsFree) {
  auto g = blank_grid();
  ASSERT_EQ(g->draw(kestrel::test::uniform_scan(kestrel::test::LaserModel::urg04lx(), 3000), {0, 0, 0}), Status::kOk);
  Cell c;
  ASSERT_TRUE(g->geometry().to_cell(-0.25f, 0.0f, c));
  EXPECT_TRUE(occupancy::is_free(g->at(c)));
  ASSERT_TRUE(g->geometry().to_cell(-0.6f, 0.0f, c));
  EXPECT_TRUE(occupancy::is_unknown(g->at(c)));
}

TEST(OccupancyGrid, BadScansAndPosesAreRefusedAndDrawNothing) {
  auto g = blank_grid();
  const kestrel::test::LaserModel urg = kestrel::test::LaserModel::urg04lx();
  const LaserScan s = kestrel::test::uniform_scan(urg, 1000);
  EXPECT_EQ(g->draw(s, {NAN, 0, 0}), Status::kNotFinite);
  EXPECT_EQ(g->draw(s, {0, 0, INFINITY}), Status::kNotFinite);
  EXPECT_EQ(g->draw(s, {40.0f, 0, 0}), Status::kOutOfRange);
  const LaserScan utm = kestrel::test::uniform_scan(kestrel::test::LaserModel::utm30lx(), 1000);
  EXPECT_EQ(g->draw(utm, {0, 0, 0}), Status::kInvalidArgument);
  EXPECT_EQ(g->scans_drawn(), 0u);
  EXPECT_TRUE(g->drawn().empty());
}

// Near the grid's edge the rays are cut where they leave it: no write outside (ASan would
// tell), and what lies inside is drawn.
TEST(OccupancyGrid, RaysLeavingTheGridAreCut) {
  auto g = blank_grid();
  const kestrel::test::LaserModel urg = kestrel::test::LaserModel::urg04lx();
  const float edge = 0.5f * kGridSide * 0.12f;
  ASSERT_EQ(g->draw(kestrel::test::uniform_scan(urg, 3000), {edge - 1.0f, edge - 1.0f, 0.7f}), Status::kOk);
  Cell c;
  ASSERT_TRUE(g->geometry().to_cell(edge - 0.5f, edge - 0.5f, c));
  EXPECT_TRUE(occupancy::is_free(g->at(c)));
}

// A wall drawn where the estimate put it, and then seen through from where it is not: misses
// wear it away; a wall hit scan after scan stays, even with rays grazing it.
TEST(OccupancyGrid, MissesClearAWallDrawnInTheWrongPlace) {
  auto g = blank_grid();
  const kestrel::test::LaserModel urg = kestrel::test::LaserModel::urg04lx();
  kestrel::test::SegmentWorld near_wall, far_wall;
  near_wall.add(1.5, -10, 1.5, 10);
  far_wall.add(3.0, -10, 3.0, 10);
  ASSERT_EQ(g->draw(near_wall.scan(urg, 0, 0, 0), {0, 0, 0}), Status::kOk);
  Cell c;
  ASSERT_TRUE(g->geometry().to_cell(1.5f, 0.05f, c));
  EXPECT_TRUE(occupancy::is_occupied(g->at(c)));
  for (int k = 0; k < 10; ++k) ASSERT_EQ(g->draw(far_wall.scan(urg, 0, 0, 0), {0, 0, 0}), Status::kOk);
  EXPECT_TRUE(occupancy::is_free(g->at(c)));
  Cell far;
  ASSERT_TRUE(g->geometry().to_cell(3.0f, 0.05f, far));
  EXPECT_TRUE(occupancy::is_occupied(g->at(far)));
  // Seen aslant from beside it, the far wall's cells keep their walls.
  for (int k = 0; k < 10; ++k) ASSERT_EQ(g->draw(far_wall.scan(urg, 2.5, -2.0, 1.2), {2.5f, -2.0f, 1.2f}), Status::kOk);
  int still_walls = 0;
  for (float y = -1.0f; y <= 1.0f; y += 0.12f) {
    Cell w;
    ASSERT_TRUE(g->geometry().to_cell(3.0f, y, w));
    still_walls += occupancy::is_occupied(g->at(w)) ? 1 : 0;
  }
  EXPECT_GE(still_walls, 15);
}

// A wall's cells straddle its line, and the rays that run along its far side pass through
// them: ten beams a scan at 2 m with the URG-04LX. One scan counts once per cell, so the
// scans that hit the wall keep it however many of their beams graze it.
TEST(OccupancyGrid, AScanCountsOncePerCell) {
  auto g = blank_grid();
  const kestrel::test::LaserModel urg = kestrel::test::LaserModel::urg04lx();
  Cell c;
  ASSERT_TRUE(g->geometry().to_cell(2.0f, 0.0f, c));
  // A hand-made scan: beam 0 returns from the cell's centre, every other beam passes through
  // the cell to 3 m (the rays through it, seen from the origin).
  LaserScan s = kestrel::test::uniform_scan(urg, range_code::kNoReturn);
  const Point2 centre = g->geometry().centre_of(c);
  int through = 0;
  for (uint16_t b = 0; b < urg.beams; ++b) {
    const double a = urg.first_angle() + urg.step() * b;
    const double off = std::fabs(std::sin(a) * centre.x - std::cos(a) * centre.y);  // from the ray
    if (std::cos(a) > 0.9 && off < 0.05) {
      s.range_mm[b] = through++ == 0 ? static_cast<uint16_t>(std::hypot(centre.x, centre.y) * 1000.0) : 3000;
    }
  }
  ASSERT_GE(through, 7);  // one hit and six misses a scan: uncapped, the misses would win
  for (int k = 0; k < 20; ++k) ASSERT_EQ(g->draw(s, {0, 0, 0}), Status::kOk);
  EXPECT_TRUE(occupancy::is_occupied(g->at(c)));
}

TEST(OccupancyGrid, DrawingDoesNotAllocate) {
  auto g = blank_grid();
  kestrel::test::SegmentWorld w;
  w.add_box(-3, -3, 3, 3);
  const LaserScan s = w.scan(kestrel::test::LaserModel::urg04lx(), 0.5, 0.2, 0.3);
  alloc_guard::Scope guard;
  ASSERT_EQ(g->draw(s, {0.5f, 0.2f, 0.3f}), Status::kOk);
  EXPECT_EQ(guard.allocations(), 0u);
}

}  // namespace
}  // namespace kestrel::planning
