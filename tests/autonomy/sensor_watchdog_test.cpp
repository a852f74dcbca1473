// SensorWatchdog on its own: when a device counts as silent, what the mission is told, and how
// the silences are counted.
#include "kestrel/autonomy/sensor_watchdog.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace kestrel::autonomy {
namespace {

TimeUs ms(int64_t v) {
  return TimeUs::from_us(v * 1000);
}

NavState valid_nav() {
  NavState n;
  n.valid = true;
  return n;
}

SensorWatchdog configured() {
  SensorWatchdog w;
  w.configure(SensorTimeouts{});  // 0.1 s IMU, 0.5 s laser
  return w;
}

// Nothing heard yet is silence: the mission gets no estimate before both devices have talked.
TEST(SensorWatchdog, NothingHeardYetIsSilence) {
  SensorWatchdog w = configured();
  w.imu_polled(ms(0));
  w.scan_polled(ms(0));
  EXPECT_FALSE(w.imu_fresh());
  EXPECT_FALSE(w.scan_fresh());
  EXPECT_FALSE(w.for_mission(valid_nav()).valid);
  w.imu_alive(ms(1));
  EXPECT_FALSE(w.for_mission(valid_nav()).valid);
  w.scan_alive(ms(2));
  EXPECT_TRUE(w.for_mission(valid_nav()).valid);
  EXPECT_EQ(w.counters().imu + w.counters().scan, 0u);  // never fresh, so never fell silent
}

// A device is silent when its own task has polled and found nothing usable for longer than its
// timeout (inclusive up to it).
TEST(SensorWatchdog, EachDeviceIsSilentOncePolledEmptyPastItsTimeout) {
  SensorWatchdog w = configured();
  w.imu_alive(ms(1000));
  w.scan_alive(ms(1000));
  w.imu_polled(ms(1100));
  EXPECT_TRUE(w.imu_fresh());
  w.imu_polled(ms(1101));
  EXPECT_FALSE(w.imu_fresh());
  w.scan_polled(ms(1500));
  EXPECT_TRUE(w.scan_fresh());
  w.scan_polled(ms(1501));
  EXPECT_FALSE(w.scan_fresh());
  SensorWatchdog custom;
  custom.configure(SensorTimeouts{0.02f, 2.0f});
  custom.imu_alive(ms(0));
  custom.scan_alive(ms(0));
  custom.imu_polled(ms(21));
  custom.scan_polled(ms(2000));
  EXPECT_FALSE(custom.imu_fresh());
  EXPECT_TRUE(custom.scan_fresh());
}

// A loop that is late is not a silent device: until the device's task polls again, however
// long that takes, nothing says the device fell quiet, and a poll that finds samples waiting
// makes it fresh.
TEST(SensorWatchdog, ALateLoopIsNoSilence) {
  SensorWatchdog w = configured();
  w.imu_alive(ms(0));
  w.scan_alive(ms(0));
  EXPECT_TRUE(w.for_mission(valid_nav()).valid);  // asked at any later time: nothing polled
  w.imu_alive(ms(400));                           // the IMU task ran 0.4 s late and found samples
  EXPECT_TRUE(w.imu_fresh());
  EXPECT_EQ(w.counters().imu, 0u);
}

// The mission's estimate is the filter's, with valid cleared while either device is silent;
// the filter's own "not yet initialised" stays.
TEST(SensorWatchdog, TheMissionsEstimateIsInvalidWhileEitherDeviceIsSilent) {
  SensorWatchdog w = configured();
  NavState n = valid_nav();
  n.position_m = {1, 2, 3};
  w.imu_alive(ms(0));
  w.scan_alive(ms(0));
  const NavState ok = w.for_mission(n);
  EXPECT_TRUE(ok.valid);
  EXPECT_EQ(ok.position_m, n.position_m);
  w.imu_polled(ms(150));
  EXPECT_FALSE(w.for_mission(n).valid);  // the IMU
  w.imu_alive(ms(160));
  w.scan_polled(ms(600));
  EXPECT_FALSE(w.for_mission(n).valid);  // the laser
  w.scan_alive(ms(610));
  EXPECT_TRUE(w.for_mission(n).valid);
  NavState uninitialised = n;
  uninitialised.valid = false;
  EXPECT_FALSE(w.for_mission(uninitialised).valid);
}

// Each fall into silence is counted once, however often the watchdog is asked during it.
TEST(SensorWatchdog, EachSilenceIsCountedOnce) {
  SensorWatchdog w = configured();
  for (int t = 0; t <= 2000; t += 5) {
    if (t < 300 || t > 700) {  // one IMU silence
      w.imu_alive(ms(t));
    } else {
      w.imu_polled(ms(t));
    }
    if (t < 1000) {  // the laser gone for good
      w.scan_alive(ms(t));
    } else {
      w.scan_polled(ms(t));
    }
    (void)w.for_mission(valid_nav());
  }
  EXPECT_EQ(w.counters().imu, 1u);
  EXPECT_EQ(w.counters().scan, 1u);
}

// The loop's clock stepping back an hour is no silence, and does not hide one: a device silent
// after the step shows within its timeout, not an hour later. Stepping far ahead is silence.
TEST(SensorWatchdog, AClockSteppingBackNeitherIsNorHidesASilence) {
  SensorWatchdog w = configured();
  w.imu_alive(ms(3'600'000));
  w.scan_alive(ms(3'600'000));
  w.imu_polled(ms(0));
  w.scan_polled(ms(0));
  EXPECT_TRUE(w.for_mission(valid_nav()).valid);
  w.imu_polled(ms(100));
  EXPECT_TRUE(w.for_mission(valid_nav()).valid);
  w.imu_polled(ms(101));
  EXPECT_FALSE(w.for_mission(valid_nav()).valid);  // the IMU, silent since the step
  EXPECT_EQ(w.counters().imu, 1u);
  w.imu_alive(ms(200));
  w.scan_alive(ms(200));
  w.imu_polled(ms(3'800'000));
  EXPECT_FALSE(w.for_mission(valid_nav()).valid);
}

TEST(SensorWatchdog, TimeoutsOutsideTheirRangeAreInvalid) {
  EXPECT_TRUE(SensorTimeouts{}.valid());
  for (const float bad : {0.0f, -0.1f, 60.5f, std::nanf(""), INFINITY}) {
    EXPECT_FALSE((SensorTimeouts{bad, 0.5f}.valid())) << bad;
    EXPECT_FALSE((SensorTimeouts{0.1f, bad}.valid())) << bad;
  }
}

}  // namespace
}  // namespace kestrel::autonomy
