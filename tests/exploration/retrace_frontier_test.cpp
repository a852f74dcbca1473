// srt.retrace_target = frontier: the coarse grid's layers of what the nodes' scans showed (seen
// free, walls; visited_grid.hpp), its frontier cells, their count by bearing
// (unflown_bearings.hpp), and the planner's marks from the scans it is given
// (srt_star_planner.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "kestrel/exploration/srt_star_planner.hpp"
#include "kestrel/exploration/unflown_bearings.hpp"
#include "kestrel/exploration/visited_grid.hpp"
#include "planner_settle.hpp"
#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

using test::LaserModel;
using test::SegmentWorld;


// Cell indices of a point; the grid is anchored at (0, 0), so cells are whole metres.
struct CellOf {
  const VisitedGrid& g;
  bool frontier(float x, float y) const {
    int ix = 0, iy = 0;
    return g.cell_of({x, y}, ix, iy) && g.frontier_cell(ix, iy);
  }
  bool seen(float x, float y) const {
    int ix = 0, iy = 0;
    return g.cell_of({x, y}, ix, iy) && g.seen_cell(ix, iy);
  }
  bool wall(float x, float y) const {
    int ix = 0, iy = 0;
    return g.cell_of({x, y}, ix, iy) && g.wall_cell(ix, iy);
  }
};

// Flown around (0, 0) (cells -1..1), a strip seen free east of it along y in [0, 1) to x = 6,
// and a wall in the cell after it.
VisitedGrid strip_seen_up_to_a_wall() {
  VisitedGrid g;
  g.mark({0.0f, 0.0f});
  for (float x = 2.5f; x < 6.0f; x += 1.0f) g.mark_seen({x, 0.5f});
  g.mark_wall({6.5f, 0.5f});
  return g;
}

TEST(VisitedGridFrontier, AFrontierCellIsUnseenBesideSpaceSeenFreeNotBehindAWall) {
  VisitedGrid g = strip_seen_up_to_a_wall();
  const CellOf c{g};
  EXPECT_TRUE(c.seen(3.5f, 0.5f));
  EXPECT_TRUE(c.wall(6.5f, 0.5f));
  // Beside the strip, either side: unexplored space next to explored space.
  for (float x = 2.5f; x < 6.0f; x += 1.0f) {
    EXPECT_TRUE(c.frontier(x, 1.5f)) << x;
    EXPECT_TRUE(c.frontier(x, -0.5f)) << x;
  }
  // Not the strip itself, nor the wall, nor what lies behind the wall (its only neighbour that
  // was seen at all is the wall's cell), nor a cell flown beside the strip, nor cells away.
  EXPECT_FALSE(c.frontier(3.5f, 0.5f));
  EXPECT_FALSE(c.frontier(6.5f, 0.5f));
  EXPECT_FALSE(c.frontier(7.5f, 0.5f));
  EXPECT_FALSE(c.frontier(1.5f, 0.5f));  // flown (a neighbour of the mark at the origin)
  EXPECT_FALSE(c.frontier(3.5f, 2.5f));
  // A wall's cell stays one when a later beam crosses it (a 1 m cell holds the wall and the
  // free space before it): what is behind it does not become a frontier.
  g.mark_seen({6.5f, 0.5f});
  EXPECT_FALSE(c.frontier(7.5f, 0.5f));
  EXPECT_FALSE(c.frontier(6.5f, 0.5f));
  // Off the grid and for non-finite points nothing is marked or a frontier.
  g.mark_seen({std::nanf(""), 0.5f});
  g.mark_wall({INFINITY, 0.5f});
  g.mark_seen({100.0f, 0.5f});
  EXPECT_FALSE(g.frontier_cell(-1, 0));
  EXPECT_FALSE(g.frontier_cell(VisitedGrid::kSide, 0));
  g.clear();
  g.mark({0.0f, 0.0f});
  EXPECT_FALSE(c.seen(3.5f, 0.5f));
  EXPECT_FALSE(c.wall(6.5f, 0.5f));
  EXPECT_FALSE(c.frontier(3.5f, 1.5f));
}

TEST(VisitedGridFrontier, NothingIsMarkedBeforeTheGridIsAnchored) {
  VisitedGrid g;
  g.mark_seen({0.5f, 0.5f});
  g.mark_wall({1.5f, 0.5f});
  g.mark({0.0f, 0.0f});
  const CellOf c{g};
  EXPECT_FALSE(c.seen(0.5f, 0.5f));
  EXPECT_FALSE(c.wall(1.5f, 0.5f));
}

TEST(UnflownBearings, CountsTheFrontierCellsByBearingWeighedAsUnflownCells) {
  const VisitedGrid g = strip_seen_up_to_a_wall();
  UnflownBearings b;
  b.count(g, {0.5f, 0.5f}, RetraceTarget::kFrontier);
  // Eight frontier cells, all east: within the cone east, none west or north.
  EXPECT_GT(b.total(), 0u);
  EXPECT_EQ(b.score(0.0f), b.total());
  EXPECT_EQ(b.score(static_cast<float>(M_PI)), 0u);
  EXPECT_EQ(b.score(static_cast<float>(M_PI / 2)), 0u);
  // Each weighs kReachCells / its distance in cells, rounded, as an unflown cell does.
  uint32_t expected = 0;
  for (int dx = 2; dx <= 5; ++dx)
    for (int dy : {-1, 1})
      expected += static_cast<uint32_t>(std::lround(UnflownBearings::kReachCells / std::hypot(dx, dy)));
  EXPECT_EQ(b.total(), expected);
  // Counting unflown cells instead sees far more: the extent is the flown 3 x 3 cells only,
  // all flown, so none; and the frontier is not bounded by the extent.
  b.count(g, {0.5f, 0.5f}, RetraceTarget::kUnflown);
  EXPECT_EQ(b.total(), 0u);
}

TEST(RetraceTarget, NamesRoundTripAndOthersAreRefused) {
  for (RetraceTarget t : kRetraceTargets) {
    const Result<RetraceTarget> back = parse_retrace_target(to_string(t));
    ASSERT_TRUE(back.ok()) << to_string(t);
    EXPECT_EQ(back.value(), t);
  }
  EXPECT_FALSE(parse_retrace_target("seen").ok());
  EXPECT_FALSE(parse_retrace_target(nullptr).ok());
  SrtParams srt;
  srt.retrace_target = static_cast<RetraceTarget>(5);
  SrtStarPlanner planner;
  EXPECT_EQ(planner.configure(srt, GuidanceParams{}), Status::kInvalidArgument);
}

// A 4 x 5 m room, walls on the half metres (inside cells, not on their edges), with a 1.2 m door
// in its east wall, scanned by the URG-04LX from (2, 3) facing east: the root's arrival step.
struct RoomWithADoor {
  SegmentWorld world;
  RoomWithADoor() {
    world.add(0.5, 0.5, 4.5, 0.5);
    world.add(4.5, 0.5, 4.5, 2.4);
    world.add(4.5, 3.6, 4.5, 5.5);
    world.add(4.5, 5.5, 0.5, 5.5);
    world.add(0.5, 5.5, 0.5, 0.5);
  }
};

// The planner configured so, given `calls` scans of the room from (2, 3) facing east: the first
// grows the root (its arrival step done, sliced or not), the rest are scans on the way to the
// first waypoint, 2 d or more away.
std::unique_ptr<SrtStarPlanner> scanned(RetraceMode mode, RetraceTarget target, int calls,
                                        uint32_t work_per_cycle = 0) {
  auto planner = std::make_unique<SrtStarPlanner>();
  SrtParams srt;
  srt.retrace = mode;
  srt.retrace_target = target;
  srt.arrival_work_per_cycle = work_per_cycle;
  EXPECT_EQ(planner->configure(srt, GuidanceParams{}), Status::kOk);
  const RoomWithADoor room;
  const LaserScan scan = room.world.scan(LaserModel::urg04lx(), 2.0, 3.0, 0.0);
  bool fresh = false;
  const Pose2 at{2.0f, 3.0f, 0.0f};
  for (int call = 0; call < calls; ++call) {
    test::update_until_settled(*planner, at, scan, TimeUs{}, fresh, [](Status st) { EXPECT_EQ(st, Status::kOk); });
    EXPECT_EQ(planner->mode(), PlannerMode::kForward);
  }
  return planner;
}

// The URG-04LX's 682 beams are marked 64 or fewer a call, a different slice each call: 11 calls
// mark every direction.
constexpr int kSlicesOfTheUrg = 11;

TEST(SrtStarPlannerRetraceFrontier, TheScansMarkTheRoomSeenItsWallsAndTheFrontierThroughTheDoor) {
  const auto planner = scanned(RetraceMode::kAlways, RetraceTarget::kFrontier, kSlicesOfTheUrg);
  const CellOf c{planner->visited()};
  EXPECT_TRUE(c.seen(3.5f, 1.5f));
  EXPECT_TRUE(c.seen(3.5f, 4.5f));
  EXPECT_TRUE(c.wall(4.5f, 1.5f));  // the east wall's cells beside the door
  EXPECT_TRUE(c.wall(2.5f, 0.5f));  // the south wall's
  // Through the door nothing returns within the laser's 4 m: free out to R_p (3.5 m), x 5.5.
  EXPECT_TRUE(c.seen(5.2f, 3.0f));
  EXPECT_TRUE(c.frontier(6.5f, 3.5f));
  // Behind the walls the laser saw (south and north; the west wall lies in the blind arc, where
  // a 1 m cell holding it can be crossed by a beam and read free), nothing is a frontier.
  for (float x = 1.5f; x < 4.0f; x += 1.0f) {
    EXPECT_TRUE(c.wall(x, 0.5f)) << x;
    EXPECT_TRUE(c.wall(x, 5.5f)) << x;
    EXPECT_FALSE(c.frontier(x, -0.5f)) << x;
    EXPECT_FALSE(c.frontier(x, 6.5f)) << x;
  }
}

int count_cells(const VisitedGrid& g, bool (VisitedGrid::*layer)(int, int) const) {
  int n = 0;
  for (int iy = 0; iy < VisitedGrid::kSide; ++iy)
    for (int ix = 0; ix < VisitedGrid::kSide; ++ix) n += (g.*layer)(ix, iy) ? 1 : 0;
  return n;
}

// A call marks one slice of the beams, and its work stays a small share of the cycle's budget;
// after a slice of each kind nothing new is seen from the same place. The arrival step is
// sliced or not alike: the marks are made only between arrival steps.
TEST(SrtStarPlannerRetraceFrontier, EachScanMarksOneSliceAndEverySliceInTurn) {
  const auto one = scanned(RetraceMode::kAlways, RetraceTarget::kFrontier, 1);
  const auto all = scanned(RetraceMode::kAlways, RetraceTarget::kFrontier, kSlicesOfTheUrg);
  const auto twice = scanned(RetraceMode::kAlways, RetraceTarget::kFrontier, 2 * kSlicesOfTheUrg);
  const auto sliced = scanned(RetraceMode::kAlways, RetraceTarget::kFrontier, kSlicesOfTheUrg, 1);
  const int seen_one = count_cells(one->visited(), &VisitedGrid::seen_cell);
  const int seen_all = count_cells(all->visited(), &VisitedGrid::seen_cell);
  EXPECT_GT(seen_one, 0);
  EXPECT_GT(seen_all, seen_one);
  EXPECT_EQ(count_cells(twice->visited(), &VisitedGrid::seen_cell), seen_all);
  EXPECT_EQ(count_cells(twice->visited(), &VisitedGrid::wall_cell),
            count_cells(all->visited(), &VisitedGrid::wall_cell));
  for (int iy = 0; iy < VisitedGrid::kSide; ++iy) {
    for (int ix = 0; ix < VisitedGrid::kSide; ++ix) {
      EXPECT_EQ(all->visited().seen_cell(ix, iy), sliced->visited().seen_cell(ix, iy));
      EXPECT_EQ(all->visited().wall_cell(ix, iy), sliced->visited().wall_cell(ix, iy));
    }
  }
  // 62 beams of at most 4 m: under a third of the arrival budget a cycle (4.7 k units at most).
  EXPECT_GT(all->last_work(), 0u);
  EXPECT_LT(all->last_work(), SrtParams{}.arrival_work_per_cycle / 3);
}

// Only the frontier target marks the layers (it costs work on every scan), and only for a
// planner that retraces.
TEST(SrtStarPlannerRetraceFrontier, NoMarksWithoutTheFrontierTargetOrTheRetrace) {
  const auto unflown = scanned(RetraceMode::kAlways, RetraceTarget::kUnflown, kSlicesOfTheUrg);
  const auto off = scanned(RetraceMode::kOff, RetraceTarget::kFrontier, kSlicesOfTheUrg);
  const auto unguarded = scanned(RetraceMode::kGuarded, RetraceTarget::kFrontier, kSlicesOfTheUrg);
  for (const SrtStarPlanner* p : {unflown.get(), off.get(), unguarded.get()}) {
    EXPECT_EQ(count_cells(p->visited(), &VisitedGrid::seen_cell), 0);
    EXPECT_EQ(count_cells(p->visited(), &VisitedGrid::wall_cell), 0);
  }
}

}  // namespace
}  // namespace kestrel::exploration
