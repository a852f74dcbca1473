// The Hokuyo driver against a scanner simulated on the far end of a pseudo-terminal, speaking
// SCIP 2.0 as the real URG-04LX does.
#include "kestrel/platform/linux/hokuyo_scip.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "kestrel/platform/linux/linux_clock.hpp"
#include "kestrel/platform/linux/serial_port.hpp"
#include "endless_link.hpp"

namespace kestrel::platform {
namespace {

struct PtyPair {
  FdLink device;  // the scanner's end
  SerialPort port;
  PtyPair() {
    const int master = posix_openpt(O_RDWR | O_NOCTTY);
    EXPECT_GE(master, 0);
    EXPECT_EQ(grantpt(master), 0);
    EXPECT_EQ(unlockpt(master), 0);
    EXPECT_EQ(set_nonblocking(master), Status::kOk);
    device = FdLink(master);
    EXPECT_EQ(port.open(ptsname(master), 115200), Status::kOk);
  }
};

void write_all(FdLink& link, const uint8_t* p, std::size_t n) {
  std::size_t sent = 0;
  for (int i = 0; i < 1000 && sent < n; ++i) {
    const Result<std::size_t> w = link.write(p + sent, n - sent);
    ASSERT_TRUE(w.ok());
    sent += w.value();
  }
  ASSERT_EQ(sent, n);
}

TEST(HokuyoModel, GeometryOfTheUrg04lxAndUtm30lx) {
  const hal::LaserGeometry urg = HokuyoModel::urg04lx().geometry();
  EXPECT_EQ(urg.beam_count, 682);
  EXPECT_NEAR(urg.first_angle_rad, -340.0 * 2 * M_PI / 1024, 1e-5);
  EXPECT_NEAR(urg.angle_step_rad * urg.beam_count, 239.77 * M_PI / 180, 1e-3);  // the datasheet's field
  const hal::LaserGeometry utm = HokuyoModel::utm30lx().geometry();
  EXPECT_EQ(utm.beam_count, 1081);
  EXPECT_NEAR(utm.first_angle_rad, -135.0 * M_PI / 180, 1e-5);
}

TEST(HokuyoScip, RequestsScansAndDecodesThem) {
  PtyPair pty;
  LinuxClock clock;
  HokuyoScip laser(pty.port, clock, HokuyoModel::urg04lx());
  ASSERT_EQ(laser.start(), Status::kOk);
  char req[32] = {};
  std::size_t got = 0;
  for (int i = 0; i < 100 && got < 16; ++i) {
    (void)pty.device.wait_readable(Duration::from_ms(10));
    const Result<std::size_t> r = pty.device.read(reinterpret_cast<uint8_t*>(req) + got, 16 - got);
    ASSERT_TRUE(r.ok());
    got += r.value();
  }
  EXPECT_EQ(std::string(req, 16), "MD0044072501000\n");

  static uint16_t ranges[682];
  for (int i = 0; i < 682; ++i) ranges[i] = static_cast<uint16_t>(i == 5 ? 0 : 1000 + i);
  static uint8_t wire[4096];
  // One scan at a time: poll() hands out only the newest, so two written at once would be one.
  static LaserScan scans[2];
  for (int k = 0; k < 2; ++k) {
    const std::size_t n = comms::scip_encode_md_scan(44, 725, 100u * (k + 1), ranges, 682, wire, sizeof(wire));
    write_all(pty.device, wire, n);
    bool got_scan = false;
    for (int i = 0; i < 200 && !got_scan; ++i) {
      (void)pty.port.wait_readable(Duration::from_ms(10));
      ASSERT_EQ(laser.pump(), Status::kOk);
      got_scan = laser.poll(scans[k]) == Status::kOk;
    }
    ASSERT_TRUE(got_scan) << "scan " << k;
  }
  const LaserScan& a = scans[0];
  EXPECT_EQ(a.beam_count, 682);
  EXPECT_EQ(a.range_mm[0], 1000);
  EXPECT_EQ(a.range_mm[5], range_code::kNoReturn);
  EXPECT_NEAR(a.first_angle_rad, -340.0 * 2 * M_PI / 1024, 1e-5);
  EXPECT_GT(scans[1].stamp, a.stamp);
  EXPECT_EQ(laser.decoder().sum_errors(), 0u);
}

// Bytes a test queues, read as they were queued: scans delivered when the test says, at the
// time its manual clock says.
class QueuedLink final : public hal::Link {
 public:
  Result<std::size_t> write(const uint8_t*, std::size_t size) override { return size; }
  Result<std::size_t> read(uint8_t* out, std::size_t capacity) override {
    const std::size_t n = std::min(capacity, size_ - read_);
    std::memcpy(out, bytes_ + read_, n);
    read_ += n;
    return n;
  }
  void queue_scan(uint32_t sensor_ms) {
    static uint16_t ranges[682];
    for (uint16_t& r : ranges) r = 1500;
    const std::size_t n = comms::scip_encode_md_scan(44, 725, sensor_ms, ranges, 682, bytes_ + size_,
                                                     sizeof(bytes_) - size_);
    ASSERT_GT(n, 0u);
    size_ += n;
  }

 private:
  uint8_t bytes_[16384] = {};
  std::size_t size_ = 0, read_ = 0;
};

struct ScriptedScanner {
  QueuedLink link;
  ManualTimeSource clock{TimeUs{5'000'000}};
  HokuyoScip laser{link, clock, HokuyoModel::urg04lx()};
  LaserScan scan;
  // The scan stamped `sensor_ms` on the scanner's clock, arriving `arrival_ms` on the board's.
  TimeUs deliver(uint32_t sensor_ms, int64_t arrival_ms) {
    link.queue_scan(sensor_ms);
    clock.set(TimeUs{arrival_ms * 1000});
    EXPECT_EQ(laser.pump(), Status::kOk);
    EXPECT_EQ(laser.poll(scan), Status::kOk);
    return scan.stamp;
  }
};

// A scan that arrives late keeps the scanner's own spacing; a quicker one moves the offset down
// by the delay it saved, and no further.
TEST(HokuyoScip, StampsKeepTheScannersSpacingThroughLateArrivals) {
  static ScriptedScanner s;
  const TimeUs a = s.deliver(100, 5'000);
  const TimeUs b = s.deliver(200, 5'104);  // 4 ms late
  const TimeUs c = s.deliver(300, 5'198);  // 2 ms quicker than the first
  EXPECT_EQ(a.us, 5'000'000);
  // Within the offset's drift allowance (DeviceClock::kDriftAllowancePpm: 21 us over 104 ms).
  EXPECT_NEAR((b - a).us, 100'000, 25);
  EXPECT_NEAR((c - b).us, 98'000, 25);
}

// The board's clock read the same for two scans (a drained backlog in one tick, a coarse clock):
// each was the quickest yet, so both map to that one time. The stack must still see the later
// scan after the earlier one: a scan at the same time is taken as from the past.
TEST(HokuyoScip, AScanMappedOntoThePreviousOnesTimeIsHandedOnAfterIt) {
  static ScriptedScanner s;
  const TimeUs a = s.deliver(100, 5'000);
  const TimeUs b = s.deliver(300, 5'000);
  EXPECT_GT(b, a);
  EXPECT_LT((b - a).us, 1'000);
}

// pump() returns after a bounded amount of an endless stream, and the loop gets its tick.
TEST(HokuyoScip, PumpReturnsWhileTheDeviceFloods) {
  test::EndlessLink link('x');
  ManualTimeSource clock;
  static HokuyoScip laser(link, clock, HokuyoModel::urg04lx());
  EXPECT_EQ(laser.pump(), Status::kOk);
  EXPECT_LT(link.reads, 1000);  // 51.2 MB read before returning, without the bound
}

}  // namespace
}  // namespace kestrel::platform
