#pragma once
// The vehicle's sensors and autopilot reached through the HIL link (modules/comms framing) over
// any byte Link: TCP to the simulator's bridge for hardware-in-the-loop runs, or a serial port
// to an autopilot-side bridge that speaks the same framing. One object implements all four
// HAL devices, because one stream carries them all; pump() moves bytes into small fixed
// queues, and each device's poll reads its own queue.
//
// Time: the far end stamps every frame on its own clock (the simulator's starts at zero, an
// autopilot's at its boot). The stack compares stamps with the board's clock (a scan's age on
// the way home, a measurement from the future), so every stamp is mapped onto the board's
// clock through one DeviceClock for the link (core/device_clock.hpp), as the Hokuyo driver
// does its sensor's. Unmapped, a simulator's scans looked hours old to kestrel-fw, whose
// flight home then held still until it stalled and landed where it was. Each stream keeps the
// peer's order through the mapping, whose offset may fall between two reads (StreamStamps).
#include <array>
#include <cstddef>
#include <cstdint>

#include "kestrel/comms/hil_codec.hpp"
#include "kestrel/core/device_clock.hpp"
#include "kestrel/core/ring_buffer.hpp"
#include "kestrel/core/stream_stamps.hpp"
#include "kestrel/hal/altimeter.hpp"
#include "kestrel/hal/flight_controller.hpp"
#include "kestrel/hal/imu.hpp"
#include "kestrel/hal/laser_scanner.hpp"
#include "kestrel/hal/link.hpp"

namespace kestrel::platform {

struct HilCounters {
  uint32_t frames = 0;
  uint32_t malformed = 0;          // frames whose payload did not decode
  uint32_t bad_stamps = 0;         // frames dropped for a stamp DeviceClock refused
  uint32_t unknown_type = 0;
  uint32_t crc_errors = 0;         // frames dropped by their CRC or an impossible length
  uint32_t skipped_bytes = 0;      // outside any frame: noise, a damaged sync, a bad length's rest
  uint32_t dropped_imu = 0;        // IMU queue full: the loop fell behind
  uint32_t overwritten_scans = 0;  // a scan replaced one that was never read
  uint32_t write_failures = 0;
};

class HilClient final : public hal::LaserScanner, public hal::Imu, public hal::Altimeter, public hal::FlightController {
 public:
  // `clock` is the board's: what the stamps are mapped onto, read as frames arrive.
  HilClient(hal::Link& link, const TimeSource& clock, const hal::LaserGeometry& geometry, Duration imu_period)
      : link_(link), clock_(clock), geometry_(geometry), imu_period_(imu_period) {}

  // Most bytes one pump() reads: the link's traffic (a 1081-beam scan at 40 Hz and the IMU,
  // about 100 KB/s) is a few hundred bytes per loop tick, so this drains any backlog within a
  // few calls, yet a peer that floods the link cannot hold the loop in pump().
  static constexpr std::size_t kMaxPumpBytes = 16384;

  // Reads what the link has (up to kMaxPumpBytes) and decodes it. kClosed when the peer has
  // gone away.
  Status pump();

  // hal::LaserScanner
  hal::LaserGeometry geometry() const override { return geometry_; }
  Status poll(LaserScan& out) override;
  // hal::Imu
  Duration sample_period() const override { return imu_period_; }
  Status poll(ImuSample& out) override;
  // hal::Altimeter
  Status poll(AltimeterSample& out) override;
  // hal::FlightController
  Status arm(bool armed) override;
  Status send(const AttitudeSetpoint& setpoint) override;
  Status poll_status(FlightStatus& out) override;

  const HilCounters& counters() const { return counters_; }

 private:
  Status write_frame(uint8_t type, const uint8_t* payload, std::size_t size);
  void dispatch(TimeUs arrival);

  hal::Link& link_;
  const TimeSource& clock_;
  DeviceClock peer_clock_;
  // Each stream's own order kept through the mapping (core/stream_stamps.hpp).
  StreamStamps imu_stamps_, scan_stamps_, altitude_stamps_, status_stamps_;
  hal::LaserGeometry geometry_;
  Duration imu_period_;
  comms::HilDecoder decoder_;
  RingBuffer<ImuSample, 64> imu_queue_;
  RingBuffer<AltimeterSample, 8> altitude_queue_;
  // Two slots: a frame is decoded into the one not holding the newest good scan, and becomes
  // the newest only once it passes, so a dropped frame cannot wipe a scan not yet read (a
  // LaserScan is 3 KB: too large for the loop's stack).
  std::array<LaserScan, 2> scans_{};
  std::size_t newest_ = 0;
  bool scan_fresh_ = false;
  FlightStatus status_;
  bool status_fresh_ = false;
  HilCounters counters_;
};

}  // namespace kestrel::platform
