#include <gtest/gtest.h>

#include <memory>

#include "kestrel/scan_matching/contour_extractor.hpp"
#include "synthetic.hpp"

namespace kestrel::scan_matching {
namespace {

// GIVEN one straight wall WHEN contours are extracted THEN all its points form one polyline.
TEST(Contours, StraightWallIsOneContour) {
  const auto pts = test::to_points(test::cast_scan({0, 0, 0}, {{2, -5, 2, 5}}, 361, 3.14159f));
  auto ex = std::make_unique<ContourExtractor>(Params{});
  auto c = std::make_unique<Contours>();
  ex->extract(pts, *c);
  ASSERT_GT(pts.count, 100);
  EXPECT_EQ(c->contour_count, 1);
  EXPECT_EQ(c->segment_count, pts.count - 1);
}

// A corner joins into one contour; a gap (a doorway) splits the wall in two.
TEST(Contours, CornerJoinsAndGapSplits) {
  auto ex = std::make_unique<ContourExtractor>(Params{});
  auto c = std::make_unique<Contours>();
  const auto corner = test::to_points(test::cast_scan({0, 0, 0}, {{2, -2, 2, 2}, {2, 2, -2, 2}}, 361, 3.14159f));
  ex->extract(corner, *c);
  EXPECT_EQ(c->contour_count, 1);
  const auto gap = test::to_points(test::cast_scan({0, 0, 0}, {{2, -3, 2, -0.5f}, {2, 0.5f, 2, 3}}, 361, 3.14159f));
  ex->extract(gap, *c);
  EXPECT_EQ(c->contour_count, 2);
}

// A depth step (a box in front of a wall) is not joined into a surface.
TEST(Contours, DepthDiscontinuityIsNotJoined) {
  auto ex = std::make_unique<ContourExtractor>(Params{});
  auto c = std::make_unique<Contours>();
  const auto pts = test::to_points(test::cast_scan({0, 0, 0}, {{3, -3, 3, 3}, {1, -0.3f, 1, 0.3f}}, 361, 3.14159f));
  ex->extract(pts, *c);
  EXPECT_EQ(c->contour_count, 3);  // wall left of the box, the box, wall right of it
}

// A railing (every third beam passes through to the wall behind) stays one contour, and the
// wall seen through it forms its own contours instead of zig-zagging with the railing.
TEST(Contours, RailingStaysTogether) {
  auto ex = std::make_unique<ContourExtractor>(Params{});
  auto c = std::make_unique<Contours>();
  const auto pts = test::to_points(test::cast_scan({0, 0, 0}, {{1.5f, -1, 1.5f, 1, 3}, {3, -3, 3, 3}}, 361, 3.14159f));
  ex->extract(pts, *c);
  uint16_t rail_root = 0xFFFF;
  int rail_points = 0, mixed = 0;
  for (uint16_t i = 0; i < pts.count; ++i) {
    if (pts.x[i] < 2.0f) {
      ++rail_points;
      if (rail_root == 0xFFFF) rail_root = c->contour[i];
      if (c->contour[i] != rail_root) ++mixed;
    }
  }
  EXPECT_GT(rail_points, 30);
  EXPECT_EQ(mixed, 0);
  for (uint16_t k = 0; k < c->segment_count; ++k) {
    const bool a_rail = pts.x[c->seg_a[k]] < 2.0f, b_rail = pts.x[c->seg_b[k]] < 2.0f;
    EXPECT_EQ(a_rail, b_rail) << "a segment joins the railing to the wall behind";
  }
}

TEST(Contours, EmptyAndSinglePoint) {
  auto ex = std::make_unique<ContourExtractor>(Params{});
  auto c = std::make_unique<Contours>();
  ScanPoints pts;
  ex->extract(pts, *c);
  EXPECT_EQ(c->contour_count, 0);
  pts.count = 1;
  pts.x[0] = 1;
  pts.range_mm[0] = 1000;
  ex->extract(pts, *c);
  EXPECT_EQ(c->contour_count, 1);
  EXPECT_EQ(c->segment_count, 0);
}

}  // namespace
}  // namespace kestrel::scan_matching
