// The Simulation through its HAL face: lockstep clock, sensors, autopilot, ground truth,
// contacts ending the flight, no heap in the loop, and byte-identical repeat runs.
#include <gtest/gtest.h>

#include <cstring>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/sim/builtin_worlds.hpp"
#include "kestrel/sim/simulation.hpp"
#include "kestrel/sim/world_parser.hpp"

namespace kestrel::sim {
namespace {

World make(const char* text) {
  auto r = parse_world(text, "test");
  EXPECT_TRUE(r.ok) << r.error;
  return r.world;
}

constexpr const char* kBox = "start 2 2 0 0\nwall 0 0 10 0\nwall 10 0 10 4\nwall 10 4 0 4\nwall 0 4 0 0\n";

void hover_setpoint(Simulation& sim, float pitch = 0, float thrust = 0.5f) {
  AttitudeSetpoint sp;
  sp.stamp = sim.clock().now();
  sp.pitch_rad = pitch;
  sp.thrust = thrust;
  ASSERT_EQ(sim.flight_controller().send(sp), Status::kOk);
}

TEST(Simulation, HalDriversProduceDataOnTheLockstepClock) {
  Simulation sim(make(kBox), SimConfig{});
  hal::Clock& clock = sim.clock();
  EXPECT_EQ(clock.now().us, 0);
  ASSERT_EQ(clock.sleep_until(TimeUs::from_s(1.0)), Status::kOk);
  EXPECT_EQ(clock.now().us, 1000000);
  EXPECT_EQ(clock.sleep_until(TimeUs::from_s(0.5)), Status::kOk);  // in the past: no-op
  EXPECT_EQ(clock.now().us, 1000000);
  LaserScan scan;
  ASSERT_EQ(sim.laser().poll(scan), Status::kOk);
  EXPECT_EQ(scan.beam_count, 1081);
  EXPECT_EQ(scan.stamp.us, 39 * 25000);
  int imu = 0;
  ImuSample s;
  while (sim.imu().poll(s) == Status::kOk) ++imu;
  EXPECT_EQ(imu, 200);
  EXPECT_NEAR(s.accel_mps2.z(), 9.81, 0.5);  // standing on the floor
  // On the floor the mirror beams are nearer than the scanner's minimum range: no height.
  AltimeterSample a;
  EXPECT_EQ(sim.altimeter().poll(a), Status::kNoData);
  FlightStatus st;
  ASSERT_EQ(sim.flight_controller().poll_status(st), Status::kOk);
  EXPECT_FALSE(st.armed);
}

TEST(Simulation, TakesOffHoversAndReportsTruthAtPastTimes) {
  SimConfig cfg;
  cfg.command_delay_s = 0.05;
  cfg.truth_history_s = 1.0;
  if (KESTREL_SIM_SHORT_TESTS) cfg.laser.deflected_beams = 20;  // keep the altimeter
  if (KESTREL_SIM_SHORT_TESTS) cfg.laser.beam_count = 60;      // but cast few beams
  Simulation sim(make(kBox), cfg);
  ASSERT_EQ(sim.flight_controller().arm(true), Status::kOk);
  hover_setpoint(sim, 0, 0.55f);
  (void)sim.step_until(TimeUs::from_s(1.0));
  hover_setpoint(sim, 0, 0.45f);
  (void)sim.step_until(TimeUs::from_s(2.0));
  hover_setpoint(sim);
  (void)sim.step_until(TimeUs::from_s(3.0));
  // 1 s up at +0.981 m/s², 1 s braking: 0.981 m, independent of the (equal) delays.
  EXPECT_NEAR(sim.truth().position_m.z(), 0.981, 1e-6);
  EXPECT_NEAR(sim.truth().velocity_mps.z(), 0, 1e-9);
  VehicleState past;
  ASSERT_EQ(sim.truth_at(TimeUs::from_s(2.5), past), Status::kOk);
  EXPECT_NEAR(past.position_m.z(), 0.981, 1e-6);
  ASSERT_EQ(sim.truth_at(TimeUs{2000500}, past), Status::kOk);  // between two steps
  EXPECT_EQ(past.stamp.us, 2000500);
  EXPECT_EQ(sim.truth_at(TimeUs::from_s(1.5), past), Status::kOutOfRange);  // older than 1 s
  EXPECT_EQ(sim.truth_at(TimeUs::from_s(3.5), past), Status::kOutOfRange);  // future
  // Hovering at 0.98 m the mirror beams give the height.
  AltimeterSample a, newest;
  int n = 0;
  while (sim.altimeter().poll(a) == Status::kOk) {
    newest = a;
    ++n;
  }
  EXPECT_GT(n, 40);
  EXPECT_NEAR(newest.height_m, 0.981, 0.01);
}

TEST(Simulation, ContactEndsTheFlightWithTimeAndPlace) {
  SimConfig cfg;
  cfg.laser = LaserParams::urg04lx();  // the laser does not matter here: the cheaper one
  Simulation sim(make(kBox), cfg);
  ASSERT_EQ(sim.flight_controller().arm(true), Status::kOk);
  hover_setpoint(sim, 0, 0.55f);
  (void)sim.step_until(TimeUs::from_s(1.0));
  hover_setpoint(sim, 0.3f, 0.45f);  // forward, hard, towards the wall at x = 10
  (void)sim.step_until(TimeUs::from_s(8.0));
  ASSERT_TRUE(sim.flight_ended());
  ASSERT_EQ(sim.contacts().size(), 1u);
  const Contact& c = sim.contacts()[0];
  EXPECT_NEAR(c.position_m.x(), 9.95, 0.05);
  EXPECT_GT(c.stamp.us, 1000000);
  EXPECT_LT(c.stamp.us, 8000000);
  const Eigen::Vector3d where = sim.truth().position_m;
  (void)sim.step_until(TimeUs::from_s(9.0));
  EXPECT_EQ(sim.truth().position_m, where);  // stopped where it hit
  EXPECT_EQ(sim.now().us, 9000000);           // but time goes on
}

TEST(Simulation, SteppingDoesNotAllocate) {
  const auto w = load_builtin_world("cluttered-lab");
  ASSERT_TRUE(w.ok);
  SimConfig cfg;
  if (KESTREL_SIM_SHORT_TESTS) cfg.laser = LaserParams::urg04lx();
  Simulation sim(w.world, cfg);
  ASSERT_EQ(sim.flight_controller().arm(true), Status::kOk);
  hover_setpoint(sim, 0, 0.55f);
  alloc_guard::Scope guard;  // from the first step: the first contact query must not allocate
  (void)sim.step_until(TimeUs::from_s(0.2));
  hover_setpoint(sim, 0.02f, 0.5f);
  (void)sim.step_until(TimeUs::from_s(KESTREL_SIM_SHORT_TESTS ? 0.5 : 1.2));
  LaserScan scan;
  ImuSample imu;
  (void)sim.laser().poll(scan);
  while (sim.imu().poll(imu) == Status::kOk) {
  }
  EXPECT_EQ(guard.allocations(), 0u);
}

// FNV-1a over everything a run produces.
struct Digest {
  uint64_t h = 1469598103934665603ull;
  void add(const void* p, std::size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
};

uint64_t run_digest(uint64_t seed, const LaserParams& laser, double seconds) {
  const auto w = load_builtin_world("iarc-arena");
  SimConfig cfg;
  cfg.seed = seed;
  cfg.laser = laser;
  cfg.vehicle.gust_std_mps2 = 0.3;  // gusts draw random numbers too
  Simulation sim(w.world, cfg);
  Digest d;
  (void)sim.flight_controller().arm(true);
  for (int64_t ms = 0; ms < static_cast<int64_t>(seconds * 1000); ms += 10) {
    AttitudeSetpoint sp;
    sp.stamp = sim.now();
    sp.thrust = ms < 1000 ? 0.55f : (ms < 2000 ? 0.45f : 0.5f);
    sp.pitch_rad = ms > 2000 ? 0.05f : 0.0f;
    (void)sim.flight_controller().send(sp);
    (void)sim.step_until(TimeUs{(ms + 10) * 1000});
    LaserScan scan;
    if (sim.laser().poll(scan) == Status::kOk) d.add(scan.range_mm.data(), scan.beam_count * sizeof(uint16_t));
    ImuSample imu;
    while (sim.imu().poll(imu) == Status::kOk) {
      d.add(imu.accel_mps2.data(), sizeof(float) * 3);
      d.add(imu.gyro_radps.data(), sizeof(float) * 3);
    }
    d.add(sim.truth().position_m.data(), sizeof(double) * 3);
  }
  return d.h;
}

TEST(Simulation, SameSeedGivesIdenticalBytesAndAnotherSeedDoesNot) {
  const double seconds = KESTREL_SIM_SHORT_TESTS ? 1.0 : 3.0;
  const uint64_t a = run_digest(42, LaserParams::utm30lx(), seconds);
  EXPECT_EQ(a, run_digest(42, LaserParams::utm30lx(), seconds));
  EXPECT_NE(a, run_digest(43, LaserParams::utm30lx(), seconds));
  const uint64_t u = run_digest(7, LaserParams::urg04lx(), seconds);
  EXPECT_EQ(u, run_digest(7, LaserParams::urg04lx(), seconds));
}

}  // namespace
}  // namespace kestrel::sim
