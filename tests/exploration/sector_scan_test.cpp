// SRT-Star perception (paper 002 section IV, Fig. 3): sectors, safe-region radii and frontier
// classification on synthetic scans.
#include "kestrel/exploration/sector_scan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "synthetic_world.hpp"

namespace kestrel::exploration {
namespace {

using test::LaserModel;
using test::SegmentWorld;
using test::uniform_scan;

int count_kind(const SectorScan& s, FrontierKind k) {
  int n = 0;
  for (const LocalFrontier& f : s.frontiers()) n += f.kind == k ? 1 : 0;
  return n;
}

// A small room with a 1.4 m doorway 1 m ahead of the vehicle; behind it a room whose far wall is
// 3 m away.
SegmentWorld doorway_scene() {
  SegmentWorld w;
  w.add(-1.0, -1.2, -1.0, 1.2);  // the small room the vehicle is in
  w.add(-1.0, -1.2, 1.0, -1.2);
  w.add(-1.0, 1.2, 1.0, 1.2);
  w.add(1.0, -3.0, 1.0, -0.7);  // its front wall with the doorway, shared with the next room
  w.add(1.0, 0.7, 1.0, 3.0);
  w.add(1.0, -3.0, 3.0, -3.0);  // the next room
  w.add(1.0, 3.0, 3.0, 3.0);
  w.add(3.0, -3.0, 3.0, 3.0);
  return w;
}

// A 2 m corridor closed 12 m ahead, its walls seen aslant from inside.
SegmentWorld corridor_scene() {
  SegmentWorld w;
  w.add(-3.0, -1.0, 12.0, -1.0);
  w.add(-3.0, 1.0, 12.0, 1.0);
  w.add(12.0, -1.0, 12.0, 1.0);
  return w;
}

class SectorTest : public ::testing::Test {
 protected:
  std::unique_ptr<SectorScan> sectors = std::make_unique<SectorScan>();
  SrtParams params;
  LaserModel urg = LaserModel::urg04lx();
};

TEST_F(SectorTest, OpenSpaceMakesEverySectorFreeWithItsMidPointAFrontier) {
  ASSERT_EQ(sectors->build(uniform_scan(urg, range_code::kNoReturn), params), Status::kOk);
  ASSERT_EQ(sectors->count(), params.sector_count);
  EXPECT_NEAR(sectors->width_rad() * sectors->count(), urg.fov_rad, 1e-5);
  EXPECT_NEAR(sectors->start_rad(), -urg.fov_rad / 2, 1e-5);
  for (uint16_t s = 0; s < sectors->count(); ++s) {
    EXPECT_TRUE(sectors->obstacle_free(s));
    EXPECT_EQ(sectors->radius_mm(s), 3500);
  }
  EXPECT_EQ(count_kind(*sectors, FrontierKind::kMid), params.sector_count);
  EXPECT_EQ(count_kind(*sectors, FrontierKind::kLeft) + count_kind(*sectors, FrontierKind::kRight), 0);
  const LocalFrontier& f = sectors->frontiers()[3];
  EXPECT_FLOAT_EQ(f.range_m, 3.5f);
  EXPECT_NEAR(f.angle_rad, sectors->mid_angle(f.sector), 1e-6);
}

TEST_F(SectorTest, ReturnsBeyondPerceptionRangeStillCountAsFree) {
  ASSERT_EQ(sectors->build(uniform_scan(urg, 3800), params), Status::kOk);
  EXPECT_EQ(count_kind(*sectors, FrontierKind::kMid), params.sector_count);
}

TEST_F(SectorTest, FullyEnclosedRoomHasNoFrontier) {
  SegmentWorld room;
  room.add_box(-2.0, -1.5, 2.5, 1.5);
  for (double heading : {0.0, 0.7, 2.0, -2.5}) {
    ASSERT_EQ(sectors->build(room.scan(urg, 0.2, 0.1, heading), params), Status::kOk);
    EXPECT_TRUE(sectors->frontiers().empty()) << "heading " << heading;
    for (uint16_t s = 0; s < sectors->count(); ++s) EXPECT_FALSE(sectors->obstacle_free(s));
  }
}

TEST_F(SectorTest, DoorwayGivesDiscontinuityFrontiersOnTheFarSide) {
  ASSERT_EQ(sectors->build(doorway_scene().scan(urg, 0, 0, 0), params), Status::kOk);
  EXPECT_EQ(count_kind(*sectors, FrontierKind::kMid), 0);  // the far wall is within R_p
  ASSERT_EQ(count_kind(*sectors, FrontierKind::kRight), 1);
  ASSERT_EQ(count_kind(*sectors, FrontierKind::kLeft), 1);
  for (const LocalFrontier& f : sectors->frontiers()) {
    // Both on the doorway's edges, in the far-reaching sectors, at their radius (about 3 m).
    EXPECT_LT(std::fabs(f.angle_rad), std::atan2(0.7, 1.0) + 0.01);
    EXPECT_GT(f.range_m, 2.9f);
    EXPECT_GT(sectors->radius_mm(f.sector), 2900);
    const uint16_t nb = f.kind == FrontierKind::kRight ? f.sector - 1 : f.sector + 1;
    EXPECT_LT(sectors->radius_mm(nb), 1500) << "the neighbour beyond the edge is the wall";
  }
}

// From inside a 2 m corridor its walls, seen aslant, step the sectors' nearest returns by more
// than discontinuity_m from one sector to the next with no gap anywhere: the points such steps
// make lie on the walls, where no later safe region covers them. The range never jumps between
// neighbouring beams there, so by default they are no frontiers (paper 002's radii alone: some).
TEST_F(SectorTest, AWallSeenAslantIsNoDiscontinuity) {
  const SegmentWorld corridor = corridor_scene();
  for (double heading : {0.0, 0.3, -0.5}) {
    const LaserScan scan = corridor.scan(urg, 0.0, 0.5, heading);
    ASSERT_EQ(sectors->build(scan, params), Status::kOk);
    EXPECT_EQ(count_kind(*sectors, FrontierKind::kLeft) + count_kind(*sectors, FrontierKind::kRight), 0)
        << "heading " << heading;
    SrtParams paper = params;
    paper.discontinuity_needs_beam_jump = false;
    ASSERT_EQ(sectors->build(scan, paper), Status::kOk);
    EXPECT_GE(count_kind(*sectors, FrontierKind::kLeft) + count_kind(*sectors, FrontierKind::kRight), 1)
        << "heading " << heading;
  }
}

// Beams that say nothing of their direction (dropouts, deflected beams) are stepped over when
// looking for a jump: dropouts along the corridor's walls make no jump of their own, and a
// dropout on the doorway's edge beam leaves the jump across it (and the door's frontiers).
TEST_F(SectorTest, BeamsWithoutAReturnAreSteppedOverForJumps) {
  const SegmentWorld corridor = corridor_scene();
  LaserScan scan = corridor.scan(urg, 0.0, 0.5, 0.0);
  for (std::size_t i = 0; i < scan.beam_count; i += 7)
    scan.range_mm[i] = i % 2 == 0 ? range_code::kDropout : range_code::kDeflected;
  ASSERT_EQ(sectors->build(scan, params), Status::kOk);
  EXPECT_EQ(count_kind(*sectors, FrontierKind::kLeft) + count_kind(*sectors, FrontierKind::kRight), 0);

  scan = doorway_scene().scan(urg, 0, 0, 0);
  int edges = 0;
  for (std::size_t i = 1; i < scan.beam_count; ++i) {
    if (std::abs(int{scan.range_mm[i]} - int{scan.range_mm[i - 1]}) > 1000) {
      scan.range_mm[i] = range_code::kDropout;  // the first beam past each jamb
      ++edges;
      ++i;
    }
  }
  ASSERT_EQ(edges, 2);
  ASSERT_EQ(sectors->build(scan, params), Status::kOk);
  EXPECT_EQ(count_kind(*sectors, FrontierKind::kLeft), 1);
  EXPECT_EQ(count_kind(*sectors, FrontierKind::kRight), 1);
}

TEST_F(SectorTest, SmallStepsAreNotDiscontinuities) {
  SegmentWorld w;
  w.add(-1.0, -1.2, -1.0, 1.2);
  w.add(-1.0, -1.2, 1.0, -1.2);
  w.add(1.0, -1.2, 1.0, -0.7);
  w.add(1.0, -0.7, 1.5, -0.7);
  w.add(1.5, -0.7, 1.5, 1.2);  // a 0.5 m step in depth, below discontinuity_m = 1 m
  w.add(-1.0, 1.2, 1.5, 1.2);
  ASSERT_EQ(sectors->build(w.scan(urg, 0, 0, 0), params), Status::kOk);
  EXPECT_TRUE(sectors->frontiers().empty());
}

TEST_F(SectorTest, RangeCodesHaveTheirDocumentedMeaning) {
  LaserScan s = uniform_scan(urg, range_code::kNoReturn);
  // Sector 0 holds beams 0..21 of 682 with 32 sectors.
  s.range_mm[3] = range_code::kTooNear;
  ASSERT_EQ(sectors->build(s, params), Status::kOk);
  EXPECT_FALSE(sectors->obstacle_free(0));
  EXPECT_EQ(sectors->radius_mm(0), 0);
  s.range_mm[3] = range_code::kDropout;
  ASSERT_EQ(sectors->build(s, params), Status::kOk);
  EXPECT_FALSE(sectors->obstacle_free(0));  // unknown: not known to be free
  EXPECT_EQ(sectors->radius_mm(0), 3500);   // the other beams saw nothing within R_p
  for (int i = 0; i < 21; ++i) s.range_mm[i] = range_code::kDeflected;
  ASSERT_EQ(sectors->build(s, params), Status::kOk);
  EXPECT_EQ(sectors->radius_mm(0), 0);  // nothing seen at all
}

TEST_F(SectorTest, ClockwiseScanGivesTheSameSectorsAsCounterClockwise) {
  SegmentWorld w;
  w.add(1.0, -10, 1.0, -0.2);
  w.add(2.5, -0.2, 2.5, 10);
  w.add(-1.0, -10, -1.0, 10);
  LaserScan ccw = w.scan(urg, 0, 0, 0);
  LaserScan cw = ccw;
  cw.first_angle_rad = ccw.angle_of(ccw.beam_count - 1);
  cw.angle_step_rad = -ccw.angle_step_rad;
  for (int i = 0; i < ccw.beam_count; ++i) cw.range_mm[i] = ccw.range_mm[ccw.beam_count - 1 - i];
  SectorScan a, b;
  ASSERT_EQ(a.build(ccw, params), Status::kOk);
  ASSERT_EQ(b.build(cw, params), Status::kOk);
  EXPECT_NEAR(a.start_rad(), b.start_rad(), 1e-5);
  for (uint16_t s = 0; s < a.count(); ++s) EXPECT_EQ(a.radius_mm(s), b.radius_mm(s));
  EXPECT_EQ(a.frontiers().size(), b.frontiers().size());
}

TEST_F(SectorTest, RayClearDistanceKeepsTheClearanceFromEveryReturn) {
  // A thin post 1.5 m ahead, slightly left of the nose, and a wall 2 m to the right.
  SegmentWorld w;
  w.add(1.5, 0.05, 1.5, 0.08);
  w.add(-1, -2, 5, -2);
  const LaserScan scan = w.scan(urg, 0, 0, 0);
  ASSERT_EQ(sectors->build(scan, params), Status::kOk);
  const double rho = params.clearance_m, cap = params.perception_range_m - rho;
  // Distance from return i to the segment from the origin to d along angle a.
  auto gap = [&](int i, double a, double d) {
    const double r = scan.range_mm[i] * 1e-3, b = scan.angle_of(i);
    const double along = std::clamp(r * std::cos(b - a), 0.0, d);
    return std::hypot(r * std::cos(b) - along * std::cos(a), r * std::sin(b) - along * std::sin(a));
  };
  int shortened = 0;
  for (uint16_t s = 0; s < sectors->count(); ++s) {
    for (uint16_t j = 0; j < SectorScan::kRaysPerSector; ++j) {
      const double a = sectors->ray_angle(s, j), d = sectors->clear_mm(s, j) * 1e-3;
      EXPECT_LE(d, sectors->radius_mm(s) * 1e-3 + 1e-9);
      EXPECT_LE(d, cap + 1e-9);
      double nearest = 1e9, nearest_beyond = 1e9;
      for (int i = 0; i < scan.beam_count; ++i) {
        if (!LaserScan::is_return(scan.range_mm[i])) continue;
        nearest = std::min(nearest, gap(i, a, d));
        nearest_beyond = std::min(nearest_beyond, gap(i, a, d + 0.05));
      }
      EXPECT_GE(nearest, rho - 2e-3) << "sector " << s << " ray " << j;  // the disc fits all the way
      // ... and the distance is tight unless a radius or the cap bounds it.
      if (d + 0.05 < std::min(cap, sectors->radius_mm(s) * 1e-3)) {
        EXPECT_LT(nearest_beyond, rho) << "sector " << s << " ray " << j;
        shortened += sectors->obstacle_free(s) ? 1 : 0;
      }
    }
  }
  EXPECT_GE(shortened, 2);  // rays of obstacle-free sectors beside the post were shortened
}

TEST_F(SectorTest, RejectsEmptyScansAndBadParameters) {
  LaserScan empty = uniform_scan(urg, 1000);
  empty.beam_count = 0;
  EXPECT_EQ(sectors->build(empty, params), Status::kInvalidArgument);
  EXPECT_EQ(sectors->count(), 0);
  LaserScan nan_angle = uniform_scan(urg, 1000);
  nan_angle.angle_step_rad = NAN;
  EXPECT_EQ(sectors->build(nan_angle, params), Status::kInvalidArgument);
  SrtParams bad;
  bad.sector_count = kMaxSectors + 1;
  EXPECT_EQ(sectors->build(uniform_scan(urg, 1000), bad), Status::kInvalidArgument);
  // Fewer beams than sectors: one beam per sector.
  LaserScan few = uniform_scan(urg, range_code::kNoReturn);
  few.beam_count = 5;
  ASSERT_EQ(sectors->build(few, params), Status::kOk);
  EXPECT_EQ(sectors->count(), 5);
}


TEST_F(SectorTest, SlicedBuildEqualsTheOneCallBuild) {
  SegmentWorld w;
  w.add_box(-2.0, -1.5, 3.0, 1.2);
  w.add(0.8, 1.2, 0.8, 0.7);  // a jamb near the vehicle
  LaserScan ccw = w.scan(urg, 0.1, 0.0, 0.5);
  LaserScan cw = ccw;  // the same scan taken clockwise
  cw.first_angle_rad = ccw.angle_of(ccw.beam_count - 1);
  cw.angle_step_rad = -ccw.angle_step_rad;
  for (int i = 0; i < ccw.beam_count; ++i) cw.range_mm[i] = ccw.range_mm[ccw.beam_count - 1 - i];
  for (const LaserScan* scan : {&ccw, &cw}) {
    auto whole = std::make_unique<SectorScan>();
    ASSERT_EQ(whole->build(*scan, params), Status::kOk);
    for (uint32_t budget : {1u, 7u, 500u}) {
      SCOPED_TRACE(::testing::Message() << "budget " << budget << (scan == &cw ? " clockwise" : ""));
      auto sliced = std::make_unique<SectorScan>();
      for (int pass = 0; pass < 2; ++pass) {  // the second pass reuses the direction tables
        ASSERT_EQ(sliced->begin(*scan, params), Status::kOk);
        int calls = 0;
        while (!sliced->ready() && calls < 100000) {
          EXPECT_GE(sliced->advance(*scan, budget), 1u);  // every call makes progress
          ++calls;
        }
        ASSERT_TRUE(sliced->ready());
        EXPECT_GT(calls, 1);
        ASSERT_EQ(sliced->count(), whole->count());
        for (uint16_t s = 0; s < whole->count(); ++s) {
          EXPECT_EQ(sliced->radius_mm(s), whole->radius_mm(s));
          EXPECT_EQ(sliced->obstacle_free(s), whole->obstacle_free(s));
          for (uint16_t j = 0; j < SectorScan::kRaysPerSector; ++j)
            EXPECT_EQ(sliced->clear_mm(s, j), whole->clear_mm(s, j)) << "sector " << s << " ray " << j;
        }
        ASSERT_EQ(sliced->frontiers().size(), whole->frontiers().size());
        for (std::size_t i = 0; i < whole->frontiers().size(); ++i) {
          EXPECT_EQ(sliced->frontiers()[i].sector, whole->frontiers()[i].sector);
          EXPECT_EQ(sliced->frontiers()[i].kind, whole->frontiers()[i].kind);
          EXPECT_EQ(sliced->frontiers()[i].range_m, whole->frontiers()[i].range_m);
        }
      }
    }
  }
}

}  // namespace
}  // namespace kestrel::exploration
