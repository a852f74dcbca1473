// srt.retrace: the path flown, loops kept (flown_history.hpp), and a tree that runs out where
// nothing is left unflown flying back along it to where more is (srt_star_planner.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "kestrel/exploration/flown_history.hpp"
#include "kestrel/exploration/srt_star_planner.hpp"
#include "kestrel/exploration/work_units.hpp"
#include "retrace_flight_out.hpp"
#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

using test::LaserModel;
using test::uniform_scan;

const LaserModel kUrg = LaserModel::urg04lx();

TEST(FlownHistory, KeepsPointsASpacingApartInTheOrderFlown) {
  FlownHistory h;
  const float s = FlownHistory::kSpacingM;
  for (int i = 0; i <= 100; ++i) h.record({0.1f * s * static_cast<float>(i), 0});  // 10 spacings east
  ASSERT_EQ(h.size(), 11u);
  for (std::size_t i = 0; i < h.size(); ++i) EXPECT_NEAR(h.point(i).x, s * static_cast<float>(i), 1e-4f);
  // Back the same way: a loop is kept, unlike the mission's breadcrumb trail.
  for (int i = 99; i >= 0; --i) h.record({0.1f * s * static_cast<float>(i), 0});
  EXPECT_EQ(h.size(), 21u);
  EXPECT_NEAR(h.point(20).x, 0.0f, 1e-4f);
  h.record({NAN, 0});
  h.record({0, INFINITY});
  EXPECT_EQ(h.size(), 21u);
}

TEST(FlownHistory, WhenFullEveryOtherPointGoesTheNewestStaysAndTheSpacingDoubles) {
  FlownHistory h;
  for (std::size_t i = 0; i < FlownHistory::kCapacity; ++i) h.record({static_cast<float>(i), 0});  // 1 m apart
  ASSERT_EQ(h.size(), FlownHistory::kCapacity);
  h.record({static_cast<float>(FlownHistory::kCapacity) + 1.0f, 0});
  EXPECT_FLOAT_EQ(h.spacing_m(), 2.0f * FlownHistory::kSpacingM);
  EXPECT_EQ(h.size(), FlownHistory::kCapacity / 2 + 2);
  EXPECT_FLOAT_EQ(h.point(0).x, 0.0f);
  EXPECT_FLOAT_EQ(h.point(1).x, 2.0f);
  EXPECT_FLOAT_EQ(h.point(h.size() - 2).x, static_cast<float>(FlownHistory::kCapacity - 1));
  EXPECT_FLOAT_EQ(h.point(h.size() - 1).x, static_cast<float>(FlownHistory::kCapacity) + 1.0f);
}

TEST(FlownHistory, FindsTheEarliestVisitOfAPlaceAndCutsBackToAPoint) {
  FlownHistory h;
  const Point2 path[] = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {1, -0.1f}, {1, -1.2f}};
  for (const Point2& p : path) h.record(p);
  ASSERT_EQ(h.size(), 7u);
  EXPECT_EQ(h.earliest_near(0, 5, h.point(5), 0.5f), 1u);  // (1, -0.1) is where (1, 0) was
  EXPECT_EQ(h.earliest_near(2, 5, h.point(5), 0.5f), 5u);  // not after index 2: itself
  EXPECT_EQ(h.earliest_near(0, 6, {9, 9}, 0.5f), 6u);      // nowhere near: the last
  h.keep_first(3);
  EXPECT_EQ(h.size(), 3u);
  EXPECT_FLOAT_EQ(h.point(2).x, 2.0f);
}

using test::Outward;

struct RetraceFlight {
  std::unique_ptr<SrtStarPlanner> planner = std::make_unique<SrtStarPlanner>();
  std::vector<Point2> waypoints;  // issued while retracing
  std::vector<Point2> arrivals;   // where the vehicle was when each counted as reached
  std::vector<uint32_t> arrival_work;  // Arrival::kOnTheWaypoint: the work of the arriving call
  uint32_t most_work = 0;              // of any call
  std::size_t trail_at_retrace = 0;    // the path flown's points when the way back began
  Pose2 end{};
};

enum class Arrival { kOnTheWaypoint, kAsEarlyAsAllowed };

// The root at the start sees open space only to the west (behind the flight, so no waypoint
// is ever reached on the way out); the flight out runs past the time limit, and the fresh tree
// at its end is grown from a scan with walls 1 m away all round: it runs out at once. Then
// the vehicle is put on each waypoint in turn.
// Arrival::kAsEarlyAsAllowed: on the way back the vehicle flies straight at each waypoint from
// where it was, and turns for the next one where the planner first gives it.
// work_per_cycle: the arrival step's budget, 0 for one shot; 1 runs one item a call.
constexpr uint32_t kOneShot = 0;
constexpr uint32_t kVerdexSlices = SrtParams{}.arrival_work_per_cycle;

RetraceFlight fly(RetraceMode mode, int retrace_legs = 300, uint32_t work_per_cycle = kOneShot,
                  Arrival arrival = Arrival::kOnTheWaypoint, bool guarded = false,
                  Outward shape = Outward::kLawnMower) {
  RetraceFlight r;
  SrtParams srt;
  srt.arrival_work_per_cycle = work_per_cycle;
  srt.retrace = mode;
  GuidanceParams g;
  g.waypoint_time_limit_s = 1000.0f;
  EXPECT_EQ(r.planner->configure(srt, g, guarded), Status::kOk);
  // Every call's work, for the budget's test.
  const auto check = [&r](Status st) {
    EXPECT_EQ(st, Status::kOk);
    r.most_work = std::max(r.most_work, r.planner->last_work());
  };
  const LaserScan enclosed = test::retrace_enclosed_scan();
  bool fresh = false;
  test::retrace_take_start(*r.planner, fresh, check);
  EXPECT_EQ(r.planner->mode(), PlannerMode::kForward);
  EXPECT_LT(r.planner->waypoint().x, -0.3f);
  test::retrace_fly_out(*r.planner, shape, fresh, [&](Status st) {
    check(st);
    EXPECT_FALSE(fresh);
  });
  EXPECT_EQ(r.planner->restarts(), 0u);
  const Point2 last = test::retrace_flight_out(shape).back();
  r.end = {last.x, last.y, 0};
  TimeUs t = TimeUs::from_s(1001);
  // Sliced, the arrival step (the trail's count among it) goes on over the next calls, the
  // vehicle waiting where it is.
  test::update_until_settled(*r.planner, r.end, enclosed, t, fresh, check);
  EXPECT_EQ(r.planner->restarts(RestartReason::kTimeout), 1u);
  r.trail_at_retrace = r.planner->trail().size();
  for (int k = 0; k < retrace_legs && r.planner->mode() == PlannerMode::kRetrace; ++k) {
    r.waypoints.push_back(r.planner->waypoint());
    const Point2 w = r.planner->waypoint();
    if (arrival == Arrival::kAsEarlyAsAllowed) {
      // In 2 cm steps, 0.1 s apart, until the planner moves on.
      const Point2 from{r.end.x, r.end.y};
      const int steps = std::max(1, static_cast<int>(std::ceil(distance(from, w) / 0.02f)));
      for (int i = 1; i <= steps; ++i) {
        const float f = static_cast<float>(i) / static_cast<float>(steps);
        r.end = {from.x + f * (w.x - from.x), from.y + f * (w.y - from.y), 0};
        t += Duration::from_ms(100);
        test::update_until_settled(*r.planner, r.end, enclosed, t, fresh, check);
        if (r.planner->mode() != PlannerMode::kRetrace || r.planner->waypoint().x != w.x ||
            r.planner->waypoint().y != w.y)
          break;
      }
      r.arrivals.push_back({r.end.x, r.end.y});
      continue;
    }
    r.end = {w.x, w.y, 0};
    r.arrivals.push_back({w.x, w.y});
    t += Duration::from_s(1);
    bool arriving = true;  // the first call's work is the arrival's
    test::update_until_settled(*r.planner, r.end, enclosed, t, fresh, [&](Status st) {
      check(st);
      if (arriving) r.arrival_work.push_back(r.planner->last_work());
      arriving = false;
    });
  }
  return r;
}

TEST(SrtStarPlannerRetrace, ARunOutWithNothingUnflownNearFliesBackToWhereMoreIsSkippingTheLoop) {
  const RetraceFlight r = fly(RetraceMode::kAlways);
  EXPECT_EQ(r.planner->retraces(), 1u);
  ASSERT_GE(r.waypoints.size(), 10u);
  EXPECT_NE(r.planner->mode(), PlannerMode::kRetrace);
  EXPECT_EQ(r.planner->restarts(RestartReason::kRetraced), 1u);
  // Every waypoint is a point of the flight out, 2 m or so from the one before; the loop
  // north (y over 1.5 m between x 20 and 22) is not flown again.
  const std::vector<Point2> out = test::retrace_flight_out();
  const auto off_the_path = [&out](Point2 q) {
    float nearest = 1e9f;
    for (const Point2& p : out) nearest = std::min(nearest, std::hypot(p.x - q.x, p.y - q.y));
    return nearest;
  };
  // Each leg, not only its ends, keeps to the path flown: a corner cut on the way back can
  // go through the wall of the door the vehicle came by.
  Point2 before{r.waypoints.front()};
  for (const Point2& w : r.waypoints) {
    EXPECT_LT(off_the_path(w), 0.3f) << w.x << ", " << w.y;
    for (int k = 1; k < 10; ++k) {
      const float f = 0.1f * static_cast<float>(k);
      const Point2 q{before.x + f * (w.x - before.x), before.y + f * (w.y - before.y)};
      EXPECT_LT(off_the_path(q), 0.35f) << "the leg to " << w.x << ", " << w.y << " leaves the path at " << q.x << ", "
                                        << q.y;
    }
    EXPECT_FALSE(w.x > 19.5f && w.x < 22.5f && w.y > 1.5f) << "the loop again at " << w.x << ", " << w.y;
    EXPECT_LT(std::hypot(w.x - before.x, w.y - before.y),
              SrtStarPlanner::kRetraceStepM + 2.0f * FlownHistory::kSpacingM);
    before = w;
  }
  // It ended beside the unflown rooms, on the first leg of the flight, where the fresh trees
  // grew (each ran out against the walls of the scans given: once more, then the look back).
  EXPECT_LT(r.end.x, 19.0f);
  EXPECT_NEAR(r.end.y, 0.0f, 0.3f);
  ASSERT_FALSE(r.planner->tree().nodes().empty());
  EXPECT_NEAR(r.planner->tree().nodes()[0].position.x, r.end.x, 1e-4f);
  EXPECT_LE(r.planner->trail().size(), 40u);  // cut back to where the retrace ended
}

// A leg's end counts as reached before the vehicle is on it (kRetraceArrivalM), but never so
// early that the straight line on to the next leg's end cuts the corner by more than
// kRetraceDeviationM: the early turn past a door's jamb was what the review's corner bound
// missed (SRT alone, kinematic flights, touching the partition's end).
TEST(SrtStarPlannerRetrace, TurningEarlyForTheNextLegCutsNoCornerByMoreThanTheDeviation) {
  const RetraceFlight r = fly(RetraceMode::kAlways, 300, kOneShot, Arrival::kAsEarlyAsAllowed);
  EXPECT_EQ(r.planner->retraces(), 1u);
  ASSERT_GE(r.waypoints.size(), 10u);
  const std::vector<Point2> out = test::retrace_flight_out();
  std::size_t early = 0;
  for (std::size_t k = 0; k + 1 < r.waypoints.size(); ++k) {
    const float cut = distance_to_segment(r.arrivals[k], r.waypoints[k + 1], r.waypoints[k]);
    EXPECT_LE(cut, SrtStarPlanner::kRetraceDeviationM + 0.01f) << "at " << r.waypoints[k].x << ", " << r.waypoints[k].y;
    early += distance(r.arrivals[k], r.waypoints[k]) > 0.3f ? 1 : 0;
    // The line actually flown, from where the vehicle turned, keeps to the path flown out.
    for (int i = 1; i < 10; ++i) {
      const float f = 0.1f * static_cast<float>(i);
      const Point2 q{r.arrivals[k].x + f * (r.waypoints[k + 1].x - r.arrivals[k].x),
                     r.arrivals[k].y + f * (r.waypoints[k + 1].y - r.arrivals[k].y)};
      float nearest = 1e9f;
      for (const Point2& p : out) nearest = std::min(nearest, distance(p, q));
      EXPECT_LT(nearest, 0.35f) << "the turn at " << r.waypoints[k].x << ", " << r.waypoints[k].y
                                << " leaves the path at " << q.x << ", " << q.y;
    }
  }
  // On the straight stretches the turn comes well before the waypoint: the flight goes on.
  EXPECT_GE(early, r.waypoints.size() / 2);
  // And it still ends where the one-by-one flight ends, beside the unflown rooms.
  EXPECT_LT(r.end.x, 19.0f);
}

// The trail's count and the arrival steps in slices, as on the Verdex: the same way back.
TEST(SrtStarPlannerRetrace, SlicedTheWayBackIsTheOneShotOne) {
  const RetraceFlight whole = fly(RetraceMode::kAlways);
  const RetraceFlight sliced = fly(RetraceMode::kAlways, 300, kVerdexSlices);
  ASSERT_EQ(sliced.planner->retraces(), 1u);
  ASSERT_EQ(sliced.waypoints.size(), whole.waypoints.size());
  for (std::size_t i = 0; i < whole.waypoints.size(); ++i) {
    EXPECT_FLOAT_EQ(sliced.waypoints[i].x, whole.waypoints[i].x) << i;
    EXPECT_FLOAT_EQ(sliced.waypoints[i].y, whole.waypoints[i].y) << i;
  }
  EXPECT_FLOAT_EQ(sliced.end.x, whole.end.x);
}

// Each arrival on the way back finds the leg after the next: the earliest visit of its end, a
// search from the trail's best point up to it, is work the cycle's budget must see (on the
// Verdex, a trail point's test is software floating point).
TEST(SrtStarPlannerRetrace, EveryArrivalOnTheWayBackCountsItsSearchWithinTheBudget) {
  const RetraceFlight r = fly(RetraceMode::kAlways, 300, kVerdexSlices);
  ASSERT_GE(r.arrival_work.size(), 10u);
  // The first legs start some 200 trail points after the best one, near the start.
  EXPECT_GT(r.arrival_work.front(), 100 * work::kTrailPoint);
  // The last two arrivals are at the leg before the last, which has no leg after it, and at the
  // last, where the fresh tree's step counts its own.
  for (std::size_t k = 0; k + 2 < r.arrival_work.size(); ++k) {
    EXPECT_GE(r.arrival_work[k], 1 + work::kTrailPoint) << k;  // at least one point tested
    EXPECT_LE(r.arrival_work[k], SrtParams{}.arrival_work_per_cycle) << k;
  }
  // No call, the trail's count and the retrace's start among them, goes past the budget by
  // more than the item it finishes (srt_star_planner.hpp).
  EXPECT_LE(r.most_work, SrtParams{}.arrival_work_per_cycle + 1 + (FlownHistory::kCapacity + 50) * work::kTrailPoint);
  // Nearer the best point there is less to search.
  EXPECT_LT(r.arrival_work[r.arrival_work.size() - 3], r.arrival_work.front());
}

// One item a call (a budget of 1 unit), so a call's work is the largest item it ran: with the
// history nearly full, the retrace's start is two searches along it, each an item of its own
// (kTrailScan's last, kRetraceBegin). Done as one, that call would be twice the largest.
TEST(SrtStarPlannerRetrace, WithANearlyFullHistoryNoItemSearchesItTwice) {
  const RetraceFlight r = fly(RetraceMode::kAlways, 400, 1, Arrival::kOnTheWaypoint, false, Outward::kLong);
  ASSERT_EQ(r.planner->retraces(), 1u);
  ASSERT_GE(r.trail_at_retrace, 800u);
  ASSERT_LT(r.trail_at_retrace, FlownHistory::kCapacity);  // not thinned
  // The rooms beside the start drew it back: the first search ran most of the history.
  EXPECT_LT(r.end.x, 19.0f);
  EXPECT_GT(r.most_work, r.trail_at_retrace / 2 * work::kTrailPoint);
  // One search of every point, next_leg's few tests of the points a leg skips, and the item's 1.
  constexpr uint32_t kLegTests = 4 * work::kTrailPoint + 6 * work::kPathBeam;  // 2 m of 0.5 m points
  EXPECT_LE(r.most_work, 2 + r.trail_at_retrace * work::kTrailPoint + kLegTests) << r.most_work;
}

// Held on a leg of the way back until the time limit: exploration restarts where the vehicle
// is, and the path flown ends there too, not where the retrace began (a later retrace would
// fly the jump between them).
TEST(SrtStarPlannerRetrace, TheTimeLimitOnTheWayBackCutsTheHistoryToWhereTheVehicleIs) {
  RetraceFlight r = fly(RetraceMode::kAlways, 5);
  ASSERT_EQ(r.planner->mode(), PlannerMode::kRetrace);
  const std::size_t before = r.planner->trail().size();
  // Stuck half-way to the next waypoint.
  const Point2 w = r.planner->waypoint();
  const Pose2 stuck{0.5f * (r.end.x + w.x), 0.5f * (r.end.y + w.y), 0};
  bool fresh = false;
  const TimeUs late = r.planner->waypoint_time() + Duration::from_s(1001);
  ASSERT_EQ(r.planner->update(stuck, uniform_scan(kUrg, 1000), late, fresh), Status::kOk);
  EXPECT_NE(r.planner->mode(), PlannerMode::kRetrace);
  EXPECT_EQ(r.planner->restarts(RestartReason::kTimeout), 2u);
  const FlownHistory& h = r.planner->trail();
  ASSERT_LT(h.size(), before);
  const Point2 last = h.point(h.size() - 1);
  EXPECT_LT(std::hypot(last.x - stuck.x, last.y - stuck.y), 2.0f * SrtStarPlanner::kRetraceStepM);
}

TEST(SrtStarPlannerRetrace, OffTheRunOutGoesOnWhereTheVehicleIs) {
  const RetraceFlight r = fly(RetraceMode::kOff);
  EXPECT_EQ(r.planner->retraces(), 0u);
  EXPECT_TRUE(r.waypoints.empty());
  EXPECT_EQ(r.planner->restarts(RestartReason::kRetraced), 0u);
  EXPECT_EQ(r.planner->mode(), PlannerMode::kLookBack);
  EXPECT_FLOAT_EQ(r.planner->waypoint().x, 38.0f);
}

// kGuarded: only a planner whose explorer's commands the approach limiter guards (the blend)
// flies back along a path it may have flown close to a jamb; SRT alone does not.
TEST(SrtStarPlannerRetrace, GuardedRetracesOnlyAGuardedPlanner) {
  const RetraceFlight unguarded = fly(RetraceMode::kGuarded);
  EXPECT_FALSE(unguarded.planner->retraces_enabled());
  EXPECT_EQ(unguarded.planner->retraces(), 0u);
  EXPECT_EQ(unguarded.planner->trail().size(), 0u);  // nor is the path kept
  const RetraceFlight guarded = fly(RetraceMode::kGuarded, 300, kOneShot, Arrival::kOnTheWaypoint, true);
  EXPECT_TRUE(guarded.planner->retraces_enabled());
  EXPECT_EQ(guarded.planner->retraces(), 1u);
  EXPECT_LT(guarded.end.x, 19.0f);
}

TEST(SrtStarPlannerRetrace, ModesRoundTripByNameAndOthersAreRefused) {
  for (RetraceMode m : kRetraceModes) {
    const Result<RetraceMode> back = parse_retrace_mode(to_string(m));
    ASSERT_TRUE(back.ok()) << to_string(m);
    EXPECT_EQ(back.value(), m);
  }
  EXPECT_FALSE(parse_retrace_mode("yes").ok());
  EXPECT_FALSE(parse_retrace_mode(nullptr).ok());
  SrtParams srt;
  srt.retrace = static_cast<RetraceMode>(7);
  SrtStarPlanner planner;
  EXPECT_EQ(planner.configure(srt, GuidanceParams{}), Status::kInvalidArgument);
}

}  // namespace
}  // namespace kestrel::exploration
