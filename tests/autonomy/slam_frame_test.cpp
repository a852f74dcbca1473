// The SLAM's frame against the filter's, across home fixes applied to a real NavFilter: a pose
// the SLAM gives in the frame its map was drawn in must come back where the filter now puts the
// vehicle.
#include "kestrel/autonomy/slam_frame.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "kestrel/core/angle.hpp"
#include "kestrel/estimation/nav_filter.hpp"
#include "synthetic_flight.hpp"

namespace kestrel::autonomy {
namespace {

using test::make_flight;
using test::matched_params;
using test::StreamPlayer;
using test::SyntheticConfig;

Pose2 pose_of(const NavState& s) { return {s.position_m.x(), s.position_m.y(), s.heading_rad}; }

// Applies a fix that says the vehicle was `shift` * (its estimate) at the current time, and
// tells the frame.
void apply_fix(estimation::NavFilter& filter, SlamFrame& frame, const Pose2& shift) {
  const NavState now = filter.state();
  PoseMeasurement2 fix;
  fix.stamp = now.stamp;
  fix.pose = shift.compose(pose_of(now));
  const Pose2 before = filter.frame_correction();
  ASSERT_EQ(filter.apply_correction(fix), Status::kOk);
  frame.filter_moved(before, filter.frame_correction());
}

TEST(SlamFrame, RoundTrip) {
  SlamFrame f;
  f.filter_moved(Pose2{}, Pose2{0.4f, -1.2f, 0.3f});
  const Pose2 p{3.0f, 2.0f, -1.0f};
  const Pose2 back = f.to_slam(f.to_filter(p));
  EXPECT_NEAR(back.x, p.x, 1e-5f);
  EXPECT_NEAR(back.y, p.y, 1e-5f);
  EXPECT_NEAR(angle_diff(back.theta, p.theta), 0.0f, 1e-5f);
}

// GIVEN a flight whose filter takes two home fixes with rotation (the SLAM's map, drawn from the
// poses before them, does not move), WHEN the SLAM later reports the vehicle where the
// uncorrected trajectory has it (the truth, here), THEN to_filter() gives the filter's own
// estimate: a correction the SLAM makes after the fixes does not undo them. Composing the
// frames in the other order would put it decimetres off (checked, so the test can fail).
TEST(SlamFrame, FollowsTheFilterAcrossTwoFixes) {
  SyntheticConfig c;
  c.duration_s = 14.0;
  c.seed = 5;
  const auto fl = make_flight(c);
  auto filter = std::make_unique<estimation::NavFilter>(matched_params(c));
  StreamPlayer player(fl, Duration{});
  SlamFrame frame;
  Pose2 wrong;  // the frame composed the other way: frame * after * before^-1

  player.play_until(*filter, TimeUs::from_s(6.0));
  const Pose2 shift1{0.9f, -0.4f, 0.3f};
  Pose2 before = filter->frame_correction();
  apply_fix(*filter, frame, shift1);
  wrong = wrong.compose(filter->frame_correction()).compose(before.inverse());

  player.play_until(*filter, TimeUs::from_s(9.0));
  const Pose2 shift2{0.1f, 0.0f, -0.35f};
  before = filter->frame_correction();
  apply_fix(*filter, frame, shift2);
  wrong = wrong.compose(filter->frame_correction()).compose(before.inverse());

  player.play_until(*filter, TimeUs::from_s(14.0));
  const NavState end = filter->state();
  const std::size_t i = player.truth_index(end.stamp);
  const Pose2 slam_pose{fl.truth[i].position_m.x(), fl.truth[i].position_m.y(), fl.heading[i]};
  const Pose2 in_filter = frame.to_filter(slam_pose);
  EXPECT_NEAR(in_filter.x, end.position_m.x(), 0.03f);
  EXPECT_NEAR(in_filter.y, end.position_m.y(), 0.03f);
  EXPECT_NEAR(angle_diff(in_filter.theta, end.heading_rad), 0.0f, 0.01f);
  // ...and the estimate's pose goes into the SLAM's frame where the SLAM has the vehicle.
  const Pose2 prior = frame.to_slam(pose_of(end));
  EXPECT_NEAR(prior.x, slam_pose.x, 0.03f);
  EXPECT_NEAR(prior.y, slam_pose.y, 0.03f);

  const Pose2 off = wrong.compose(slam_pose);
  EXPECT_GT(std::hypot(off.x - end.position_m.x(), off.y - end.position_m.y()), 0.1f);
}

}  // namespace
}  // namespace kestrel::autonomy
