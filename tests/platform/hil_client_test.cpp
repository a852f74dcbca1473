// The HIL client against a peer that speaks the framing by hand, over a loopback TCP pair.
#include "kestrel/platform/linux/hil_client.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "kestrel/comms/hil_messages.hpp"
#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/platform/linux/tcp_link.hpp"
#include "endless_link.hpp"

namespace kestrel::platform {
namespace {

using comms::HilType;

// The board's clock, far from the peer's zero (a board up for an hour).
ManualTimeSource board_clock{TimeUs::from_s(3600)};

struct Pair {
  TcpLink client, server;
  Pair() {
    TcpListener l;
    EXPECT_EQ(l.listen("127.0.0.1", 0), Status::kOk);
    EXPECT_EQ(client.connect("127.0.0.1", l.port(), Duration::from_ms(1000)), Status::kOk);
    EXPECT_EQ(l.accept(server, Duration::from_ms(1000)), Status::kOk);
  }
};

template <class Msg>
void send_msg(TcpLink& link, HilType type, const Msg& m) {
  static uint8_t payload[comms::kHilMaxPayload], frame[comms::kHilMaxPayload + comms::kHilOverhead];
  const std::size_t p = comms::encode_payload(m, payload, sizeof(payload));
  const std::size_t f = comms::hil_encode(static_cast<uint8_t>(type), payload, p, frame, sizeof(frame));
  std::size_t sent = 0;
  while (sent < f) {
    const Result<std::size_t> w = link.write(frame + sent, f - sent);
    ASSERT_TRUE(w.ok());
    sent += w.value();
  }
}

// Pumps until `done` holds or a second passes.
template <class Pred>
bool pump_until(HilClient& c, TcpLink& link, Pred done) {
  for (int i = 0; i < 100; ++i) {
    (void)link.wait_readable(Duration::from_ms(10));
    if (c.pump() != Status::kOk) return false;
    if (done()) return true;
  }
  return false;
}

// Each message through the device interface by which it reaches the stack.
Status take(HilClient& c, ImuSample& s) { return c.poll(s); }
Status take(HilClient& c, LaserScan& s) { return static_cast<hal::LaserScanner&>(c).poll(s); }
Status take(HilClient& c, FlightStatus& s) { return c.poll_status(s); }

// The board's hour in StampsAreMappedOntoTheBoardsClock, and how far a stamp mapped onto it may
// be off: DeviceClock's drift allowance leaks 200 ppm of the board time between frames, 2 us
// over that test's 10 ms.
constexpr TimeUs kBoardHour = TimeUs::from_s(3600);
constexpr double kLeakMs = 0.003;

// The peer sends `m`; the client is pumped until it hands over a message of that kind. The
// stamp that came with it, in milliseconds past the board's hour (NaN: none came).
template <class Msg>
double delivered_ms(HilClient& hil, Pair& pair, HilType type, const Msg& m) {
  send_msg(pair.server, type, m);
  static Msg got;  // a scan is 2 kB: off the stack, as the tests keep theirs
  if (!pump_until(hil, pair.client, [&] { return take(hil, got) == Status::kOk; })) return std::nan("");
  return static_cast<double>((got.stamp - kBoardHour).us) / 1000.0;
}

TEST(HilClient, DeliversSensorFramesToTheRightDevice) {
  Pair pair;
  hal::LaserGeometry g;
  g.beam_count = 1081;
  static HilClient hil(pair.client, board_clock, g, Duration::from_ms(5));
  for (int i = 0; i < 3; ++i) {
    ImuSample s;
    s.stamp = TimeUs::from_us(1000 * i);
    s.accel_mps2.z() = 9.8f;
    send_msg(pair.server, HilType::kImu, s);
  }
  static LaserScan scan;
  scan.stamp = TimeUs::from_us(2500);
  scan.beam_count = 1081;
  scan.range_mm[1080] = 777;
  send_msg(pair.server, HilType::kLaserScan, scan);
  FlightStatus st;
  st.armed = true;
  send_msg(pair.server, HilType::kFlightStatus, st);

  int imu_count = 0;
  ImuSample s;
  static LaserScan got;
  bool have_scan = false, have_status = false;
  ASSERT_TRUE(pump_until(hil, pair.client, [&] {
    while (hil.poll(s) == Status::kOk) ++imu_count;
    if (static_cast<hal::LaserScanner&>(hil).poll(got) == Status::kOk) have_scan = true;
    FlightStatus fs;
    if (hil.poll_status(fs) == Status::kOk) have_status = fs.armed;
    return imu_count == 3 && have_scan && have_status;
  }));
  EXPECT_EQ(got.range_mm[1080], 777);
  EXPECT_EQ(static_cast<hal::LaserScanner&>(hil).poll(got), Status::kNoData);  // each scan is read once
  EXPECT_EQ(hil.counters().malformed, 0u);
}

// The peer's stamps (the simulator's clock starts at zero) reach the stack on the board's
// clock, keeping their own spacing: a backlog that arrives at once is not closed up onto its
// last frame, and a later, quicker frame moves them by no more than its saved delay.
TEST(HilClient, StampsAreMappedOntoTheBoardsClock) {
  Pair pair;
  ManualTimeSource board{kBoardHour};
  HilClient hil(pair.client, board, {}, Duration::from_ms(5));
  for (int i = 0; i < 4; ++i) {  // 20 ms of IMU samples, stamped 10-25 ms on the peer's clock
    ImuSample s;
    s.stamp = TimeUs::from_us(10'000 + 5'000 * i);
    send_msg(pair.server, HilType::kImu, s);
  }
  AltimeterSample a;
  a.stamp = TimeUs::from_us(20'000);
  send_msg(pair.server, HilType::kAltitude, a);
  std::vector<ImuSample> got;
  bool have_alt = false;
  AltimeterSample alt;
  ASSERT_TRUE(pump_until(hil, pair.client, [&] {
    ImuSample s;
    while (hil.poll(s) == Status::kOk) got.push_back(s);
    if (hil.poll(alt) == Status::kOk) have_alt = true;
    return got.size() == 4 && have_alt;
  }));
  // All arrived at 3600 s on the board (its clock stood still): the newest frame, 25 ms, had
  // the least delay, so it maps to 3600 s and the others keep their 5 ms spacing before it.
  for (int i = 0; i < 4; ++i) EXPECT_EQ(got[i].stamp, kBoardHour - Duration::from_ms(15 - 5 * i)) << i;
  EXPECT_EQ(alt.stamp, kBoardHour - Duration::from_ms(5));
  // A scan stamped 30 ms arriving 10 ms of board time later: 5 ms later than its stamp says,
  // so the offset stands and the scan is 5 ms old.
  board.advance(Duration::from_ms(10));
  static LaserScan scan;
  scan.stamp = TimeUs::from_us(30'000);
  scan.beam_count = 1;
  EXPECT_NEAR(delivered_ms(hil, pair, HilType::kLaserScan, scan), 5.0, kLeakMs);
  FlightStatus st;
  st.stamp = TimeUs::from_us(31'000);
  EXPECT_NEAR(delivered_ms(hil, pair, HilType::kFlightStatus, st), 6.0, kLeakMs);
  // A quicker frame: stamped 40 ms, arriving at its own stamp's board time less 2 ms of the
  // delay all the others had. It moves the stamps by that saved delay and no more.
  board.set(kBoardHour + Duration::from_ms(13));
  ImuSample quick;
  quick.stamp = TimeUs::from_us(40'000);
  EXPECT_NEAR(delivered_ms(hil, pair, HilType::kImu, quick), 13.0, kLeakMs);
  // A stamp an hour ahead (damaged, yet through its CRC): dropped and counted, the offset kept.
  board.advance(Duration::from_ms(5));
  ImuSample wild;
  wild.stamp = TimeUs::from_s(3600 + 3600);
  send_msg(pair.server, HilType::kImu, wild);
  ImuSample next;
  next.stamp = TimeUs::from_us(45'000);
  EXPECT_NEAR(delivered_ms(hil, pair, HilType::kImu, next), 18.0, kLeakMs);
  EXPECT_EQ(hil.counters().bad_stamps, 1u);
}

// Regression (hil_hover with the CPU short): IMU samples queued while a late frame set the
// offset, then read out after a quicker frame lowered it by more than their spacing, were
// handed on before the sample read just before them, and the filter dropped them as time
// running backwards. Pinned: the queue is read out in the peer's order on the board's clock.
TEST(HilClient, QueuedSamplesStayInOrderWhenAQuickerFrameLowersTheOffset) {
  Pair pair;
  ManualTimeSource board{kBoardHour + Duration::from_ms(50)};
  HilClient hil(pair.client, board, {}, Duration::from_ms(5));
  for (int i = 0; i < 3; ++i) {  // stamped 0, 5, 10 ms, all arriving 50 ms past the hour
    ImuSample s;
    s.stamp = TimeUs::from_us(5000 * i);
    send_msg(pair.server, HilType::kImu, s);
  }
  AltimeterSample alt;  // and an altitude stamped 10 ms
  alt.stamp = TimeUs::from_us(10'000);
  send_msg(pair.server, HilType::kAltitude, alt);
  ASSERT_TRUE(pump_until(hil, pair.client, [&] { return hil.counters().frames == 4; }));
  ImuSample first;
  ASSERT_EQ(hil.poll(first), Status::kOk);
  EXPECT_EQ(first.stamp, kBoardHour + Duration::from_ms(40));
  // Stamped 45 ms, arriving 51 ms past the hour: 34 ms quicker than the frames before it.
  board.set(kBoardHour + Duration::from_ms(51));
  ImuSample quick;
  quick.stamp = TimeUs::from_us(45'000);
  send_msg(pair.server, HilType::kImu, quick);
  ASSERT_TRUE(pump_until(hil, pair.client, [&] { return hil.counters().frames == 5; }));
  // Each stream keeps its own order: the altitude, the first of its stream, is mapped as it is
  // (16 ms past the hour), and the IMU's next sample still comes after the IMU's first.
  ASSERT_EQ(hil.poll(alt), Status::kOk);
  EXPECT_NEAR(static_cast<double>((alt.stamp - kBoardHour).us), 16'000.0, 5.0);
  TimeUs last = first.stamp;
  for (int i = 0; i < 3; ++i) {
    ImuSample s;
    ASSERT_EQ(hil.poll(s), Status::kOk);
    EXPECT_GT(s.stamp, last) << i;
    last = s.stamp;
  }
  EXPECT_NEAR(static_cast<double>((last - kBoardHour).us), 51'000.0, 5.0);  // back on the mapping
  EXPECT_EQ(hil.counters().bad_stamps, 0u);
}

TEST(HilClient, SendsSetpointsAndArmCommands) {
  Pair pair;
  HilClient hil(pair.client, board_clock, {}, Duration::from_ms(5));
  ASSERT_EQ(hil.arm(true), Status::kOk);
  AttitudeSetpoint sp;
  sp.thrust = 0.55f;
  sp.pitch_rad = -0.1f;
  ASSERT_EQ(hil.send(sp), Status::kOk);
  comms::HilDecoder d;
  int frames = 0;
  bool armed = false;
  AttitudeSetpoint out;
  uint8_t buf[256];
  for (int i = 0; i < 100 && frames < 2; ++i) {
    (void)pair.server.wait_readable(Duration::from_ms(10));
    const Result<std::size_t> r = pair.server.read(buf, sizeof(buf));
    ASSERT_TRUE(r.ok());
    for (std::size_t k = 0; k < r.value(); ++k) {
      if (!d.push(buf[k])) continue;
      ++frames;
      if (d.type() == static_cast<uint8_t>(HilType::kArm)) {
        ASSERT_EQ(comms::decode_arm(d.payload(), d.size(), armed), Status::kOk);
      } else {
        ASSERT_EQ(comms::decode_payload(d.payload(), d.size(), out), Status::kOk);
      }
    }
  }
  EXPECT_EQ(frames, 2);
  EXPECT_TRUE(armed);
  EXPECT_FLOAT_EQ(out.thrust, 0.55f);
  EXPECT_FLOAT_EQ(out.pitch_rad, -0.1f);
}

// A status frame that is dropped (a NaN inside, or a stamp DeviceClock refuses) must not touch
// the one the stack has not read yet: the autopilot's last good word is what poll_status gives.
TEST(HilClient, DroppedStatusFrameLeavesTheUnreadOneIntact) {
  Pair pair;
  HilClient hil(pair.client, board_clock, {}, Duration::from_ms(5));
  FlightStatus good;
  good.stamp = TimeUs::from_us(1000);
  good.armed = true;
  good.battery_v = 11.1f;
  good.roll_rad = 0.1f;
  send_msg(pair.server, HilType::kFlightStatus, good);
  FlightStatus nan_roll = good;
  nan_roll.stamp = TimeUs::from_us(2000);
  nan_roll.armed = false;
  nan_roll.roll_rad = std::nanf("");
  send_msg(pair.server, HilType::kFlightStatus, nan_roll);
  FlightStatus far_ahead = good;
  far_ahead.stamp = TimeUs::from_s(7200);  // an hour past the first: refused
  far_ahead.armed = false;
  far_ahead.battery_v = 3.0f;
  send_msg(pair.server, HilType::kFlightStatus, far_ahead);
  ASSERT_TRUE(pump_until(hil, pair.client, [&] { return hil.counters().frames == 3; }));
  EXPECT_EQ(hil.counters().malformed, 1u);
  EXPECT_EQ(hil.counters().bad_stamps, 1u);
  FlightStatus got;
  ASSERT_EQ(hil.poll_status(got), Status::kOk);
  EXPECT_TRUE(got.armed);
  EXPECT_FLOAT_EQ(got.battery_v, 11.1f);
  EXPECT_FLOAT_EQ(got.roll_rad, 0.1f);
  EXPECT_EQ(got.stamp, board_clock.now());  // the good frame's own stamp, mapped
  EXPECT_EQ(hil.poll_status(got), Status::kNoData);
}

// The same for scans: a scan frame dropped (its timing outside its domain, or a stamp refused)
// leaves the good one not yet read, and is not counted as overwriting it; a good one is.
TEST(HilClient, DroppedScanFrameLeavesTheUnreadOneIntact) {
  Pair pair;
  static HilClient hil(pair.client, board_clock, {}, Duration::from_ms(5));
  static LaserScan good;
  good.stamp = TimeUs::from_us(1000);
  good.beam_count = 3;
  good.range_mm[2] = 777;
  send_msg(pair.server, HilType::kLaserScan, good);
  static LaserScan bad;
  bad = good;
  bad.stamp = TimeUs::from_us(2000);
  bad.range_mm[2] = 111;
  bad.beam_interval = Duration::from_us(-1);  // no such sweep
  send_msg(pair.server, HilType::kLaserScan, bad);
  bad.beam_interval = {};
  bad.stamp = TimeUs::from_s(7200);  // an hour past the first: refused
  send_msg(pair.server, HilType::kLaserScan, bad);
  ASSERT_TRUE(pump_until(hil, pair.client, [&] { return hil.counters().frames == 3; }));
  EXPECT_EQ(hil.counters().malformed, 1u);
  EXPECT_EQ(hil.counters().bad_stamps, 1u);
  EXPECT_EQ(hil.counters().overwritten_scans, 0u);
  static LaserScan got;
  ASSERT_EQ(take(hil, got), Status::kOk);
  EXPECT_EQ(got.range_mm[2], 777);
  EXPECT_EQ(got.stamp, board_clock.now());  // the good frame's own stamp, mapped
  EXPECT_EQ(take(hil, got), Status::kNoData);

  good.stamp = TimeUs::from_us(3000);
  send_msg(pair.server, HilType::kLaserScan, good);
  good.stamp = TimeUs::from_us(4000);
  good.range_mm[2] = 888;
  send_msg(pair.server, HilType::kLaserScan, good);
  ASSERT_TRUE(pump_until(hil, pair.client, [&] { return hil.counters().frames == 5; }));
  EXPECT_EQ(hil.counters().overwritten_scans, 1u);
  ASSERT_EQ(take(hil, got), Status::kOk);
  EXPECT_EQ(got.range_mm[2], 888);
}

// pump() returns after a bounded amount of an endless stream, and the loop gets its tick.
TEST(HilClient, PumpReturnsWhileThePeerFloods) {
  static test::EndlessLink link(0x00);  // no sync byte: all skipped
  static HilClient hil(link, board_clock, {}, Duration::from_ms(5));
  EXPECT_EQ(hil.pump(), Status::kOk);
  EXPECT_LT(link.reads, 1000);  // 51.2 MB read before returning, without the bound
  EXPECT_EQ(hil.counters().skipped_bytes, static_cast<uint32_t>(link.reads * 512));
}

TEST(HilClient, PeerGoneIsReportedAndGarbageCounted) {
  Pair pair;
  HilClient hil(pair.client, board_clock, {}, Duration::from_ms(5));
  const uint8_t junk[] = {0xA5, 0x5A, 99, 1, 0, 7, 0x12, 0x34};  // unknown type, bad CRC
  const uint8_t noise[] = {0x00, 0xA5, 0x13};                    // no frame starts in it
  ASSERT_TRUE(pair.server.write(junk, sizeof(junk)).ok());
  ASSERT_TRUE(pair.server.write(noise, sizeof(noise)).ok());
  for (int i = 0; i < 10 && hil.counters().skipped_bytes < sizeof(noise); ++i) {
    (void)pair.client.wait_readable(Duration::from_ms(100));
    EXPECT_EQ(hil.pump(), Status::kOk);
  }
  EXPECT_EQ(hil.counters().crc_errors, 1u);
  EXPECT_EQ(hil.counters().skipped_bytes, sizeof(noise));
  pair.server.close();
  (void)pair.client.wait_readable(Duration::from_ms(500));
  EXPECT_EQ(hil.pump(), Status::kClosed);
}

}  // namespace
}  // namespace kestrel::platform
