// The grid frontier explorer (paper 003 section 3.2) on synthetic scans, its two levels stepped
// in lockstep: the plan it flies, when it gives a goal up, the keep-out boxes, what crosses
// between the levels and what a reset forgets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/core/angle.hpp"
#include "kestrel/exploration/frontier_explorer.hpp"
#include "frontier_worlds.hpp"
#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

using test::LaserModel;
using test::nav_at;
using test::SegmentWorld;

const LaserModel kUrg = LaserModel::urg04lx();

using test_worlds::room_and_corridor;

struct Rig {
  std::unique_ptr<FrontierExplorer> ex = std::make_unique<FrontierExplorer>();
  SegmentWorld world;
  GuidanceSetpoint out;
  double t = 0;
  Status configure(const Params& p = {}) { return ex->configure(p, BeamGeometry::of(world.scan(kUrg, 1, 1, 0))); }
  // One guidance cycle of both levels with the vehicle at (x, y, heading), 0.1 s after the last.
  Status step(float x, float y, float heading, bool level3 = true) {
    t += 0.1;
    const LaserScan s = world.scan(kUrg, x, y, heading, TimeUs::from_s(t));
    const Status st = ex->step(nav_at(x, y, heading), s, out);
    if (level3) ex->background_step();
    return st;
  }
};

// The nearest frontier at first is behind the vehicle, in the laser's blind arc: the plan is
// to stay and face it.
TEST(FrontierExplorer, FirstItTurnsToFaceWhatItsBlindArcHid) {
  Rig r;
  r.world = room_and_corridor();
  ASSERT_EQ(r.configure(), Status::kOk);
  for (int k = 0; k < 3; ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.0f), Status::kOk);
  const FrontierPlan& plan = r.ex->plan_in_flight();
  ASSERT_TRUE(plan.has_goal);
  EXPECT_EQ(plan.path.size(), 1u);
  EXPECT_LT(plan.frontier.x, 2.0f);
  EXPECT_GT(std::fabs(r.ex->status().heading_target_rad), 1.5f);
}

// Having looked all round the room: the plan leads out through the door, the command points
// along it and the heading turns towards it.
TEST(FrontierExplorer, FliesThePathToTheNearestFrontier) {
  Rig r;
  r.world = room_and_corridor();
  ASSERT_EQ(r.configure(), Status::kOk);
  for (int k = 0; k < 130; ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.05f * static_cast<float>(k)), Status::kOk);
  for (int k = 0; k < 11; ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.0f), Status::kOk);
  const FrontierPlan& plan = r.ex->plan_in_flight();
  ASSERT_TRUE(plan.has_goal);
  ASSERT_GE(plan.path.size(), 2u);
  EXPECT_NEAR(plan.path[0].x, 2.0f, 0.15f);
  // The frontier lies out of the room, in the corridor beyond the door.
  EXPECT_GT(plan.frontier.x, 4.0f);
  EXPECT_GT(plan.frontier.y, 0.0f);
  const ExplorerStatus& st = r.ex->status();
  ASSERT_TRUE(st.has_target);
  EXPECT_GT(st.v_fr.x(), 0.2f);  // towards the door
  EXPECT_GT(r.out.velocity_mps.x(), 0.0f);
  EXPECT_LE(r.out.velocity_mps.head<2>().norm(), Params{}.guidance.speed_limit_mps + 1e-5f);
  EXPECT_NEAR(st.heading_target_rad, std::atan2(st.target.y - 2.0f, st.target.x - 2.0f), 1e-4f);
  const FrontierCounters c = r.ex->counters();
  EXPECT_EQ(c.scans_drawn, 141u);
  EXPECT_GE(c.plans, 14u);
  EXPECT_FALSE(r.ex->finished());
}

// A closed room: once the vehicle has turned round and seen all of it, nothing is left and
// the explorer says so (the mission then flies home).
TEST(FrontierExplorer, AClosedRoomSeenAllRoundIsExplored) {
  Rig r;
  r.world.add_box(0, 0, 3, 3);
  ASSERT_EQ(r.configure(), Status::kOk);
  for (int k = 0; k < 200 && !r.ex->finished(); ++k)
    ASSERT_EQ(r.step(1.5f, 1.5f, 0.05f * static_cast<float>(k)), Status::kOk);
  EXPECT_TRUE(r.ex->finished());
  EXPECT_FALSE(r.ex->plan_in_flight().has_goal);
  EXPECT_TRUE(r.ex->frontiers().empty());
}

// Without level 3 nothing is planned: the explorer holds where it is (the field alone), its
// scans wait in the one-slot queue and the rest are dropped and counted; it never says it is
// done.
TEST(FrontierExplorer, WithoutLevel3ItHoldsAndDropsScans) {
  Rig r;
  r.world = room_and_corridor();
  ASSERT_EQ(r.configure(), Status::kOk);
  for (int k = 0; k < 10; ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.0f, /*level3=*/false), Status::kOk);
  EXPECT_FALSE(r.ex->status().has_target);
  EXPECT_EQ(r.ex->status().v_fr, Eigen::Vector2f::Zero());  // the field alone
  const FrontierCounters c = r.ex->counters();
  EXPECT_EQ(c.scans_offered, 2u);
  EXPECT_EQ(c.scans_dropped, 8u);
  EXPECT_EQ(c.scans_drawn, 0u);
  EXPECT_FALSE(r.ex->finished());
  // Level 3 catches up on what waited and plans.
  ASSERT_EQ(r.step(2.0f, 2.0f, 0.0f), Status::kOk);
  ASSERT_EQ(r.step(2.0f, 2.0f, 0.0f), Status::kOk);
  EXPECT_TRUE(r.ex->status().has_target);
}

// Level 3 stalls after planning (a background thread that stopped): the plan it left is flown
// for up to 5 s, then the explorer holds on the field alone, counting the holds.
TEST(FrontierExplorer, AStalePlanIsNotFlown) {
  Rig r;
  r.world = room_and_corridor();
  ASSERT_EQ(r.configure(), Status::kOk);
  for (int k = 0; k < 5; ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.0f), Status::kOk);
  ASSERT_TRUE(r.ex->status().has_target);
  for (int k = 0; k < 45; ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.0f, /*level3=*/false), Status::kOk);
  EXPECT_TRUE(r.ex->status().has_target);  // 4.5 s after the last plan
  EXPECT_EQ(r.ex->counters().stale_holds, 0u);
  for (int k = 0; k < 10; ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.0f, /*level3=*/false), Status::kOk);
  EXPECT_FALSE(r.ex->status().has_target);
  EXPECT_EQ(r.ex->status().v_fr, Eigen::Vector2f::Zero());
  EXPECT_GT(r.ex->counters().stale_holds, 0u);
  // Level 3 back: it draws the two scans that waited, then a fresh one and plans; the plan
  // is flown at the step after.
  for (int k = 0; k < 3; ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.0f), Status::kOk);
  EXPECT_TRUE(r.ex->status().has_target);
}

// A vehicle that does not move (held by something the grid does not show) gives its goal up
// after stuck_time_s, blacklists it, and the next goal is elsewhere.
TEST(FrontierExplorer, AVehicleThatCannotMoveGivesItsGoalUp) {
  Rig r;
  r.world = room_and_corridor();
  Params p;
  p.frontier.stuck_time_s = 5.0f;
  p.frontier.patience_s = 100.0f;
  ASSERT_EQ(r.configure(p), Status::kOk);
  for (int k = 0; k < 20; ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.0f), Status::kOk);
  ASSERT_TRUE(r.ex->plan_in_flight().has_goal);
  const Point2 first = r.ex->plan_in_flight().frontier;
  for (int k = 0; k < 80; ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.0f), Status::kOk);
  const FrontierCounters c = r.ex->counters();
  EXPECT_GE(c.blacklisted, 1u);
  EXPECT_GE(c.stuck, 1u);
  ASSERT_FALSE(r.ex->blacklist().empty());
  EXPECT_NEAR(r.ex->blacklist()[0].x, first.x, 0.2f);
  EXPECT_NEAR(r.ex->blacklist()[0].y, first.y, 0.2f);
  if (r.ex->plan_in_flight().has_goal) {
    const Point2 now = r.ex->plan_in_flight().frontier;
    EXPECT_GT(std::hypot(now.x - first.x, now.y - first.y), p.frontier.blacklist_radius_m);
  }
}

// The operator's keep-out box across the door (a glass pane the laser sees through): the
// corridor is seen but no path leads there. The grid cannot tell that from walls drawn where
// there are none, so it is drawn again max_grid_restarts times; then the room is all there is.
TEST(FrontierExplorer, NoPathCrossesAKeepOutBox) {
  Rig r;
  r.world = room_and_corridor();
  Params p;
  p.srt.keep_out[0] = {3.8f, 1.2f, 4.4f, 2.8f};
  p.srt.keep_out_count = 1;
  p.frontier.relaxed_lethal_m = 0.0f;
  ASSERT_EQ(r.configure(p), Status::kOk);
  for (int k = 0; k < 600 && !r.ex->finished(); ++k) {
    ASSERT_EQ(r.step(2.0f, 2.0f, 0.05f * static_cast<float>(k)), Status::kOk);
    for (const Point2& q : r.ex->plan_in_flight().path) ASSERT_LT(q.x, 3.8f);
  }
  EXPECT_TRUE(r.ex->finished());
  EXPECT_EQ(r.ex->counters().grid_restarts, p.frontier.max_grid_restarts);
}

// The box lies where the estimate puts it: with the estimate 1.5 m off along the wall, the
// operator's box over a glass door lies beside the door's gap in the map. Taken 2 m longer
// along its wall (keep_out_drift_margin_m), it shuts the gap; as given, paths lead through.
TEST(FrontierExplorer, ADriftMarginShutsTheGapBesideADriftedBox) {
  float furthest_east[2] = {0.0f, 0.0f};
  for (const int with_margin : {0, 1}) {
    SCOPED_TRACE(with_margin);
    Rig r;
    r.world = room_and_corridor();  // the door's gap: x 4, y 1.4..2.6
    Params p;
    p.srt.keep_out[0] = {3.9f, 2.9f, 4.1f, 4.1f};
    p.srt.keep_out_count = 1;
    p.srt.keep_out_drift_margin_m = with_margin ? 2.0f : 0.0f;
    p.frontier.relaxed_lethal_m = 0.0f;
    ASSERT_EQ(r.configure(p), Status::kOk);
    for (int k = 0; k < 600 && !r.ex->finished(); ++k) {
      ASSERT_EQ(r.step(2.0f, 2.0f, 0.05f * static_cast<float>(k)), Status::kOk);
      for (const Point2& q : r.ex->plan_in_flight().path)
        furthest_east[with_margin] = std::max(furthest_east[with_margin], q.x);
    }
  }
  EXPECT_GT(furthest_east[0], 4.2f);  // out through the door
  EXPECT_LT(furthest_east[1], 3.8f);
}

// Frontiers the search cannot reach, with none it can: the grid is forgotten and drawn again
// from where the vehicle is (walls drawn while the estimate ran away shut the rest off); with
// max_grid_restarts 0 the explorer finishes at once instead.
TEST(FrontierExplorer, InaccessibleFrontiersRestartTheGridAFewTimes) {
  for (uint8_t restarts : {uint8_t{0}, uint8_t{1}}) {
    Rig r;
    r.world = room_and_corridor();
    Params p;
    p.srt.keep_out[0] = {3.8f, 1.2f, 4.4f, 2.8f};
    p.srt.keep_out_count = 1;
    p.frontier.max_grid_restarts = restarts;
    ASSERT_EQ(r.configure(p), Status::kOk);
    int k = 0;
    for (; k < 600 && !r.ex->finished(); ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.05f * static_cast<float>(k)), Status::kOk);
    EXPECT_TRUE(r.ex->finished());
    EXPECT_EQ(r.ex->counters().grid_restarts, restarts);
    EXPECT_GT(r.ex->frontier_cells().inaccessible(), 0u);
  }
}

// Paper 003: a goal pose placed a predefined distance apart from the frontier, in free space.
TEST(FrontierExplorer, ThePathEndsShortOfTheFrontier) {
  Rig r;
  r.world = room_and_corridor();
  ASSERT_EQ(r.configure(), Status::kOk);
  for (int k = 0; k < 130; ++k) ASSERT_EQ(r.step(2.0f, 2.0f, 0.05f * static_cast<float>(k)), Status::kOk);
  const FrontierPlan& plan = r.ex->plan_in_flight();
  ASSERT_TRUE(plan.has_goal);
  ASSERT_GE(plan.path.size(), 2u);
  const Point2 end = plan.path.back();
  const float gap = std::hypot(end.x - plan.frontier.x, end.y - plan.frontier.y);
  EXPECT_GE(gap, Params{}.frontier.goal_inset_m - 0.13f);
  EXPECT_LE(gap, Params{}.frontier.goal_inset_m + 0.2f);
}

// reset() forgets the map at level 3's next step (on a board level 3 may be running then).
TEST(FrontierExplorer, ResetForgetsTheMapAtLevel3sNextStep) {
  Rig r;
  r.world.add_box(0, 0, 3, 3);
  ASSERT_EQ(r.configure(), Status::kOk);
  for (int k = 0; k < 200 && !r.ex->finished(); ++k)
    ASSERT_EQ(r.step(1.5f, 1.5f, 0.05f * static_cast<float>(k)), Status::kOk);
  ASSERT_TRUE(r.ex->finished());
  ASSERT_GT(r.ex->grid().scans_drawn(), 0u);
  r.ex->reset();
  EXPECT_FALSE(r.ex->finished());
  r.ex->background_step();
  EXPECT_EQ(r.ex->counters().scans_drawn, 0u);
  ASSERT_EQ(r.step(1.5f, 1.5f, 0.0f), Status::kOk);
  EXPECT_EQ(r.ex->grid().scans_drawn(), 1u);
}

TEST(FrontierExplorer, RefusesInconsistentParameters) {
  Rig r;
  Params p;
  p.frontier.lethal_m = 0.3f;  // nearer the walls than the limiter's 0.4 m allows
  p.frontier.relaxed_lethal_m = 0.25f;
  EXPECT_EQ(p.validate(), Status::kOk);  // alone consistent: the other explorers take it
  EXPECT_EQ(r.configure(p), Status::kInvalidArgument);
  p.approach.enabled = false;
  EXPECT_EQ(r.configure(p), Status::kOk);
  p = {};
  p.frontier.relaxed_lethal_m = 0.5f;  // above lethal_m
  EXPECT_EQ(r.configure(p), Status::kInvalidArgument);
  p = {};
  p.frontier.soft_m = 0.2f;  // below lethal_m
  EXPECT_EQ(r.configure(p), Status::kInvalidArgument);
  p = {};
  p.frontier.cell_m = NAN;
  EXPECT_EQ(r.configure(p), Status::kInvalidArgument);
  // Regression (audit): distances beyond the rays' 60 m overflowed the cell arithmetic (a
  // blacklist disc of 6 km excluded nothing; a minimum frontier of 100 km wrapped its count).
  p = {};
  p.frontier.blacklist_radius_m = 6000.0f;
  EXPECT_EQ(p.validate(), Status::kInvalidArgument);
  p = {};
  p.frontier.min_frontier_m = 1e5f;
  EXPECT_EQ(p.validate(), Status::kInvalidArgument);
  p = {};
  p.frontier.switch_margin_m = INFINITY;
  EXPECT_EQ(p.validate(), Status::kInvalidArgument);
  // Nor may the blend's waypoint distance d wrap its 16-bit twice-d step (33 m became 0.46 m).
  p = {};
  p.guidance.arrival_distance_m = 33.0f;
  EXPECT_EQ(p.validate(), Status::kInvalidArgument);
  p = {};
  p.frontier.soft_m = 40.0f;  // beyond the obstacle distance's 85 cells
  EXPECT_EQ(r.configure(p), Status::kInvalidArgument);
  p = {};
  p.frontier.replan_period_s = 10.0f;  // every plan would be stale before the next
  EXPECT_EQ(r.configure(p), Status::kInvalidArgument);
}

TEST(FrontierExplorer, NeitherLevelAllocates) {
  Rig r;
  r.world = room_and_corridor();
  ASSERT_EQ(r.configure(), Status::kOk);
  alloc_guard::Scope guard;
  for (int k = 0; k < 30; ++k) (void)r.step(2.0f + 0.05f * static_cast<float>(k), 2.0f, 0.0f);
  EXPECT_EQ(guard.allocations(), 0u);
}

}  // namespace
}  // namespace kestrel::exploration
