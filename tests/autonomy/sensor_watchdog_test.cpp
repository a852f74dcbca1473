// SensorWatchdog on its own: when a device counts as silent, what the mission is told, and how
// the silences are counted.
#include "kestrel/autonomy/sensor_watchdog.hpp"

#include <gtest/gtest.h>

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
  EXPECT_FALSE(w.imu_fresh(ms(0)));
  EXPECT_FALSE(w.scan_fresh(ms(0)));
  EXPECT_FALSE(w.for_mission(valid_nav(), ms(0)).valid);
  w.imu_alive(ms(0));
  EXPECT_FALSE(w.for_mission(valid_nav(), ms(1)).valid);
  w.scan_alive(ms(1));
  EXPECT_TRUE(w.for_mission(valid_nav(), ms(2)).valid);
  EXPECT_EQ(w.counters().imu + w.counters().scan, 0u);  // never fresh, so never fell silent
}

// A device is fresh up to its timeout after the last sample, inclusive, and silent after.
TEST(SensorWatchdog, EachDeviceIsFreshUpToItsTimeout) {
  SensorWatchdog w = configured();
  w.imu_alive(ms(1000));
  w.scan_alive(ms(1000));
  EXPECT_TRUE(w.imu_fresh(ms(1100)));
  EXPECT_FALSE(w.imu_fresh(ms(1101)));
  EXPECT_TRUE(w.scan_fresh(ms(1500)));
  EXPECT_FALSE(w.scan_fresh(ms(1501)));
  SensorWatchdog custom;
  custom.configure(SensorTimeouts{0.02f, 2.0f});
  custom.imu_alive(ms(0));
  custom.scan_alive(ms(0));
  EXPECT_FALSE(custom.imu_fresh(ms(21)));
  EXPECT_TRUE(custom.scan_fresh(ms(2000)));
}

// The mission's estimate is the filter's, with valid cleared while either device is silent;
// the filter's own "not yet initialised" stays.
TEST(SensorWatchdog, TheMissionsEstimateIsInvalidWhileEitherDeviceIsSilent) {
  SensorWatchdog w = configured();
  NavState n = valid_nav();
  n.position_m = {1, 2, 3};
  w.imu_alive(ms(0));
  w.scan_alive(ms(0));
  const NavState ok = w.for_mission(n, ms(50));
  EXPECT_TRUE(ok.valid);
  EXPECT_EQ(ok.position_m, n.position_m);
  EXPECT_FALSE(w.for_mission(n, ms(150)).valid);  // the IMU
  w.imu_alive(ms(150));
  EXPECT_TRUE(w.for_mission(n, ms(200)).valid);
  EXPECT_FALSE(w.for_mission(n, ms(600)).valid);  // the laser
  w.imu_alive(ms(600));
  w.scan_alive(ms(600));
  NavState uninitialised = n;
  uninitialised.valid = false;
  EXPECT_FALSE(w.for_mission(uninitialised, ms(601)).valid);
}

// Each fall into silence is counted once, however often the watchdog is asked during it.
TEST(SensorWatchdog, EachSilenceIsCountedOnce) {
  SensorWatchdog w = configured();
  w.imu_alive(ms(0));
  w.scan_alive(ms(0));
  for (int t = 0; t <= 2000; t += 5) {
    if (t < 300 || t > 700) w.imu_alive(ms(t));  // one IMU silence
    if (t < 1000) w.scan_alive(ms(t));           // the laser gone for good
    (void)w.for_mission(valid_nav(), ms(t));
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
  EXPECT_TRUE(w.for_mission(valid_nav(), ms(0)).valid);
  EXPECT_TRUE(w.for_mission(valid_nav(), ms(100)).valid);
  EXPECT_FALSE(w.for_mission(valid_nav(), ms(101)).valid);  // the IMU, silent since the step
  EXPECT_EQ(w.counters().imu, 1u);
  w.imu_alive(ms(200));
  w.scan_alive(ms(200));
  EXPECT_FALSE(w.for_mission(valid_nav(), ms(3'800'000)).valid);
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
