// The Hokuyo driver against a scanner simulated on the far end of a pseudo-terminal, speaking
// SCIP 2.0 as the real URG-04LX does.
#include "kestrel/platform/linux/hokuyo_scip.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>

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
  for (uint32_t t : {100u, 200u}) {
    const std::size_t n = comms::scip_encode_md_scan(44, 725, t, ranges, 682, wire, sizeof(wire));
    write_all(pty.device, wire, n);
  }
  static LaserScan a, b;
  int scans = 0;
  for (int i = 0; i < 200 && scans < 2; ++i) {
    (void)pty.port.wait_readable(Duration::from_ms(10));
    ASSERT_EQ(laser.pump(), Status::kOk);
    if (laser.poll(scans == 0 ? a : b) == Status::kOk) ++scans;
  }
  ASSERT_GE(scans, 1);
  EXPECT_EQ(a.beam_count, 682);
  EXPECT_EQ(a.range_mm[0], 1000);
  EXPECT_EQ(a.range_mm[5], range_code::kNoReturn);
  EXPECT_NEAR(a.first_angle_rad, -340.0 * 2 * M_PI / 1024, 1e-5);
  if (scans == 2) {
    EXPECT_EQ((b.stamp - a.stamp).us, 100'000);  // sensor clock spacing, not arrival jitter
  }
  EXPECT_EQ(laser.decoder().sum_errors(), 0u);
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
