// What the explorer is told of a scan match (match_constraint.hpp): the flat axis turned from
// the matcher's frame into the filter's by the SLAM's correction, so that LookAcross faces
// across the axis the matcher could not measure, not across where it lay before the corrections.
#include "kestrel/autonomy/match_constraint.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kestrel/core/angle.hpp"
#include "kestrel/exploration/params.hpp"

namespace kestrel::autonomy {
namespace {

namespace mf = scan_matching::match_flag;
constexpr float kPi = std::numbers::pi_v<float>;

scan_matching::ScanMatch degenerate_along(float axis_rad) {
  scan_matching::ScanMatch m;
  m.measurement.flags = mf::kDegenerate;
  m.major_axis_rad = axis_rad;
  m.axis_ratio = 50;
  return m;
}

// An axis is a line: either sense is the same axis.
float axis_difference(float a, float b) {
  const float d = std::fabs(wrap_angle(a - b));
  return std::min(d, kPi - d);
}

// GIVEN a hallway along the matcher's x axis and a SLAM correction that turned the filter's
// frame by 0.5 rad, THEN the explorer is told the axis lies at 0.5 rad in its frame.
TEST(MatchConstraint, TheFlatAxisIsTurnedIntoTheFiltersFrame) {
  const exploration::MatchConstraint c =
      match_constraint_in_nav_frame(degenerate_along(0.0f), TimeUs::from_us(7), Pose2{2.0f, -1.0f, 0.5f});
  EXPECT_EQ(c.stamp, TimeUs::from_us(7));
  EXPECT_TRUE(c.degenerate);
  EXPECT_TRUE(c.usable);
  EXPECT_NEAR(c.flat_axis_rad, 0.5f, 1e-6f);
  // The correction's translation moves no axis.
  EXPECT_EQ(match_constraint_in_nav_frame(degenerate_along(0.3f), TimeUs{}, Pose2{5.0f, 5.0f, 0.0f}).flat_axis_rad, 0.3f);
}

TEST(MatchConstraint, TheTurnedAxisIsWrapped) {
  const exploration::MatchConstraint c =
      match_constraint_in_nav_frame(degenerate_along(3.0f), TimeUs{}, Pose2{0.0f, 0.0f, 0.5f});
  EXPECT_LE(std::fabs(c.flat_axis_rad), kPi);
  EXPECT_LT(axis_difference(c.flat_axis_rad, 3.5f), 1e-5f);
}

TEST(MatchConstraint, ALostMatchIsNotUsableAndAClearOneNotDegenerate) {
  scan_matching::ScanMatch lost = degenerate_along(0.0f);
  lost.measurement.flags |= mf::kLost;
  EXPECT_FALSE(match_constraint_in_nav_frame(lost, TimeUs{}, Pose2{}).usable);
  scan_matching::ScanMatch clear;
  const exploration::MatchConstraint c = match_constraint_in_nav_frame(clear, TimeUs{}, Pose2{});
  EXPECT_FALSE(c.degenerate);
  EXPECT_TRUE(c.usable);
}

// GIVEN the matcher's hallway axis along its x and the filter's frame turned by 1.0 rad, WHEN
// the spell of degenerate matches has lasted LookAcross's time, THEN the heading it commands is
// across the hallway in the filter's frame (at 1.0 +- pi/2): across the matcher's x, it would
// look along the hallway by 1.0 rad off (57 degrees) and see no more of it.
TEST(MatchConstraint, LookAcrossFacesAcrossTheAxisInTheFiltersFrame) {
  exploration::LookAcrossParams p;
  p.after_s = 0.5f;
  p.release_s = 1.0f;
  exploration::LookAcross look;
  look.configure(p);
  const Pose2 correction{0.0f, 0.0f, 1.0f};
  for (int i = 0; i <= 30; ++i) {
    look.note(match_constraint_in_nav_frame(degenerate_along(0.0f), TimeUs::from_us(25000 * i), correction));
  }
  ASSERT_TRUE(look.active());
  const float heading = look.heading(1.0f);  // the waypoint straight along the hallway
  EXPECT_NEAR(axis_difference(heading, 1.0f + kPi / 2), 0.0f, 1e-5f);
  EXPECT_GT(axis_difference(heading, kPi / 2), 0.9f);
}

}  // namespace
}  // namespace kestrel::autonomy
