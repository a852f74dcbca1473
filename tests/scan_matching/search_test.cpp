#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "kestrel/scan_matching/correlative_search.hpp"
#include "kestrel/scan_matching/local_map.hpp"
#include "synthetic.hpp"

namespace kestrel::scan_matching {
namespace {

using Map = LikelihoodMapStorage<576, 4 * kMaxBeams>;

struct Fixture {
  Params p;
  std::unique_ptr<Map> a = std::make_unique<Map>(), b = std::make_unique<Map>();
  std::unique_ptr<LocalMap> local;
  std::unique_ptr<CorrelativeSearch> search = std::make_unique<CorrelativeSearch>();
  explicit Fixture(float res, const std::vector<test::Wall>& walls = test::room()) {
    p.resolution_m = res;
    p.sigma_m = 2 * res;
    local = std::make_unique<LocalMap>(p, *a, *b);
    auto key = std::make_unique<KeyScan>();
    key->points = test::to_points(test::cast_scan({0, 0, 0}, walls));
    EXPECT_TRUE(local->submit(*key));
    EXPECT_EQ(local->rebuild(), Status::kOk);
  }
};

// GIVEN a scan taken at a pose exactly on the search grid WHEN searched around the origin
// THEN both modes return that grid pose, at every map resolution.
TEST(CorrelativeSearch, FindsKnownTransformExactlyAtEveryResolution) {
  for (float res : {0.0075f, 0.015f, 0.03f, 0.06f}) {
    Fixture f(res);
    const float step = res / 2.9f;  // the rotation a 3 m return resolves at this resolution
    const int kx = 5, ky = -3, kk = 4;
    const auto pts = test::to_points(test::cast_scan({kx * res, ky * res, kk * step}, test::room()));
    const LikelihoodMap* m = f.local->acquire();
    ASSERT_NE(m, nullptr);
    ASSERT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 10, 8, step), Status::kOk);
    const GridPose e = f.search->exhaustive();
    const GridPose bb = f.search->branch_and_bound();
    f.local->release();
    EXPECT_EQ(e.k, kk) << res;
    EXPECT_EQ(e.tx, kx) << res;
    EXPECT_EQ(e.ty, ky) << res;
    EXPECT_EQ(bb.k, e.k);
    EXPECT_EQ(bb.tx, e.tx);
    EXPECT_EQ(bb.ty, e.ty);
    EXPECT_EQ(bb.score, e.score);
  }
}

// Branch and bound returns exactly the exhaustive optimum (score and pose) on random cases,
// and visits fewer poses.
TEST(CorrelativeSearch, BranchAndBoundEqualsExhaustiveOnRandomCases) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(-1, 1);
  Fixture f(0.02f);
  for (int trial = 0; trial < 12; ++trial) {
    const Pose2 truth{0.3f * u(rng), 0.3f * u(rng), 0.15f * u(rng)};
    const auto pts = test::to_points(test::cast_scan(truth, test::room(), 361));
    const Pose2 centre{truth.x + 0.1f * u(rng), truth.y + 0.1f * u(rng), truth.theta + 0.03f * u(rng)};
    const LikelihoodMap* m = f.local->acquire();
    const int w = 5 + trial * 4;
    ASSERT_EQ(f.search->setup(pts, centre, *m, w, 15, 0.0044f), Status::kOk);
    const GridPose e = f.search->exhaustive();
    const uint64_t exhaustive_poses = f.search->nodes_visited();
    ASSERT_EQ(f.search->setup(pts, centre, *m, w, 15, 0.0044f), Status::kOk);
    const GridPose bb = f.search->branch_and_bound();
    f.local->release();
    EXPECT_EQ(bb.score, e.score) << trial;
    EXPECT_EQ(bb.k, e.k) << trial;
    EXPECT_EQ(bb.tx, e.tx) << trial;
    EXPECT_EQ(bb.ty, e.ty) << trial;
    if (w >= 20) {
      EXPECT_LT(f.search->nodes_visited(), exhaustive_poses) << trial;
    }
  }
}

// Every block's bound (run-length sums over the max-pooled levels) is at least the exact score
// of every translation in it, at every level.
TEST(CorrelativeSearch, BlockBoundsHoldEveryScoreInTheBlock) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  Fixture f(0.02f);
  const int half = 20;
  for (int trial = 0; trial < 4; ++trial) {
    const auto pts = test::to_points(test::cast_scan({0.3f * u(rng), 0.3f * u(rng), 0.1f * u(rng)}, test::room(), 361));
    const LikelihoodMap* m = f.local->acquire();
    ASSERT_EQ(f.search->setup(pts, {0, 0, 0}, *m, half, 4, 0.0044f), Status::kOk);
    for (int level = 1; level <= 5; ++level) {
      const int s = 1 << level;
      for (int by = -half; by <= half; by += s) {
        for (int bx = -half; bx <= half; bx += s) {
          const int k = trial - 2;
          const int32_t b = f.search->block_bound(k, level, bx, by);
          for (int ty = by; ty < by + s && ty <= half; ++ty) {
            for (int tx = bx; tx < bx + s && tx <= half; ++tx) {
              ASSERT_GE(b, f.search->score(k, tx, ty)) << level << " " << tx << " " << ty;
            }
          }
        }
      }
    }
    f.local->release();
  }
}

// The four children's bounds taken in one pass are the four bounds taken one by one, at every
// level including the exact scores of level 0, also where blocks reach past the map's edge.
TEST(CorrelativeSearch, ChildBoundsInOnePassEqualSingleBounds) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  Fixture f(0.02f);
  const int half = 40;
  for (int trial = 0; trial < 4; ++trial) {
    const auto pts = test::to_points(test::cast_scan({0.3f * u(rng), 0.3f * u(rng), 0.1f * u(rng)}, test::room(), 361));
    const LikelihoodMap* m = f.local->acquire();
    // Trial 3 sits near the map's corner: many blocks are partly outside the map.
    const Pose2 centre = trial == 3 ? Pose2{-4.5f, 4.5f, 0.3f} : Pose2{0, 0, 0};
    ASSERT_EQ(f.search->setup(pts, centre, *m, half, 4, 0.0044f), Status::kOk);
    for (int level = 0; level <= 5; ++level) {
      const int s = 1 << level;
      for (int by = -half; by <= half; by += 2 * s) {
        for (int bx = -half; bx <= half; bx += 2 * s) {
          const int k = trial - 2;
          const auto four = f.search->child_block_bounds(k, level, bx, by);
          EXPECT_EQ(four[0], f.search->block_bound(k, level, bx, by)) << level;
          EXPECT_EQ(four[1], f.search->block_bound(k, level, bx + s, by)) << level;
          EXPECT_EQ(four[2], f.search->block_bound(k, level, bx, by + s)) << level;
          EXPECT_EQ(four[3], f.search->block_bound(k, level, bx + s, by + s)) << level;
        }
      }
    }
    f.local->release();
  }
}

// Image addition (SIMD kernels for windows inside the map, cell-by-cell clipping at its edge)
// gives every translation's exact score, for every slice width the search uses.
TEST(CorrelativeSearch, SliceEqualsEveryPoseScore) {
  // A corridor longer than the 11.5 m map: its walls run to the map's edges, where the
  // windows of the points near the edge are clipped.
  const std::vector<test::Wall> corridor{{-20, -1, 20, -1}, {-20, 1.3f, 20, 1.3f}};
  Fixture f(0.02f, corridor);
  const auto pts = test::to_points(test::cast_scan({0.05f, -0.03f, 0.02f}, corridor, 361));
  const LikelihoodMap* m = f.local->acquire();
  ASSERT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 30, 3, 0.0044f), Status::kOk);
  for (const int half : {0, 2, 3, 7, 12, 20}) {
    for (const int k : {-3, 1}) {
      const int cx = 5 - half, cy = half - 4;
      const uint16_t* sl = f.search->slice(k, cx, cy, half);
      std::vector<uint16_t> got(sl, sl + (2 * half + 1) * (2 * half + 1));
      for (int uy = 0; uy <= 2 * half; ++uy) {
        for (int ux = 0; ux <= 2 * half; ++ux) {
          ASSERT_EQ(got[static_cast<std::size_t>(uy * (2 * half + 1) + ux)],
                    f.search->score(k, cx - half + ux, cy - half + uy))
              << half << " " << ux << " " << uy;
        }
      }
    }
  }
  f.local->release();
}

// The best translation outside a disc, by branch and bound, is the maximum of the slice over
// the translations outside it, on random scans, windows, rotations, centres and radii; a disc
// that covers the whole window leaves nothing.
TEST(CorrelativeSearch, BestOutsideADiscEqualsTheSlicesMaximumThere) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1, 1);
  Fixture f(0.02f);
  for (int trial = 0; trial < 16; ++trial) {
    const Pose2 truth{0.3f * u(rng), 0.3f * u(rng), 0.15f * u(rng)};
    const auto pts = test::to_points(test::cast_scan(truth, test::room(), 361));
    const LikelihoodMap* m = f.local->acquire();
    const int w = 5 + trial * 3;  // up to 50 cells, within the slice's 64
    ASSERT_EQ(f.search->setup(pts, {0, 0, 0}, *m, w, 6, 0.0044f), Status::kOk);
    std::uniform_int_distribution<int> cell(-w, w);
    const int k = trial % 13 - 6, cx = cell(rng), cy = cell(rng);
    const int radius = (trial % 4 == 3) ? 0 : 1 + (trial * 7) % (w + 1);
    const uint16_t* sl = f.search->slice(k, 0, 0, w);
    int32_t expect = -1;
    for (int y = -w; y <= w; ++y) {
      for (int x = -w; x <= w; ++x) {
        if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= radius * radius) continue;
        expect = std::max<int32_t>(expect, sl[static_cast<std::size_t>((y + w) * (2 * w + 1) + (x + w))]);
      }
    }
    const GridPose got = f.search->best_outside(k, cx, cy, radius);
    EXPECT_EQ(got.score, expect) << trial;
    EXPECT_EQ(got.k, k);
    EXPECT_GT((got.tx - cx) * (got.tx - cx) + (got.ty - cy) * (got.ty - cy), radius * radius) << trial;
    EXPECT_EQ(got.score, f.search->score(k, got.tx, got.ty)) << trial;
    EXPECT_EQ(f.search->best_outside(k, 0, 0, 2 * w).score, -1) << trial;  // the disc holds the window
    f.local->release();
  }
}

// Along a corridor whose walls run past the map's edges the score must stay flat: if points
// crossing the edge counted for some translations and not others, shifting back towards the
// key scan would bring more wall points into the map at the near edge than it loses at the
// far one, and the match would be dragged back. (6 m wide, so that the key scan's contours
// stay joined out to the map's edge: far along a narrow corridor, grazing returns are too
// sparse to join, and the dotted walls are not flat either.)
TEST(CorrelativeSearch, CorridorPastTheMapEdgeIsNotDraggedTowardsTheKeyScan) {
  const std::vector<test::Wall> corridor{{-40, -3, 40, -3}, {-40, 3, 40, 3}};
  Fixture f(0.02f, corridor);
  const LikelihoodMap* m = f.local->acquire();
  for (const float ahead : {1.5f, 2.5f}) {
    const auto pts = test::to_points(test::cast_scan({ahead, 0, 0}, corridor, 1081));
    ASSERT_EQ(f.search->setup(pts, {ahead, 0, 0}, *m, 30, 4, 0.0044f, 12), Status::kOk);
    // 0.6 m back towards the key scan and 0.6 m on: within 0.5 % (the contours' rendering);
    // with the points crossing the edge counted, back scored 3.5-5 % higher and on 4-6 % lower.
    const int32_t here = f.search->score(0, 0, 0), back = f.search->score(0, -30, 0), on = f.search->score(0, 30, 0);
    EXPECT_LE(std::abs(back - here), here / 200) << ahead;
    EXPECT_LE(std::abs(on - here), here / 200) << ahead;
  }
  f.local->release();
}

// Only the points inside a key scan's disc under every translation are scored: the disc less
// the window and slice reach. A disc that holds every point changes nothing; a bad centre is
// refused, and a disc smaller than the search's reach scores nothing.
TEST(CorrelativeSearch, OnlyPointsWithinAKeyScansReachAreScored) {
  Fixture f(0.02f);
  const auto pts = test::to_points(test::cast_scan({0, 0, 0}, test::room(), 361));
  const LikelihoodMap* m = f.local->acquire();
  ASSERT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 10, 2, 0.0044f, 5), Status::kOk);
  const int all = f.search->scored_points(0);
  const GridPose plain = f.search->branch_and_bound();
  SeenDiscs seen;
  seen.count = 1;
  seen.radius_m = 10.0f;  // the whole 6 x 4 m room
  ASSERT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 10, 2, 0.0044f, 5, 0, &seen), Status::kOk);
  EXPECT_EQ(f.search->scored_points(0), all);
  const GridPose same = f.search->branch_and_bound();
  EXPECT_EQ(same.score, plain.score);
  EXPECT_EQ(same.tx, plain.tx);
  EXPECT_EQ(same.ty, plain.ty);
  // A disc of 2.3 m around (0, 0), less the 15 cells (0.3 m) of reach: the points within 2 m.
  seen.radius_m = 2.3f;
  ASSERT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 10, 2, 0.0044f, 5, 0, &seen), Status::kOk);
  int within = 0;
  for (uint16_t i = 0; i < pts.count; ++i) within += std::hypot(pts.x[i], pts.y[i]) <= 2.0f;
  EXPECT_NEAR(f.search->scored_points(0), within, 3);  // cell rounding at the rim
  EXPECT_LT(within, all);
  // The second disc, further on, adds what lies within its reach.
  seen.count = 2;
  seen.x[1] = 2.5f;
  ASSERT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 10, 2, 0.0044f, 5, 0, &seen), Status::kOk);
  EXPECT_GT(f.search->scored_points(0), within);
  seen.radius_m = 0.2f;  // inside the search's own reach
  ASSERT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 10, 2, 0.0044f, 5, 0, &seen), Status::kOk);
  EXPECT_EQ(f.search->scored_points(0), 0);
  seen.x[0] = NAN;
  EXPECT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 10, 2, 0.0044f, 5, 0, &seen), Status::kInvalidArgument);
  f.local->release();
}

// Points that fall outside the map under every translation are dropped from the search: the
// result is the one without them.
TEST(CorrelativeSearch, PointsFarOutsideTheMapChangeNothing) {
  Fixture f(0.02f);
  const auto pts = test::to_points(test::cast_scan({0.05f, -0.03f, 0.02f}, test::room(), 361));
  auto more = pts;
  for (int i = 0; i < 50 && more.count < kMaxPoints; ++i) {
    more.x[more.count] = 40.0f + static_cast<float>(i);  // 40 m away: far outside a 11.5 m map
    more.y[more.count] = -30.0f;
    ++more.count;
  }
  const LikelihoodMap* m = f.local->acquire();
  ASSERT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 8, 8, 0.0044f), Status::kOk);
  const GridPose a = f.search->branch_and_bound();
  ASSERT_EQ(f.search->setup(more, {0, 0, 0}, *m, 8, 8, 0.0044f), Status::kOk);
  const GridPose b = f.search->branch_and_bound();
  const GridPose e = f.search->exhaustive();
  f.local->release();
  EXPECT_EQ(a.score, b.score);
  EXPECT_EQ(a.k, b.k);
  EXPECT_EQ(a.tx, b.tx);
  EXPECT_EQ(a.ty, b.ty);
  EXPECT_EQ(e.score, b.score);
}

// Points the int16 transform cannot hold, and non-finite points, are refused by setup().
TEST(CorrelativeSearch, RejectsPointsItCannotHold) {
  Fixture f(0.02f);
  auto pts = test::to_points(test::cast_scan({0, 0, 0}, test::room(), 361));
  const LikelihoodMap* m = f.local->acquire();
  EXPECT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 8, 4, 0.0044f), Status::kOk);
  EXPECT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 8, 4, 0.0044f, 0, 700.0f), Status::kInvalidArgument);  // 35,000 cells
  pts.x[3] = 700.0f;
  EXPECT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 8, 4, 0.0044f), Status::kInvalidArgument);
  pts.x[3] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 8, 4, 0.0044f), Status::kInvalidArgument);
  f.local->release();
}

TEST(CorrelativeSearch, RejectsOversizedWindows) {
  Fixture f(0.02f);
  const auto pts = test::to_points(test::cast_scan({0, 0, 0}, test::room(), 361));
  const LikelihoodMap* m = f.local->acquire();
  EXPECT_EQ(f.search->setup(pts, {0, 0, 0}, *m, kMaxWindowCells + 1, 1, 0.01f), Status::kInvalidArgument);
  EXPECT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 1, kMaxThetaSteps + 1, 0.01f), Status::kInvalidArgument);
  // A centre so far from the map that the fixed-point transform could not hold it.
  EXPECT_EQ(f.search->setup(pts, {1e6f, 0, 0}, *m, 1, 1, 0.01f), Status::kInvalidArgument);
  f.local->release();
}

}  // namespace
}  // namespace kestrel::scan_matching
