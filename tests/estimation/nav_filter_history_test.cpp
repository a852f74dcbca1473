// The state history: late measurements equal in-order ones, seconds-old SLAM corrections move
// the present state, and the history's limits are defined (paper 000 sections 5.2 and 5.3).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>

#include "kestrel/estimation/nav_filter.hpp"
#include "synthetic_flight.hpp"

namespace kestrel::estimation {
namespace {

using test::make_flight;
using test::matched_params;
using test::StreamPlayer;
using test::SyntheticConfig;

Pose2 pose_of(const NavState& s) { return {s.position_m.x(), s.position_m.y(), s.heading_rad}; }

// A SLAM correction saying the vehicle was off by `d` (new = d * old) when the filter stood at `then`.
PoseMeasurement2 correction_of(const NavState& then, const Pose2& d) {
  PoseMeasurement2 corr;
  corr.stamp = then.stamp;
  corr.pose = d.compose(pose_of(then));
  return corr;
}

void expect_same_state(const NavFilter& a, const NavFilter& b, float tol) {
  for (int ax = 0; ax < 3; ++ax) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(a.axis(ax).x(i), b.axis(ax).x(i), tol) << "axis " << ax << " state " << i;
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(a.axis(ax).P(i, j), b.axis(ax).P(i, j), tol * 1e-2f);
    }
  }
  EXPECT_NEAR(a.heading().x(0), b.heading().x(0), tol);
  EXPECT_NEAR(a.heading().x(1), b.heading().x(1), tol);
}

// GIVEN the same flight delivered with measurements on time and 150 ms late,
// THEN both filters end in the same state (the late one re-propagated its history).
TEST(NavFilterHistory, DelayedMeasurementsGiveTheInOrderResult) {
  SyntheticConfig c;
  c.duration_s = 10.0;
  c.seed = 21;
  const auto fl = make_flight(c);
  auto in_order = std::make_unique<NavFilter>(matched_params(c));
  auto late = std::make_unique<NavFilter>(matched_params(c));
  StreamPlayer p1(fl, Duration{});
  StreamPlayer p2(fl, Duration::from_ms(150));
  p1.play_until(*in_order, TimeUs::from_s(10.0));
  p2.play_until(*late, TimeUs::from_s(10.2));  // all late ones delivered
  EXPECT_EQ(in_order->counters().replays, 0u);
  EXPECT_GT(late->counters().replays, 300u);
  EXPECT_EQ(in_order->counters().pose_updates, late->counters().pose_updates);
  EXPECT_EQ(in_order->counters().altitude_updates, late->counters().altitude_updates);
  expect_same_state(*in_order, *late, 1e-5f);
}

ImuSample level_sample(int64_t ms) {
  ImuSample s;
  s.stamp = TimeUs::from_us(ms * 1000);
  s.accel_mps2 = {0.0f, 0.0f, 9.81f};
  return s;
}

PoseMeasurement2 pose_at(int64_t ms) {
  PoseMeasurement2 m;
  m.stamp = TimeUs::from_us(ms * 1000);
  m.pose = {1.0f, 2.0f, 0.5f};
  m.covariance = Eigen::Vector3f(1e-4f, 1e-4f, 1e-4f).asDiagonal();
  return m;
}

// GIVEN IMU samples taken in before the first pose, all later than its stamp and reaching more
// than max_imu_gap_s (0.1 s) past it (the laser's first beam came first, and its scan arrived
// late: paper 000's 0.2 s delay), THEN the filter keeps them, the pose in front: no gap, no
// history restart, and the next pose is taken. Before, they were dropped, the next sample was a
// 0.2 s step from the pose, taken for a gap that restarted the history, and the next poses were
// refused as older than it (kestrel-sim's delay study: one gap, four poses refused).
TEST(NavFilterHistory, FirstPoseOlderThanEveryStoredSampleKeepsThem) {
  auto f = std::make_unique<NavFilter>(EkfParams{});
  for (int64_t ms = 10; ms <= 200; ms += 5) EXPECT_EQ(f->predict(level_sample(ms)), Status::kNoData);
  ASSERT_EQ(f->update_pose(pose_at(0)), Status::kOk);
  EXPECT_EQ(f->history_span(), Duration::from_ms(200));  // from the pose to the newest sample
  for (int64_t ms = 205; ms <= 300; ms += 5) EXPECT_EQ(f->predict(level_sample(ms)), Status::kOk) << ms;
  EXPECT_EQ(f->update_pose(pose_at(100)), Status::kOk);
  EXPECT_EQ(f->counters().imu_gaps, 0u);
  EXPECT_EQ(f->counters().meas_too_old, 0u);
  EXPECT_EQ(f->counters().pose_updates, 2u);
  EXPECT_NEAR(f->state().position_m.x(), 1.0f, 1e-3f);
  EXPECT_NEAR(f->state().position_m.y(), 2.0f, 1e-3f);
  EXPECT_EQ(f->state().stamp, TimeUs::from_us(300'000));
}

// GIVEN a first pose older than the IMU's first sample by more than a gap, THEN nothing can
// carry the state across: it is counted as a gap and the filter starts at the first sample,
// keeping every stored one, and the next pose is taken.
TEST(NavFilterHistory, FirstPoseOlderThanTheImuByMoreThanAGapStartsAtTheFirstSample) {
  auto f = std::make_unique<NavFilter>(EkfParams{});
  for (int64_t ms = 300; ms <= 400; ms += 5) EXPECT_EQ(f->predict(level_sample(ms)), Status::kNoData);
  ASSERT_EQ(f->update_pose(pose_at(0)), Status::kOk);
  EXPECT_EQ(f->counters().imu_gaps, 1u);
  EXPECT_EQ(f->history_span(), Duration::from_ms(100));
  EXPECT_EQ(f->predict(level_sample(405)), Status::kOk);
  EXPECT_EQ(f->update_pose(pose_at(350)), Status::kOk);
  EXPECT_EQ(f->counters().imu_gaps, 1u);
  EXPECT_EQ(f->counters().meas_too_old, 0u);
  EXPECT_NEAR(f->state().position_m.x(), 1.0f, 1e-3f);
}

// GIVEN measurements delivered out of order (a later one before an earlier one),
// THEN the result is the same as in order.
TEST(NavFilterHistory, OutOfOrderArrivalGivesTheInOrderResult) {
  SyntheticConfig c;
  c.duration_s = 3.0;
  c.seed = 5;
  const auto fl = make_flight(c);
  auto a = std::make_unique<NavFilter>(matched_params(c));
  auto b = std::make_unique<NavFilter>(matched_params(c));
  std::size_t ip = 0;
  for (const ImuSample& s : fl.imu) {
    (void)a->predict(s);
    (void)b->predict(s);
    while (ip + 1 < fl.poses.size() && fl.poses[ip + 1].stamp + Duration::from_ms(40) <= s.stamp) {
      // a gets poses ip, ip+1 in order; b gets ip+1 first (after the initialising pair).
      EXPECT_EQ(a->update_pose(fl.poses[ip]), Status::kOk);
      EXPECT_EQ(a->update_pose(fl.poses[ip + 1]), Status::kOk);
      if (ip == 0) {
        EXPECT_EQ(b->update_pose(fl.poses[ip]), Status::kOk);
        EXPECT_EQ(b->update_pose(fl.poses[ip + 1]), Status::kOk);
      } else {
        EXPECT_EQ(b->update_pose(fl.poses[ip + 1]), Status::kOk);
        EXPECT_EQ(b->update_pose(fl.poses[ip]), Status::kOk);
      }
      ip += 2;
    }
  }
  EXPECT_GT(ip, 100u);
  expect_same_state(*a, *b, 1e-5f);
}

// GIVEN a flight, WHEN a SLAM correction arrives 2 s after the time it refers to, saying the
// vehicle was 0.5 m, -0.3 m and 0.1 rad off then, THEN the present state moves by that rigid
// shift (position, heading and velocity direction), and later scan-matcher poses keep it there.
TEST(NavFilterHistory, SecondsOldCorrectionShiftsThePresentState) {
  SyntheticConfig c;
  c.duration_s = 14.0;
  c.seed = 8;
  const auto fl = make_flight(c);
  auto filter = std::make_unique<NavFilter>(matched_params(c));
  StreamPlayer player(fl, Duration{});
  player.play_until(*filter, TimeUs::from_s(8.0));
  const NavState then = filter->state();
  player.play_until(*filter, TimeUs::from_s(10.0));
  const NavState before = filter->state();

  const Pose2 d{0.5f, -0.3f, 0.1f};
  ASSERT_EQ(filter->apply_correction(correction_of(then, d)), Status::kOk);
  const NavState after = filter->state();
  EXPECT_EQ(after.stamp, before.stamp);
  const Pose2 expected = d.compose(pose_of(before));
  EXPECT_NEAR(after.position_m.x(), expected.x, 0.005f);
  EXPECT_NEAR(after.position_m.y(), expected.y, 0.005f);
  EXPECT_NEAR(angle_diff(after.heading_rad, expected.theta), 0.0f, 0.002f);
  EXPECT_NEAR(after.position_m.z(), before.position_m.z(), 1e-4f);
  const Eigen::Vector2f v_rot = Eigen::Rotation2D<float>(d.theta) * before.velocity_mps.head<2>();
  EXPECT_NEAR(after.velocity_mps.x(), v_rot.x(), 0.01f);
  EXPECT_NEAR(after.velocity_mps.y(), v_rot.y(), 0.01f);
  EXPECT_EQ(filter->counters().corrections, 1u);
  EXPECT_NEAR(filter->frame_correction().x, d.x, 1e-4f);

  // Later scan-matcher poses (still in the scan matcher's frame) are mapped through the
  // correction: the estimate follows the corrected truth.
  player.play_until(*filter, TimeUs::from_s(14.0));
  const NavState end = filter->state();
  const std::size_t i = player.truth_index(end.stamp);
  const Pose2 truth_corrected = d.compose(Pose2{fl.truth[i].position_m.x(), fl.truth[i].position_m.y(), fl.heading[i]});
  EXPECT_NEAR(end.position_m.x(), truth_corrected.x, 0.03f);
  EXPECT_NEAR(end.position_m.y(), truth_corrected.y, 0.03f);
  EXPECT_NEAR(angle_diff(end.heading_rad, truth_corrected.theta), 0.0f, 0.01f);
  EXPECT_EQ(filter->counters().pose_rejected, 0u);
}

// GIVEN a filter whose frame a rotated correction has already moved WHEN a second correction
// comes THEN frame_correction() after * before^-1 is the rigid move of the present state: the
// move AutonomyStack::estimate_moved hands the mission for the breadcrumbs drawn since (the
// other order of composition is centimetres off, and the test tells them apart).
TEST(NavFilterHistory, FrameCorrectionsComposeToThePresentStatesMove) {
  SyntheticConfig c;
  c.duration_s = 10.0;
  c.seed = 8;
  const auto fl = make_flight(c);
  auto filter = std::make_unique<NavFilter>(matched_params(c));
  StreamPlayer player(fl, Duration{});
  player.play_until(*filter, TimeUs::from_s(5.0));
  const NavState first_then = filter->state();
  player.play_until(*filter, TimeUs::from_s(6.0));
  ASSERT_EQ(filter->apply_correction(correction_of(first_then, {0.3f, -0.2f, 0.3f})), Status::kOk);
  player.play_until(*filter, TimeUs::from_s(8.0));
  const NavState second_then = filter->state();
  player.play_until(*filter, TimeUs::from_s(9.0));
  const Pose2 frame_before = filter->frame_correction();
  const Pose2 before = pose_of(filter->state());
  ASSERT_EQ(filter->apply_correction(correction_of(second_then, {-0.4f, 0.25f, -0.08f})), Status::kOk);
  const Pose2 after = pose_of(filter->state());
  const Pose2 frame_after = filter->frame_correction();
  const Pose2 moved = frame_after.compose(frame_before.inverse()).compose(before);
  EXPECT_NEAR(moved.x, after.x, 0.005f);
  EXPECT_NEAR(moved.y, after.y, 0.005f);
  EXPECT_NEAR(angle_diff(moved.theta, after.theta), 0.0f, 0.002f);
  const Pose2 other_order = frame_before.inverse().compose(frame_after).compose(before);
  EXPECT_GT(std::hypot(other_order.x - after.x, other_order.y - after.y), 0.05f);
}

// A correction beyond max_correction_m is refused and changes nothing; one older than the
// history is out of range.
TEST(NavFilterHistory, CorrectionLimits) {
  SyntheticConfig c;
  c.duration_s = 8.0;
  c.imu_hz = 200;
  const auto fl = make_flight(c);
  auto filter = std::make_unique<NavFilter>(matched_params(c));
  StreamPlayer player(fl, Duration{});
  player.play_until(*filter, TimeUs::from_s(8.0));
  // 1024 slots at 200 Hz: 5.115 s of history.
  EXPECT_EQ(filter->history_span(), Duration::from_us(1023 * 5000));
  const NavState before = filter->state();
  PoseMeasurement2 corr;
  corr.stamp = TimeUs::from_s(5.0);
  corr.pose = Pose2{50.0f, 0.0f, 0.0f};
  EXPECT_EQ(filter->apply_correction(corr), Status::kRejected);
  EXPECT_EQ(filter->counters().corrections_rejected, 1u);
  EXPECT_NEAR(filter->state().position_m.x(), before.position_m.x(), 1e-5f);
  corr.stamp = TimeUs::from_s(2.8);
  EXPECT_EQ(filter->apply_correction(corr), Status::kOutOfRange);
  corr.stamp = TimeUs::from_s(2.9);
  corr.pose = Pose2{before.position_m.x(), before.position_m.y(), 0.0f};
  EXPECT_NE(filter->apply_correction(corr), Status::kOutOfRange);
}

// A scan-matcher pose taken before a correction but delivered after it is in the old frame:
// it must not be shifted by that correction.
TEST(NavFilterHistory, PoseOlderThanACorrectionStaysInItsFrame) {
  SyntheticConfig c;
  c.duration_s = 6.0;
  c.seed = 9;
  auto fl = make_flight(c);
  // Hold back the pose closest to 5.0 s.
  std::size_t held = 0;
  while (fl.poses[held].stamp < TimeUs::from_s(5.0)) ++held;
  const PoseMeasurement2 late_pose = fl.poses[held];
  fl.poses.erase(fl.poses.begin() + static_cast<std::ptrdiff_t>(held));
  fl.altitude.erase(fl.altitude.begin() + static_cast<std::ptrdiff_t>(held));
  auto a = std::make_unique<NavFilter>(matched_params(c));
  StreamPlayer player(fl, Duration{});
  player.play_until(*a, TimeUs::from_s(5.2));
  const NavState at = a->state();
  PoseMeasurement2 corr = correction_of(at, {0.3f, 0.0f, 0.0f});
  corr.stamp = TimeUs::from_s(5.1);  // a little before the state it was drawn from
  ASSERT_EQ(a->apply_correction(corr), Status::kOk);
  const uint32_t rejected = a->counters().pose_rejected;
  EXPECT_EQ(a->update_pose(late_pose), Status::kOk);  // not gated out as a 0.3 m jump
  EXPECT_EQ(a->counters().pose_rejected, rejected);
  // The same pose mapped through the correction would be a jump.
  PoseMeasurement2 shifted = late_pose;
  shifted.pose = a->frame_correction().compose(late_pose.pose);
  shifted.stamp = late_pose.stamp + Duration::from_us(100);
  EXPECT_EQ(a->update_pose(shifted), Status::kRejected);
}

}  // namespace
}  // namespace kestrel::estimation
