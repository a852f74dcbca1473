#pragma once
// A 2D scanning laser range finder (Hokuyo UTM-30LX, URG-04LX, a log replay, the simulator).
#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel::hal {

// What a scanner reports about itself before the first scan.
struct LaserGeometry {
  uint16_t beam_count = 0;       // beams per scan, at most kMaxBeams
  float first_angle_rad = 0;     // angle of beam 0, counter-clockwise from the sensor's x axis
  float angle_step_rad = 0;      // angle between consecutive beams
  uint16_t min_range_mm = 0;
  uint16_t max_range_mm = 0;
  Duration scan_period;          // one mirror revolution
};

class LaserScanner {
 public:
  virtual LaserGeometry geometry() const = 0;
  // Copies the newest complete scan not yet read into `out`: kOk, or kNoData when none is
  // waiting, or an error (kMalformed for a corrupt frame, kClosed when the device is gone).
  virtual Status poll(LaserScan& out) = 0;

 protected:
  ~LaserScanner() = default;
};

}  // namespace kestrel::hal
