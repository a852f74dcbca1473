#include <gtest/gtest.h>

#include "kestrel/sim/fake_autopilot.hpp"

namespace kestrel::sim {
namespace {

TEST(CommandDelayLine, ReleasesInOrderAfterTheDelay) {
  CommandDelayLine<4> line;
  AttitudeSetpoint a, b, active;
  a.thrust = 0.1f;
  b.thrust = 0.2f;
  EXPECT_TRUE(line.push(TimeUs{100}, a));
  EXPECT_TRUE(line.push(TimeUs{200}, b));
  EXPECT_FALSE(line.push(TimeUs{150}, a));  // due times must not go backwards
  EXPECT_FALSE(line.release(TimeUs{99}, active));
  EXPECT_TRUE(line.release(TimeUs{150}, active));
  EXPECT_FLOAT_EQ(active.thrust, 0.1f);
  EXPECT_TRUE(line.release(TimeUs{1000}, active));
  EXPECT_FLOAT_EQ(active.thrust, 0.2f);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(line.push(TimeUs{2000 + i}, a));
  EXPECT_FALSE(line.push(TimeUs{3000}, a));  // full
}

TEST(FakeAutopilot, AppliesSetpointsAfterTheConfiguredDelay) {
  ManualTimeSource clock(TimeUs{0});
  FakeAutopilot ap(clock, Duration::from_ms(200), Duration::from_ms(20));
  EXPECT_EQ(ap.arm(true), Status::kOk);
  EXPECT_TRUE(ap.armed());
  AttitudeSetpoint sp;
  sp.pitch_rad = 0.1f;
  clock.set(TimeUs::from_s(1.0));
  EXPECT_EQ(ap.send(sp), Status::kOk);
  EXPECT_FLOAT_EQ(ap.active(TimeUs::from_s(1.199)).pitch_rad, 0.0f);
  EXPECT_FLOAT_EQ(ap.active(TimeUs::from_s(1.2)).pitch_rad, 0.1f);
  sp.roll_rad = std::nanf("");
  EXPECT_EQ(ap.send(sp), Status::kNotFinite);
  // Disarming is immediate and drops what is queued.
  sp.roll_rad = 0;
  sp.pitch_rad = 0.3f;
  EXPECT_EQ(ap.send(sp), Status::kOk);
  EXPECT_EQ(ap.arm(false), Status::kOk);
  EXPECT_FLOAT_EQ(ap.active(TimeUs::from_s(5)).pitch_rad, 0.0f);
}

TEST(FakeAutopilot, ReportsStatusAtItsRate) {
  ManualTimeSource clock;
  FakeAutopilot ap(clock, Duration::from_ms(0), Duration::from_ms(20));
  FlightStatus st;
  EXPECT_EQ(ap.poll_status(st), Status::kNoData);
  int published = 0;
  for (int ms = 1; ms <= 100; ++ms) {
    VehicleState s;
    s.stamp = TimeUs{ms * 1000};
    s.yaw_rad = 0.5;
    ap.update_status(s);
    if (ap.poll_status(st) == Status::kOk) {
      ++published;
      EXPECT_FLOAT_EQ(st.yaw_rad, 0.5f);
    }
  }
  EXPECT_EQ(published, 5);
  // The queue holds at most kDelayCapacity set-points.
  FakeAutopilot slow(clock, Duration::from_s(10), Duration::from_ms(20));
  AttitudeSetpoint sp;
  Status last = Status::kOk;
  for (std::size_t i = 0; i <= FakeAutopilot::kDelayCapacity; ++i) last = slow.send(sp);
  EXPECT_EQ(last, Status::kCapacityExceeded);
}

}  // namespace
}  // namespace kestrel::sim
