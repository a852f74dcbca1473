// AutonomyStack at the HAL boundary, without the simulator: scripted fake devices (a clock the
// test moves, a laser and an IMU that serve what the test queues, an autopilot that records
// what it is sent and reports what the test sets) drive the stack the way the simulator's
// lockstep does (sleep to the next release, poll, background step). Pinned: configuration and
// start-up refusals, what the loop reads from each device and counts, what it does with
// malformed input and failing devices (counted, never a NaN to the autopilot), and no heap
// after start. The closed loop itself is flown in tests/flight.
#include "kestrel/autonomy/autonomy_stack.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <memory>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/core/ring_buffer.hpp"
#include "synthetic_world.hpp"

namespace kestrel::autonomy {
namespace {

namespace mf = scan_matching::match_flag;
using mission::Phase;

const test::LaserModel kUrg = test::LaserModel::urg04lx();
const Duration kScanPeriod = Duration::from_ms(100);  // the URG-04LX's 10 Hz
const Duration kImuPeriod = Duration::from_ms(5);     // 200 Hz
const Duration kAltPeriod = Duration::from_ms(50);    // 20 Hz
const TimeUs kT0 = TimeUs::from_s(100.0);
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// ---- Fake devices -------------------------------------------------------------------------

class FakeClock final : public hal::Clock {
 public:
  TimeUs now() const override { return now_; }
  Status sleep_until(TimeUs t) override {
    if (now_ < t) now_ = t;
    return Status::kOk;
  }
  void set(TimeUs t) { now_ = t; }

 private:
  TimeUs now_ = kT0;
};

// Serves queued items in order; kNoData when none is waiting; `fail_polls` polls answer
// `fail_with` instead (forever with fail_polls < 0). Fixed capacity: queueing never allocates.
template <class T, std::size_t N>
class ScriptedQueue {
 public:
  bool queue(const T& v) {
    if (queue_.push(v)) return true;
    ++dropped;
    return false;
  }
  Status poll(T& out) {
    ++polls;
    if (fail_polls != 0) {
      if (fail_polls > 0) --fail_polls;
      return fail_with;
    }
    return queue_.pop(out) ? Status::kOk : Status::kNoData;
  }
  std::size_t waiting() const { return queue_.size(); }

  int fail_polls = 0;
  Status fail_with = Status::kIoError;
  uint32_t polls = 0;
  uint32_t dropped = 0;

 private:
  RingBuffer<T, N> queue_;
};

class FakeLaser final : public hal::LaserScanner {
 public:
  FakeLaser() {
    geometry_.beam_count = kUrg.beams;
    geometry_.first_angle_rad = static_cast<float>(kUrg.first_angle());
    geometry_.angle_step_rad = static_cast<float>(kUrg.step());
    geometry_.min_range_mm = 20;
    geometry_.max_range_mm = kUrg.max_range_mm;
    geometry_.scan_period = kScanPeriod;
  }
  hal::LaserGeometry geometry() const override { return geometry_; }
  Status poll(LaserScan& out) override { return scans.poll(out); }

  hal::LaserGeometry geometry_;
  ScriptedQueue<LaserScan, 8> scans;
};

class FakeImu final : public hal::Imu {
 public:
  Duration sample_period() const override { return kImuPeriod; }
  Status poll(ImuSample& out) override { return samples.poll(out); }
  ScriptedQueue<ImuSample, 64> samples;
};

class FakeAltimeter final : public hal::Altimeter {
 public:
  Status poll(AltimeterSample& out) override { return samples.poll(out); }
  ScriptedQueue<AltimeterSample, 16> samples;
};

// Records what the stack sends; answers with the results the test sets.
class FakeAutopilot final : public hal::FlightController {
 public:
  Status arm(bool a) override {
    ++arm_calls;
    if (arm_result != Status::kOk) return arm_result;
    armed = a;
    return Status::kOk;
  }
  Status send(const AttitudeSetpoint& sp) override {
    ++sends;
    last = sp;
    // Anything the autopilot could not fly: non-finite, thrust outside 0..1, tilt beyond 60 deg.
    const bool finite = std::isfinite(sp.pitch_rad) && std::isfinite(sp.roll_rad) && std::isfinite(sp.thrust) &&
                        std::isfinite(sp.yaw_rate_radps);
    if (!finite || !(sp.thrust >= 0.0f && sp.thrust <= 1.0f) || !(std::fabs(sp.pitch_rad) < 1.05f) ||
        !(std::fabs(sp.roll_rad) < 1.05f))
      ++unflyable;
    if (send_result != Status::kOk) return send_result;
    ++accepted;
    return Status::kOk;
  }
  Status poll_status(FlightStatus& out) override {
    ++status_polls;
    if (!report_status) return Status::kNoData;
    out = status;
    out.armed = armed;
    return Status::kOk;
  }

  Status arm_result = Status::kOk;
  Status send_result = Status::kOk;
  bool report_status = true;
  FlightStatus status;  // level, heading 0
  bool armed = false;
  uint32_t arm_calls = 0, sends = 0, accepted = 0, unflyable = 0, status_polls = 0;
  AttitudeSetpoint last;
};

// ---- The rig ------------------------------------------------------------------------------

// A 6 m x 4 m room with a pillar and a slanted board (which break the room's symmetry), the
// vehicle at rest at the origin, heading 0.
test::SegmentWorld room() {
  test::SegmentWorld w;
  w.add_box(-3.0, -2.0, 3.0, 2.0);
  w.add_box(1.0, 0.6, 1.4, 1.0);
  w.add(-2.0, -1.2, -1.2, -1.6);
  return w;
}

ImuSample level_imu(TimeUs t) {
  ImuSample s;
  s.stamp = t;
  s.accel_mps2 = {0.0f, 0.0f, estimation::EkfParams{}.gravity_mps2};
  return s;
}

struct Rig {
  FakeClock clock;
  ManualTimeSource exec{kT0};  // execution time: the fakes take none
  FakeLaser laser;
  FakeImu imu;
  FakeAltimeter altimeter;
  FakeAutopilot autopilot;
  test::SegmentWorld world = room();
  std::unique_ptr<AutonomyStack> stack;

  // The devices' streams: each measures at its rate; a silent device measures nothing. The IMU
  // has a sample at the first scan's stamp, so the filter's history starts there (the case of
  // a first pose older than every stored sample is NavFilterHistory's).
  bool laser_on = true, imu_on = true;
  TimeUs next_scan = kT0, next_imu = kT0, next_alt = kT0;
  TimeUs last_scan_stamp;
  float height_m = 0.0f;

  explicit Rig(bool with_altimeter = false)
      : stack(std::make_unique<AutonomyStack>(
            Devices{clock, laser, imu, with_altimeter ? &altimeter : nullptr, autopilot}, exec)) {}

  static StackConfig config() {
    StackConfig c;
    c.mission.preflight_s = 0.2f;  // take off soon: the tests are about the loop, not the biases
    return c;
  }
  Status configure_and_start() {
    const Status s = stack->configure(config());
    return s == Status::kOk ? stack->start() : s;
  }

  // A scan of the room from the origin, as the laser takes it at `stamp`.
  LaserScan scan_at(TimeUs stamp) const {
    LaserScan s = world.scan(kUrg, 0.0, 0.0, 0.0, stamp);
    s.scan_period = kScanPeriod;
    return s;
  }

  // The simulator's lockstep: to the next release; the devices deliver what they measured by
  // then (a scan once its sweep has ended); poll; the background step.
  void run_for(Duration d) {
    const TimeUs end = clock.now() + d;
    for (TimeUs t = stack->next_release(); t <= end; t = stack->next_release()) {
      if (clock.now() < t) clock.set(t);
      deliver();
      stack->poll();
      stack->background_step();
    }
    clock.set(end);
    deliver();
  }
  void deliver() {
    const TimeUs now = clock.now();
    for (; next_imu <= now; next_imu += kImuPeriod)
      if (imu_on) (void)imu.samples.queue(level_imu(next_imu));
    for (; next_scan + kScanPeriod <= now; next_scan += kScanPeriod) {
      if (!laser_on) continue;
      (void)laser.scans.queue(scan_at(next_scan));
      last_scan_stamp = next_scan;
    }
    for (; next_alt <= now; next_alt += kAltPeriod) {
      AltimeterSample a;
      a.stamp = next_alt;
      a.height_m = height_m;
      a.variance_m2 = 1e-4f;
      (void)altimeter.samples.queue(a);
    }
  }
  // Runs the loop until the stack has read one more scan (at most `limit`); true if it did.
  bool run_until_next_scan(Duration limit = Duration::from_ms(300)) {
    const uint32_t before = stack->counters().scans;
    for (Duration ran; ran < limit && stack->counters().scans == before; ran = ran + Duration::from_ms(5))
      run_for(Duration::from_ms(5));
    return stack->counters().scans == before + 1;
  }
  // On until the vehicle is armed and set-points flow (the take-off has begun).
  bool run_until_armed(Duration limit = Duration::from_s(2.0)) {
    for (Duration ran; ran < limit && autopilot.accepted == 0; ran = ran + Duration::from_ms(10))
      run_for(Duration::from_ms(10));
    return autopilot.armed && autopilot.accepted > 0;
  }
  bool nav_finite() const {
    const NavState& n = stack->nav();
    return n.position_m.allFinite() && n.velocity_mps.allFinite() && std::isfinite(n.heading_rad);
  }
};

class AutonomyStackTest : public ::testing::Test {
 protected:
  // Whatever a test did to the stack, nothing the autopilot could not fly reached it.
  void TearDown() override {
    EXPECT_EQ(rig_->autopilot.unflyable, 0u) << "last: thrust " << rig_->autopilot.last.thrust;
  }

  std::unique_ptr<Rig> rig_ = std::make_unique<Rig>();
  Rig& r = *rig_;
};

// ---- Configuration and start-up -----------------------------------------------------------

// configure() is the only guard between a parameter file and the loop: each module's refusal
// must reach the caller (kestrel-fw prints configure_error()) and leave the stack unstartable,
// so a half-applied configuration never flies.
TEST_F(AutonomyStackTest, ConfigureRefusesEachBadSubConfigurationNamesItAndStartStaysRefused) {
  struct Case {
    const char* what;
    void (*spoil)(StackConfig&);
    const char* error;
  };
  const Case cases[] = {
      {"matcher resolution 0", [](StackConfig& c) { c.matcher.resolution_m = 0.0f; }, "scan matcher parameters"},
      {"non-finite home", [](StackConfig& c) { c.home.x = kNaN; }, "scan matcher parameters"},
      {"EKF imu gap < 0", [](StackConfig& c) { c.ekf.max_imu_gap_s = -1.0f; }, "EKF parameters"},
      {"controller NaN clip", [](StackConfig& c) { c.controller.max_position_error_m = kNaN; },
       "controller parameters"},
      {"mission timeout 0", [](StackConfig& c) { c.mission.estimate_timeout_s = 0.0f; },
       "mission parameters or waypoints"},
      {"waypoints: none", [](StackConfig& c) { c.mission_kind = mission::MissionKind::kWaypoints; },
       "mission parameters or waypoints"},
      {"home fix radius NaN", [](StackConfig& c) { c.home_fix.radius_m = kNaN; }, "home re-localisation parameters"},
  };
  for (const Case& k : cases) {
    StackConfig c = Rig::config();
    k.spoil(c);
    EXPECT_EQ(r.stack->configure(c), Status::kInvalidArgument) << k.what;
    EXPECT_STREQ(r.stack->configure_error(), k.error) << k.what;
    EXPECT_EQ(r.stack->start(), Status::kNotFound) << k.what;
    EXPECT_EQ(r.stack->scheduler().task_count(), 0u) << k.what;
  }
  // A good configuration after the refusals clears the error and starts.
  EXPECT_EQ(r.stack->configure(Rig::config()), Status::kOk);
  EXPECT_STREQ(r.stack->configure_error(), "");
  EXPECT_EQ(r.stack->start(), Status::kOk);
  // ...and a bad one after a good one (not yet started) unconfigures again.
  Rig other;
  ASSERT_EQ(other.stack->configure(Rig::config()), Status::kOk);
  StackConfig bad = Rig::config();
  bad.ekf.max_imu_gap_s = -1.0f;
  EXPECT_EQ(other.stack->configure(bad), Status::kInvalidArgument);
  EXPECT_EQ(other.stack->start(), Status::kNotFound);
}

// The explorer is configured against the laser the stack was given: a scanner that reports an
// impossible geometry must be refused before flight, not discovered by the first scan.
TEST_F(AutonomyStackTest, ExploreMissionRefusesALaserWithoutBeams) {
  r.laser.geometry_.beam_count = 0;
  StackConfig c = Rig::config();
  c.mission_kind = mission::MissionKind::kExplore;
  EXPECT_EQ(r.stack->configure(c), Status::kInvalidArgument);
  EXPECT_STREQ(r.stack->configure_error(), "explorer parameters or laser geometry");
  EXPECT_EQ(r.stack->explorer(), nullptr);
  EXPECT_EQ(r.stack->start(), Status::kNotFound);
  r.laser.geometry_ = FakeLaser{}.geometry_;
  EXPECT_EQ(r.stack->configure(c), Status::kOk);
  EXPECT_NE(r.stack->explorer(), nullptr);
}

// The operator's keep-out boxes are the explorer's parameters; the flight home's shortcut must
// keep out of them too (the laser sees through the glass they mark), so the stack hands them on.
TEST_F(AutonomyStackTest, TheMissionKeepsOutOfTheExplorersKeepOutBoxes) {
  StackConfig c = Rig::config();
  c.mission_kind = mission::MissionKind::kExplore;
  c.explorer.srt.keep_out[0] = {2.0f, 8.9f, 5.0f, 9.1f};
  c.explorer.srt.keep_out_count = 1;
  ASSERT_EQ(r.stack->configure(c), Status::kOk);
  const mission::MissionParams& p = r.stack->mission().params();
  ASSERT_EQ(p.keep_out_count, 1u);
  EXPECT_FLOAT_EQ(p.keep_out[0].x_min, 2.0f);
  EXPECT_FLOAT_EQ(p.keep_out[0].y_max, 9.1f);
}

// The home fix turns the blend's flights on the spot after take-off, for reference scans all
// round home; the frontier explorer's not (home_fix.hpp: the turn cost it and gained nothing);
// with the home fix off, neither turns.
TEST_F(AutonomyStackTest, OnlyTheBlendFamilysFlightsTurnAfterTakeOffForTheHomeFix) {
  StackConfig c = Rig::config();
  c.mission_kind = mission::MissionKind::kExplore;
  ASSERT_EQ(r.stack->configure(c), Status::kOk);
  EXPECT_FLOAT_EQ(r.stack->mission().params().takeoff_survey_rad, c.home_fix.survey_rad);
  EXPECT_GT(c.home_fix.survey_rad, 6.0f);
  c.explorer_kind = exploration::ExplorerKind::kFrontier;
  ASSERT_EQ(r.stack->configure(c), Status::kOk);
  EXPECT_FLOAT_EQ(r.stack->mission().params().takeoff_survey_rad, 0.0f);  // the default
  EXPECT_GT(r.stack->mission().params().home_survey_rad, 6.0f);  // over home it still turns
  c.home_fix.frontier_survey_rad = 1.0f;  // it is this setting the frontier's flights take
  ASSERT_EQ(r.stack->configure(c), Status::kOk);
  EXPECT_FLOAT_EQ(r.stack->mission().params().takeoff_survey_rad, 1.0f);
  // Checked with the home fix's settings, whichever the explorer.
  c.explorer_kind = exploration::ExplorerKind::kBlend;
  c.home_fix.frontier_survey_rad = -1.0f;
  EXPECT_EQ(r.stack->configure(c), Status::kInvalidArgument);
  EXPECT_STREQ(r.stack->configure_error(), "home re-localisation parameters");
  c.home_fix.frontier_survey_rad = 0.0f;
  c.home_fix.enabled = false;
  ASSERT_EQ(r.stack->configure(c), Status::kOk);
  EXPECT_FLOAT_EQ(r.stack->mission().params().takeoff_survey_rad, 0.0f);
}

// Before start() the loop must not touch a device (the firmware may poll while the sensors
// are still being brought up): nothing is read, nothing is sent, nothing counted.
TEST_F(AutonomyStackTest, BeforeStartNothingRunsAndNoDeviceIsTouched) {
  EXPECT_EQ(r.stack->start(), Status::kNotFound);  // not configured
  (void)r.laser.scans.queue(r.scan_at(kT0));
  (void)r.imu.samples.queue(level_imu(kT0));
  r.clock.set(kT0 + Duration::from_ms(200));
  EXPECT_EQ(r.stack->poll(), 0u);
  ASSERT_EQ(r.stack->configure(Rig::config()), Status::kOk);
  EXPECT_EQ(r.stack->poll(), 0u);  // configured, not started
  EXPECT_EQ(r.laser.scans.polls + r.imu.samples.polls, 0u);
  EXPECT_EQ(r.autopilot.arm_calls + r.autopilot.sends + r.autopilot.status_polls, 0u);
  EXPECT_EQ(r.laser.scans.waiting(), 1u);
  EXPECT_EQ(r.imu.samples.waiting(), 1u);
  const StackCounters zero{};
  EXPECT_EQ(std::memcmp(&r.stack->counters(), &zero, sizeof(StackCounters)), 0);
}

// start() registers the task table (task_table.hpp) with every task released at once; a
// second start() must not register it twice (which would run every task twice per period).
TEST_F(AutonomyStackTest, StartRegistersTheTaskTableOnceAndReleasesEveryTaskAtOnce) {
  const TimeUs t_start = kT0 + Duration::from_ms(7);
  r.clock.set(t_start);
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  EXPECT_EQ(r.stack->start(), Status::kOk);
  const Scheduler& s = r.stack->scheduler();
  ASSERT_EQ(s.task_count(), 4u);
  const auto rows = task_table(kScanPeriod);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_STREQ(s.spec(i).name, rows[i].name);
    EXPECT_EQ(s.spec(i).period, rows[i].period);
    EXPECT_EQ(s.spec(i).budget, rows[i].budget);  // the scan task's budget from the laser's period
  }
  EXPECT_EQ(r.stack->next_release(), t_start);
  EXPECT_EQ(r.stack->poll(), 4u);
  EXPECT_EQ(r.stack->poll(), 0u);  // nothing due until the clock moves
  EXPECT_EQ(r.stack->next_release(), t_start + Duration::from_ms(5));
  EXPECT_EQ(r.imu.samples.polls, 1u);
  EXPECT_EQ(r.laser.scans.polls, 1u);
}

// Reconfiguring a running loop would swap parameters under the tasks: refused, and the loop
// runs on with what it had.
TEST_F(AutonomyStackTest, ConfigureIsRefusedWhileTheLoopRuns) {
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  r.run_for(Duration::from_ms(500));
  const uint32_t scans = r.stack->counters().scans;
  EXPECT_EQ(r.stack->configure(Rig::config()), Status::kUnsupported);
  EXPECT_STREQ(r.stack->configure_error(), "the stack is running");
  r.run_for(Duration::from_ms(500));
  EXPECT_GT(r.stack->counters().scans, scans);
  EXPECT_EQ(r.stack->scheduler().task_count(), 4u);
}

// ---- What the loop reads and counts -------------------------------------------------------

// The counters are what metrics.json and telemetry report: every sample and scan the devices
// deliver must be read (none left waiting, none dropped by the fakes) and counted once, good
// scans of a still room must all match at the home pose, and each accepted command must be
// counted as sent.
TEST(AutonomyStack, QueuedScansImuAndAltimeterSamplesAreConsumedMatchedAndCounted) {
  auto rig = std::make_unique<Rig>(/*with_altimeter=*/true);
  Rig& r = *rig;
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  r.run_for(Duration::from_s(1.0));
  const StackCounters& c = r.stack->counters();
  // Scans stamped 0..0.9 s have ended their sweep by 1 s: 10 scans, 201 IMU samples (0..1 s), 21
  // heights.
  EXPECT_EQ(c.scans, 10u);
  EXPECT_EQ(c.scans_matched, 10u);
  EXPECT_EQ(c.scans_rejected, 0u);
  EXPECT_EQ(c.poses_gated, 0u);
  EXPECT_EQ(c.scans_lost, 0u);
  EXPECT_EQ(c.imu_samples, 201u);
  EXPECT_EQ(c.imu_errors, 0u);
  EXPECT_EQ(c.altitude_samples, 21u);
  EXPECT_EQ(c.device_errors, 0u);
  EXPECT_GE(r.stack->map_rebuilds(), 1u);
  EXPECT_EQ(r.laser.scans.waiting() + r.imu.samples.waiting() + r.altimeter.samples.waiting(), 0u);
  EXPECT_EQ(r.laser.scans.dropped + r.imu.samples.dropped + r.altimeter.samples.dropped, 0u);
  // Every scan reached the filter; the estimate sits at home, current to the newest sample.
  EXPECT_EQ(r.stack->filter().counters().pose_updates, 10u);
  const NavState& n = r.stack->nav();
  ASSERT_TRUE(n.valid);
  EXPECT_NEAR(n.position_m.x(), 0.0f, 0.02f);
  EXPECT_NEAR(n.position_m.y(), 0.0f, 0.02f);
  EXPECT_NEAR(n.heading_rad, 0.0f, 0.01f);
  EXPECT_EQ(n.stamp, kT0 + Duration::from_s(1.0));
  EXPECT_EQ(r.stack->last_match().measurement.stamp, r.last_scan_stamp);
  // Preflight over: the mission armed the autopilot, and every accepted command was counted.
  EXPECT_TRUE(r.autopilot.armed);
  EXPECT_GT(r.autopilot.accepted, 0u);
  EXPECT_EQ(c.setpoints_sent, r.autopilot.accepted);
  EXPECT_EQ(c.autopilot_errors, 0u);
  EXPECT_EQ(r.autopilot.unflyable, 0u);
}

// The laser task reads one scan per run (every 5 ms): a backlog is worked off, not dropped,
// and only the newest match is flagged new, during the poll that produced it.
TEST_F(AutonomyStackTest, ABacklogOfScansIsReadOnePerScanTaskRun) {
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  r.laser_on = false;
  for (int i = 3; i > 0; --i) ASSERT_TRUE(r.laser.scans.queue(r.scan_at(kT0 - kScanPeriod * i)));
  for (uint32_t k = 1; k <= 3; ++k) {
    r.clock.set(r.stack->next_release());
    r.deliver();
    r.stack->poll();
    r.stack->background_step();
    EXPECT_EQ(r.stack->counters().scans, k);
    EXPECT_TRUE(r.stack->new_match());
    EXPECT_EQ(r.laser.scans.waiting(), 3u - k);
  }
  r.clock.set(r.stack->next_release());
  r.stack->poll();
  EXPECT_FALSE(r.stack->new_match());
  EXPECT_EQ(r.stack->counters().scans_matched, 3u);
}

// ---- Malformed input ----------------------------------------------------------------------

// A corrupt frame must cost one scan, never the estimate: each malformed scan is counted as
// read and rejected with its reason, the filter never sees it, and the next good scan matches.
TEST_F(AutonomyStackTest, MalformedScansAreRejectedWithTheirReasonAndTheNextGoodScanMatches) {
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  ASSERT_TRUE(r.run_until_armed());
  r.run_for(Duration::from_ms(200));
  r.laser_on = false;  // only the scans below, one at a time
  struct Bad {
    const char* what;
    LaserScan scan;
    uint32_t reason;
  };
  const TimeUs now = r.clock.now();
  Bad bad[] = {
      {"NaN angle step", r.scan_at(now), mf::kBadGeometry},
      {"infinite first angle", r.scan_at(now), mf::kBadGeometry},
      {"no beams", r.scan_at(now), mf::kBadGeometry},
      {"more beams than any laser", r.scan_at(now), mf::kBadGeometry},
      {"field of view over a turn", r.scan_at(now), mf::kBadGeometry},
      {"time going backwards", r.scan_at(r.last_scan_stamp - Duration::from_ms(50)), mf::kTimeBackwards},
      {"nothing but no-returns", test::uniform_scan(kUrg, range_code::kNoReturn), mf::kTooFewPoints},
  };
  bad[0].scan.angle_step_rad = kNaN;
  bad[1].scan.first_angle_rad = kInf;
  bad[2].scan.beam_count = 0;
  bad[3].scan.beam_count = static_cast<uint16_t>(kMaxBeams + 1);
  bad[4].scan.angle_step_rad = 0.01f;  // 682 beams over 6.8 rad
  bad[6].scan.stamp = now;
  for (const Bad& b : bad) {
    const StackCounters before = r.stack->counters();
    const uint32_t poses = r.stack->filter().counters().pose_updates;
    ASSERT_TRUE(r.laser.scans.queue(b.scan));
    ASSERT_TRUE(r.run_until_next_scan()) << b.what;
    const StackCounters& c = r.stack->counters();
    EXPECT_EQ(c.scans_rejected, before.scans_rejected + 1) << b.what;
    EXPECT_EQ(c.scans_matched, before.scans_matched) << b.what;
    const uint32_t flags = r.stack->last_match().measurement.flags;
    EXPECT_NE(flags & mf::kRejected, 0u) << b.what;
    EXPECT_NE(flags & b.reason, 0u) << b.what << " flags " << flags;
    EXPECT_EQ(r.stack->filter().counters().pose_updates, poses) << b.what;
    EXPECT_TRUE(r.nav_finite()) << b.what;
  }
  // The next good scan matches at home again.
  const uint32_t matched = r.stack->counters().scans_matched;
  ASSERT_TRUE(r.laser.scans.queue(r.scan_at(r.clock.now())));
  ASSERT_TRUE(r.run_until_next_scan());
  EXPECT_EQ(r.stack->counters().scans_matched, matched + 1);
  EXPECT_TRUE(r.stack->last_match().ok());
  EXPECT_NEAR(r.stack->last_match().measurement.pose.x, 0.0f, 0.02f);
  EXPECT_NEAR(r.stack->nav().position_m.x(), 0.0f, 0.02f);
  EXPECT_EQ(r.stack->counters().device_errors, 0u);
  EXPECT_GT(r.autopilot.accepted, 0u);
}

// An IMU that glitches (NaN, infinity, a saturated or absurd reading, a stamp going backwards)
// and an autopilot whose attitude report is garbage must not poison the filter: every bad
// sample is read, counted as an IMU error and dropped; the estimate stays finite and the
// commands keep flowing, all flyable (TearDown).
TEST_F(AutonomyStackTest, NonFiniteAndAbsurdImuSamplesAreCountedAsErrorsAndNoNaNReachesTheAutopilot) {
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  ASSERT_TRUE(r.run_until_armed());
  r.run_for(Duration::from_ms(100));
  const StackCounters before = r.stack->counters();
  const uint32_t sends = r.autopilot.accepted;
  const TimeUs now = r.clock.now();
  ImuSample nan_accel = level_imu(now), inf_gyro = level_imu(now), absurd = level_imu(now),
            backwards = level_imu(now - Duration::from_ms(20));
  nan_accel.accel_mps2.x() = kNaN;
  inf_gyro.gyro_radps.z() = -kInf;
  absurd.accel_mps2.z() = 1.0e6f;  // 100 000 g
  for (const ImuSample& s : {nan_accel, inf_gyro, absurd, backwards}) ASSERT_TRUE(r.imu.samples.queue(s));
  // The autopilot's report: NaN roll, then a pitch beyond pi (not an angle).
  r.autopilot.status.roll_rad = kNaN;
  r.run_for(Duration::from_ms(50));
  r.autopilot.status.roll_rad = 0.0f;
  r.autopilot.status.pitch_rad = 7.0f;
  r.run_for(Duration::from_ms(50));
  r.autopilot.status.pitch_rad = 0.0f;
  r.run_for(Duration::from_ms(400));

  const StackCounters& c = r.stack->counters();
  EXPECT_EQ(c.imu_errors, before.imu_errors + 4);
  EXPECT_EQ(c.imu_samples, before.imu_samples + 4 + 100);  // the bad ones are read too
  EXPECT_EQ(c.device_errors, 0u);
  const estimation::NavFilterCounters& f = r.stack->filter().counters();
  EXPECT_EQ(f.imu_not_finite, 2u);
  EXPECT_EQ(f.imu_out_of_range, 1u);
  EXPECT_EQ(f.imu_time_backwards, 1u);
  EXPECT_TRUE(r.nav_finite());
  EXPECT_NEAR(r.stack->nav().position_m.x(), 0.0f, 0.02f);
  EXPECT_NEAR(r.stack->nav().position_m.y(), 0.0f, 0.02f);
  EXPECT_EQ(r.stack->nav().stamp, r.clock.now());  // still current: the good samples went on
  EXPECT_GT(r.autopilot.accepted, sends + 40);     // 500 ms of 100 Hz control
  EXPECT_EQ(c.scans_matched - before.scans_matched, c.scans - before.scans);
}

// ---- Failing devices ----------------------------------------------------------------------

// A driver error (a corrupt frame, an I/O error) is counted and costs that poll only: the next
// poll reads again, and what the device delivers afterwards is consumed as before.
TEST_F(AutonomyStackTest, DeviceErrorsAreCountedAndTheNextPollReadsAgain) {
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  r.run_for(Duration::from_ms(500));
  const StackCounters before = r.stack->counters();
  r.laser.scans.fail_polls = 3;
  r.laser.scans.fail_with = Status::kMalformed;
  r.imu.samples.fail_polls = 2;
  r.imu.samples.fail_with = Status::kIoError;
  r.run_for(Duration::from_ms(500));
  const StackCounters& c = r.stack->counters();
  EXPECT_EQ(c.device_errors, before.device_errors + 5);
  EXPECT_EQ(c.scans, before.scans + 5);  // the errors held nothing back: read later
  EXPECT_EQ(c.imu_samples, before.imu_samples + 100);
  EXPECT_EQ(c.scans_matched, c.scans);
  EXPECT_EQ(c.imu_errors, 0u);
  EXPECT_EQ(r.laser.scans.waiting() + r.imu.samples.waiting(), 0u);
  EXPECT_EQ(r.stack->nav().stamp, r.clock.now());
}

// A laser that is gone (kClosed on every poll) is a device error on every scan-task run, not
// a stalled loop: the IMU is still read, the filter stays current, and the autopilot still
// gets a flyable command every control period.
TEST_F(AutonomyStackTest, ALaserThatIsGoneIsCountedOnEveryPollAndTheLoopRunsOn) {
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  ASSERT_TRUE(r.run_until_armed());
  const StackCounters before = r.stack->counters();
  const uint32_t sends = r.autopilot.accepted;
  r.laser.scans.fail_polls = -1;
  r.laser.scans.fail_with = Status::kClosed;
  r.run_for(Duration::from_s(1.0));
  const StackCounters& c = r.stack->counters();
  EXPECT_EQ(c.device_errors, before.device_errors + 200);  // the scan task runs every 5 ms
  EXPECT_EQ(c.scans, before.scans);
  EXPECT_EQ(c.imu_samples, before.imu_samples + 200);
  EXPECT_EQ(r.stack->nav().stamp, r.clock.now());
  EXPECT_TRUE(r.nav_finite());
  EXPECT_EQ(r.autopilot.accepted, sends + 100);
}

// The autopilot decides whether the motors run: a refused arm is counted and retried every
// control period, and nothing is sent until it is accepted; a refused command is counted and
// not reported as sent.
TEST_F(AutonomyStackTest, AnAutopilotRefusingToArmIsRetriedAndSentNothingUntilItArms) {
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  r.autopilot.arm_result = Status::kIoError;
  r.run_for(Duration::from_s(1.0));  // the mission wants the motors from about 0.3 s
  ASSERT_TRUE(r.stack->mission().wants_armed());
  const uint32_t refusals = r.stack->counters().autopilot_errors;
  EXPECT_GT(refusals, 50u);
  EXPECT_EQ(r.autopilot.arm_calls, refusals);
  EXPECT_EQ(r.autopilot.sends, 0u);
  EXPECT_EQ(r.stack->counters().setpoints_sent, 0u);
  r.run_for(Duration::from_ms(100));
  EXPECT_EQ(r.autopilot.arm_calls, refusals + 10);  // once per 10 ms control period
  r.autopilot.arm_result = Status::kOk;
  r.run_for(Duration::from_ms(100));
  EXPECT_TRUE(r.autopilot.armed);
  EXPECT_EQ(r.autopilot.arm_calls, refusals + 11);  // armed once, not again
  EXPECT_GE(r.autopilot.accepted, 9u);
  EXPECT_EQ(r.stack->counters().setpoints_sent, r.autopilot.accepted);
  // The link drops commands: counted as errors, not as sent.
  const StackCounters before = r.stack->counters();
  r.autopilot.send_result = Status::kTimeout;
  r.run_for(Duration::from_ms(100));
  EXPECT_EQ(r.stack->counters().setpoints_sent, before.setpoints_sent);
  EXPECT_EQ(r.stack->counters().autopilot_errors, before.autopilot_errors + 10);
}

// ---- Silent devices -----------------------------------------------------------------------

// An IMU that falls silent in flight freezes the estimate: the filter's state stays valid and
// finite (and it refuses the scan poses as from the future). Once the IMU task has polled and
// found nothing for sensor_timeouts.imu_s (0.1 s), the controller stops steering on the frozen
// estimate (level, hover thrust) and the mission is told the estimate is stale; its failsafe
// begins estimate_timeout_s (0.5 s) later, and the descent is blind: level, at -0.3 m/s^2 for
// a second, then nearly at hover thrust, so it reaches the floor slowly. Before the watchdog the
// mission flew on the frozen estimate without end (found by this test).
TEST_F(AutonomyStackTest, AnImuThatFallsSilentInFlightLeadsToABlindFailsafeLanding) {
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  ASSERT_TRUE(r.run_until_armed());
  r.run_for(Duration::from_ms(200));
  ASSERT_NE(r.stack->mission().phase(), Phase::kFailsafeLand);
  EXPECT_EQ(r.stack->silences().imu, 0u);
  EXPECT_EQ(r.stack->control_flags() & control::control_flag::kInvalidNav, 0u);
  const float hover = Rig::config().controller.model.thrust.command_for(0.0f);
  r.imu_on = false;
  r.run_for(Duration::from_ms(150));  // stale, the failsafe not yet begun: level at hover thrust
  EXPECT_NE(r.stack->mission().phase(), Phase::kFailsafeLand);
  EXPECT_NE(r.stack->control_flags() & control::control_flag::kInvalidNav, 0u);
  EXPECT_EQ(r.autopilot.last.pitch_rad, 0.0f);
  EXPECT_EQ(r.autopilot.last.roll_rad, 0.0f);
  EXPECT_FLOAT_EQ(r.autopilot.last.thrust, hover);
  r.run_for(Duration::from_ms(400));  // 0.55 s: not yet 0.1 s + 0.5 s
  EXPECT_NE(r.stack->mission().phase(), Phase::kFailsafeLand);
  r.run_for(Duration::from_ms(100));
  EXPECT_TRUE(r.stack->nav().valid);  // the filter's own view: frozen, not invalid
  ASSERT_EQ(r.stack->mission().phase(), Phase::kFailsafeLand) << mission::to_string(r.stack->mission().phase());
  EXPECT_EQ(r.stack->silences().imu, 1u);
  EXPECT_EQ(r.stack->silences().scan, 0u);
  // The commanded descent, flown through the stack's own thrust model (z'' = k thrust + b) from
  // 1 m: level all the way, 0.3 m/s after the first second, and on the floor at 0.3-0.45 m/s
  // before the mission's descent timer ends (at a constant -0.3 m/s^2 it would be 0.77 m/s).
  const control::AxisModel thrust_model = Rig::config().controller.model.thrust;
  float z = 1.0f, vz = 0.0f;
  int steps = 0;
  for (; z > 0.0f && steps < 1000; ++steps) {
    r.run_for(Duration::from_ms(10));
    ASSERT_EQ(r.stack->mission().phase(), Phase::kFailsafeLand) << "landed by the timer at " << z << " m";
    EXPECT_EQ(r.autopilot.last.pitch_rad, 0.0f);
    EXPECT_EQ(r.autopilot.last.roll_rad, 0.0f);
    EXPECT_LT(r.autopilot.last.thrust, hover);
    vz += (thrust_model.k * r.autopilot.last.thrust + thrust_model.b) * 0.01f;
    z += vz * 0.01f;
    if (steps == 99) {
      EXPECT_NEAR(vz, -0.3f, 0.02f);  // one second of -0.3 m/s^2
    }
  }
  EXPECT_LE(z, 0.0f);
  EXPECT_GT(-vz, 0.3f);
  EXPECT_LT(-vz, 0.45f);
}

// A laser that falls silent in flight leaves the filter on the IMU alone, with no position fix.
// The stack tells the mission the estimate is stale once no scan has matched for
// sensor_timeouts.scan_s (0.5 s), and the mission fails safe estimate_timeout_s later. The IMU
// still carries the velocity, so the descent is flown on the estimate, not blind.
TEST_F(AutonomyStackTest, ALaserThatFallsSilentInFlightLeadsToTheFailsafeLanding) {
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  ASSERT_TRUE(r.run_until_armed());
  r.run_for(Duration::from_ms(200));
  r.laser_on = false;
  r.run_for(Duration::from_ms(900));
  EXPECT_NE(r.stack->mission().phase(), Phase::kFailsafeLand);
  r.run_for(Duration::from_ms(300));
  EXPECT_EQ(r.stack->mission().phase(), Phase::kFailsafeLand) << mission::to_string(r.stack->mission().phase());
  EXPECT_EQ(r.stack->silences().scan, 1u);
  EXPECT_EQ(r.stack->silences().imu, 0u);
  r.run_for(Duration::from_ms(50));
  EXPECT_EQ(r.stack->control_flags() & control::control_flag::kInvalidNav, 0u);
}

// A laser that delivers only garbage is as silent as one that delivers nothing: malformed scans
// every 100 ms in flight end in the failsafe landing. One that delivers scans with no return
// within reach (the middle of a large room for the URG-04LX's 4 m) is alive: the vehicle flies
// on the IMU, as it always did there, and the mission goes on.
TEST_F(AutonomyStackTest, OnlyMalformedScansAreASilentLaserAndEmptyScansAreNot) {
  for (const bool garbage : {true, false}) {
    Rig rig;
    ASSERT_EQ(rig.configure_and_start(), Status::kOk);
    ASSERT_TRUE(rig.run_until_armed());
    rig.run_for(Duration::from_ms(200));
    rig.laser_on = false;
    for (int i = 0; i < 15; ++i) {  // 1.5 s
      LaserScan s = garbage ? rig.scan_at(rig.clock.now()) : test::uniform_scan(kUrg, range_code::kNoReturn);
      s.stamp = rig.clock.now();
      if (garbage) s.angle_step_rad = kNaN;
      ASSERT_TRUE(rig.laser.scans.queue(s));
      rig.run_for(Duration::from_ms(100));
    }
    EXPECT_EQ(rig.stack->counters().scans_matched + 15, rig.stack->counters().scans) << garbage;
    EXPECT_EQ(rig.stack->mission().phase() == Phase::kFailsafeLand, garbage)
        << garbage << " " << mission::to_string(rig.stack->mission().phase());
    EXPECT_EQ(rig.stack->silences().scan, garbage ? 1u : 0u);
    EXPECT_EQ(rig.autopilot.unflyable, 0u) << garbage;  // the fixture's check covers r only
  }
}

// A laser that stays silent on the ground keeps the vehicle there: the mission's rest before
// take-off needs the estimate fresh throughout, and starts again when the scans come back.
TEST_F(AutonomyStackTest, ALaserSilentOnTheGroundKeepsTheVehicleOnTheGround) {
  StackConfig c = Rig::config();
  c.mission.preflight_s = 1.0f;
  ASSERT_EQ(r.stack->configure(c), Status::kOk);
  ASSERT_EQ(r.stack->start(), Status::kOk);
  r.run_for(Duration::from_ms(500));
  r.laser_on = false;
  r.run_for(Duration::from_s(5.0));
  EXPECT_EQ(r.stack->mission().phase(), Phase::kIdle) << mission::to_string(r.stack->mission().phase());
  EXPECT_FALSE(r.autopilot.armed);
  EXPECT_EQ(r.stack->silences().scan, 1u);
  r.laser_on = true;
  r.run_for(Duration::from_ms(900));  // the whole rest again
  EXPECT_FALSE(r.autopilot.armed);
  ASSERT_TRUE(r.run_until_armed());
}

// Sensor timeouts are checked with the rest of the configuration.
TEST_F(AutonomyStackTest, SensorTimeoutsOutsideTheirRangeAreRefused) {
  for (const float bad : {0.0f, -1.0f, kNaN, 61.0f}) {
    StackConfig c = Rig::config();
    c.sensor_timeouts.scan_s = bad;
    EXPECT_EQ(r.stack->configure(c), Status::kInvalidArgument) << bad;
    EXPECT_STREQ(r.stack->configure_error(), "sensor timeouts");
    c = Rig::config();
    c.sensor_timeouts.imu_s = bad;
    EXPECT_EQ(r.stack->configure(c), Status::kInvalidArgument) << bad;
  }
  EXPECT_EQ(r.stack->configure(Rig::config()), Status::kOk);
}

// Whatever else a silent device leads to, the loop does not stall or spin on it, nothing is
// counted as an error (silence is kNoData), and the autopilot keeps getting flyable commands
// every control period.
TEST_F(AutonomyStackTest, SilentDevicesStallNothingAndTheCommandsStayFlyable) {
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  ASSERT_TRUE(r.run_until_armed());
  r.run_for(Duration::from_ms(200));
  const StackCounters before = r.stack->counters();
  uint32_t sends = r.autopilot.accepted;
  r.laser_on = false;
  r.run_for(Duration::from_s(1.0));
  EXPECT_EQ(r.stack->counters().scans, before.scans);
  EXPECT_EQ(r.stack->counters().imu_samples, before.imu_samples + 200);
  EXPECT_EQ(r.stack->nav().stamp, r.clock.now());  // the IMU carries the estimate
  EXPECT_EQ(r.autopilot.accepted, sends + 100);
  sends = r.autopilot.accepted;
  r.imu_on = false;
  r.autopilot.report_status = false;
  r.run_for(Duration::from_s(1.0));
  EXPECT_EQ(r.stack->counters().imu_samples, before.imu_samples + 200);
  EXPECT_EQ(r.autopilot.accepted, sends + 100);
  EXPECT_EQ(r.stack->counters().device_errors, 0u);
  EXPECT_EQ(r.stack->counters().imu_errors, 0u);
  EXPECT_TRUE(r.nav_finite());
  // The devices come back: the loop picks them up again.
  r.laser_on = r.imu_on = true;
  r.autopilot.report_status = true;
  r.run_for(Duration::from_ms(500));
  EXPECT_GT(r.stack->counters().scans, before.scans);
  EXPECT_GT(r.stack->counters().imu_samples, before.imu_samples + 200);
  EXPECT_TRUE(r.nav_finite());
}

// ---- Memory -------------------------------------------------------------------------------

// DESIGN.md: no heap after start-up. The whole loop (scan matching, the local map's rebuild,
// the filter, mission, control, the fakes' fixed queues), fed good and malformed input and a
// failing device, allocates nothing.
TEST_F(AutonomyStackTest, TheLoopAllocatesNothingAfterStart) {
  EXPECT_TRUE(alloc_guard::active());
  ASSERT_EQ(r.configure_and_start(), Status::kOk);
  LaserScan bad = r.scan_at(kT0);
  bad.angle_step_rad = kNaN;
  ImuSample nan_imu = level_imu(kT0);
  nan_imu.gyro_radps.x() = kNaN;
  alloc_guard::Scope guard;
  r.run_for(Duration::from_s(1.5));
  (void)r.laser.scans.queue(bad);
  (void)r.imu.samples.queue(nan_imu);
  r.laser.scans.fail_polls = 2;
  r.run_for(Duration::from_s(0.5));
  EXPECT_EQ(guard.allocations(), 0u);
  EXPECT_GT(r.stack->counters().scans_matched, 10u);
  EXPECT_GT(r.autopilot.accepted, 0u);
  EXPECT_EQ(r.stack->counters().scans_rejected, 1u);
}

TEST(VehicleEkfParams, AShortReachLaserGetsTheQuieterAccelerometerModel) {
  const estimation::EkfParams defaults;
  // URG-04LX (4 m): the quieter model; UTM-30LX (30 m) and an unknown reach: the defaults.
  EXPECT_EQ(vehicle_ekf_params(4000).accel_noise_xy, kShortReachAccelNoiseXy);
  EXPECT_LT(kShortReachAccelNoiseXy, defaults.accel_noise_xy);
  EXPECT_EQ(vehicle_ekf_params(30000).accel_noise_xy, defaults.accel_noise_xy);
  EXPECT_EQ(vehicle_ekf_params(0).accel_noise_xy, defaults.accel_noise_xy);
  // Nothing else differs, and the result is a valid parameter set.
  estimation::EkfParams p = vehicle_ekf_params(4000);
  EXPECT_EQ(estimation::validate(p), Status::kOk);
  p.accel_noise_xy = defaults.accel_noise_xy;
  EXPECT_EQ(std::memcmp(&p, &defaults, sizeof p), 0);
}

}  // namespace
}  // namespace kestrel::autonomy
