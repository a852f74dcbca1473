#include <gtest/gtest.h>

#include <memory>
#include <random>

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
  explicit Fixture(float res) {
    p.resolution_m = res;
    p.sigma_m = 2 * res;
    local = std::make_unique<LocalMap>(p, *a, *b);
    auto key = std::make_unique<KeyScan>();
    key->points = test::to_points(test::cast_scan({0, 0, 0}, test::room()));
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

TEST(CorrelativeSearch, RejectsOversizedWindows) {
  Fixture f(0.02f);
  const auto pts = test::to_points(test::cast_scan({0, 0, 0}, test::room(), 361));
  const LikelihoodMap* m = f.local->acquire();
  EXPECT_EQ(f.search->setup(pts, {0, 0, 0}, *m, kMaxWindowCells + 1, 1, 0.01f), Status::kInvalidArgument);
  EXPECT_EQ(f.search->setup(pts, {0, 0, 0}, *m, 1, kMaxThetaSteps + 1, 0.01f), Status::kInvalidArgument);
  f.local->release();
}

}  // namespace
}  // namespace kestrel::scan_matching
