#pragma once
// The laser geometry an explorer is configured for. Modules do not see hal::LaserGeometry, so
// the composition code copies the scanner's geometry into this struct once, at start-up; the
// per-beam tables of the wall-following field are built from it.
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel::exploration {

struct BeamGeometry {
  uint16_t beam_count = 0;    // beams per scan, 1..kMaxBeams
  float first_angle_rad = 0;  // angle of beam 0 in the body frame, counter-clockwise
  float angle_step_rad = 0;   // between consecutive beams (non-zero, either sign)
  uint16_t max_range_mm = 0;  // the sensor's maximum range

  static BeamGeometry of(const LaserScan& scan) {
    return {scan.beam_count, scan.first_angle_rad, scan.angle_step_rad, scan.max_range_mm};
  }
  Status validate() const;
  // Whether a scan was taken with this geometry (angles to a thousandth of a step).
  bool matches(const LaserScan& scan) const;
};

}  // namespace kestrel::exploration
