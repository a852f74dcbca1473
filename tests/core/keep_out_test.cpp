// An operator's keep-out box (keep_out.hpp): valid corners, and the segment test the explorer
// and the flight home's shortcut keep out with.
#include "kestrel/core/keep_out.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace kestrel {
namespace {

// iarc-arena's window as the README's sweeps give it: x 2..5, y 8.9..9.1.
constexpr KeepOut kWindow{2.0f, 8.9f, 5.0f, 9.1f};

TEST(KeepOut, ValidCornersAreFiniteAndInOrder) {
  EXPECT_TRUE(kWindow.valid());
  EXPECT_TRUE((KeepOut{1, 1, 1, 1}).valid());  // a point
  EXPECT_FALSE((KeepOut{5, 8.9f, 2, 9.1f}).valid());
  EXPECT_FALSE((KeepOut{2, 9.1f, 5, 8.9f}).valid());
  EXPECT_FALSE((KeepOut{NAN, 8.9f, 5, 9.1f}).valid());
  EXPECT_FALSE((KeepOut{2, 8.9f, INFINITY, 9.1f}).valid());
}

TEST(KeepOut, ASegmentCrossesTheBoxGrownByTheClearance) {
  // Straight through the glass, and through its corner.
  EXPECT_TRUE(kWindow.crossed_by({3, 8}, {3, 10}, 0.0f));
  EXPECT_TRUE(kWindow.crossed_by({1.5f, 8.5f}, {2.5f, 9.5f}, 0.0f));
  // Along the hallway 0.5 m south of it: clear, but not of a box grown by 0.45 m... nor 0.6 m.
  EXPECT_FALSE(kWindow.crossed_by({1, 8.4f}, {6, 8.4f}, 0.0f));
  EXPECT_FALSE(kWindow.crossed_by({1, 8.4f}, {6, 8.4f}, 0.45f));
  EXPECT_TRUE(kWindow.crossed_by({1, 8.4f}, {6, 8.4f}, 0.6f));
  // Ending short of it, starting inside it, and a segment that is a point.
  EXPECT_FALSE(kWindow.crossed_by({3, 7}, {3, 8.8f}, 0.0f));
  EXPECT_TRUE(kWindow.crossed_by({3, 9}, {3, 7}, 0.0f));
  EXPECT_TRUE(kWindow.crossed_by({3, 9}, {3, 9}, 0.0f));
  EXPECT_FALSE(kWindow.crossed_by({3, 7}, {3, 7}, 0.0f));
  // Parallel to an axis, beside the box.
  EXPECT_FALSE(kWindow.crossed_by({5.2f, 8}, {5.2f, 10}, 0.0f));
  EXPECT_TRUE(kWindow.crossed_by({5.2f, 8}, {5.2f, 10}, 0.3f));
  // A non-finite end crosses nothing (the callers refuse such points first).
  EXPECT_FALSE(kWindow.crossed_by({NAN, 8}, {3, 10}, 0.0f));
}

// A strip is lengthened along its long side only; a box that is no strip, and a margin that is
// zero, negative or NaN, leave the box as it is.
TEST(KeepOut, AStripIsLengthenedAlongItsWallOnly) {
  const KeepOut along_x = kWindow.lengthened(2.0f);
  EXPECT_FLOAT_EQ(along_x.x_min, 0.0f);
  EXPECT_FLOAT_EQ(along_x.x_max, 7.0f);
  EXPECT_FLOAT_EQ(along_x.y_min, 8.9f);
  EXPECT_FLOAT_EQ(along_x.y_max, 9.1f);
  const KeepOut along_y = KeepOut{4.9f, 1.0f, 5.1f, 4.0f}.lengthened(1.0f);
  EXPECT_FLOAT_EQ(along_y.y_min, 0.0f);
  EXPECT_FLOAT_EQ(along_y.y_max, 5.0f);
  EXPECT_FLOAT_EQ(along_y.x_min, 4.9f);
  // No wall to lengthen along: a pillar's 1 by 1.5 m, a post's 0.1 by 0.3 m, a point.
  const KeepOut pillar{1.0f, 1.0f, 2.0f, 2.5f}, post{1.0f, 1.0f, 1.1f, 1.3f}, point{1.0f, 1.0f, 1.0f, 1.0f};
  const auto expect_same = [](const KeepOut& k, const KeepOut& same) {
    EXPECT_EQ(k.x_min, same.x_min);
    EXPECT_EQ(k.x_max, same.x_max);
    EXPECT_EQ(k.y_min, same.y_min);
    EXPECT_EQ(k.y_max, same.y_max);
  };
  for (const KeepOut& box : {pillar, post, point}) expect_same(box.lengthened(2.0f), box);
  for (const float along : {0.0f, -1.0f, NAN}) expect_same(kWindow.lengthened(along), kWindow);
  // Seen 2 m beside the window, along its wall: through the lengthened box, not the box.
  EXPECT_FALSE(kWindow.crossed_by({6.5f, 8}, {6.5f, 10}, 0.0f));
  EXPECT_TRUE(along_x.crossed_by({6.5f, 8}, {6.5f, 10}, 0.0f));
}

}  // namespace
}  // namespace kestrel
