#pragma once
// hal::LaserScanner for a Hokuyo URG-04LX or UTM-30LX on a serial (USB-ACM) Link, speaking
// SCIP 2.0 (modules/comms/scip): start() requests continuous scanning (MD), pump() decodes
// the stream, poll() hands out the newest complete scan.
//
// Time: the scanner stamps each scan with its own millisecond clock. The offset to the host's
// clock is estimated as the smallest (arrival - sensor time) seen, i.e. the arrival with the
// least transfer delay, so scan stamps track the sensor's clock without the jitter of USB
// arrival times. The stamp of beam 0 is then derived from the step geometry.
#include <cstddef>
#include <cstdint>

#include "kestrel/comms/scip.hpp"
#include "kestrel/core/device_clock.hpp"
#include "kestrel/core/stream_stamps.hpp"
#include "kestrel/core/time.hpp"
#include "kestrel/hal/laser_scanner.hpp"
#include "kestrel/hal/link.hpp"

namespace kestrel::platform {

struct HokuyoModel {
  uint16_t first_step;     // first step of the measurement range
  uint16_t last_step;
  uint16_t front_step;     // step pointing along the sensor's x axis
  uint16_t steps_per_rev;  // angular resolution
  uint16_t min_range_mm;
  uint16_t max_range_mm;
  Duration scan_period;

  static HokuyoModel urg04lx() { return {44, 725, 384, 1024, 20, 4000, Duration::from_ms(100)}; }
  static HokuyoModel utm30lx() { return {0, 1080, 540, 1440, 100, 30000, Duration::from_ms(25)}; }
  hal::LaserGeometry geometry() const;
};

class HokuyoScip final : public hal::LaserScanner {
 public:
  HokuyoScip(hal::Link& link, const TimeSource& clock, const HokuyoModel& model)
      : link_(link), clock_(clock), model_(model) {}

  // Sends the MD request (continuous scans of the whole range).
  Status start();
  // Most bytes one pump() reads: a UTM-30LX sends about 130 KB/s (3.3 KB a scan at 40 Hz), a few
  // hundred bytes per loop tick, so this drains a backlog within a few calls, yet a device
  // that floods the line cannot hold the loop in pump().
  static constexpr std::size_t kMaxPumpBytes = 16384;

  // Reads and decodes what the link has (up to kMaxPumpBytes). kClosed if the device went away.
  Status pump();

  hal::LaserGeometry geometry() const override { return model_.geometry(); }
  Status poll(LaserScan& out) override;

  const comms::ScipDecoder& decoder() const { return decoder_; }

 private:
  void convert(TimeUs arrival);

  hal::Link& link_;
  const TimeSource& clock_;
  HokuyoModel model_;
  comms::ScipDecoder decoder_;
  LaserScan scan_;
  bool fresh_ = false;
  DeviceClock sensor_clock_;  // core/device_clock.hpp
  // Mapped as it arrives, a scan never maps before the previous one, but onto its time when the
  // board's clock read the same for both (each the quickest yet): this hands it on after it.
  StreamStamps scan_stamps_;
  uint32_t last_sensor_ms_ = 0;
  int64_t unwrapped_ms_ = 0;
};

}  // namespace kestrel::platform
