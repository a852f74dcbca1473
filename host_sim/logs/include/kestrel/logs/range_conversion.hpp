#pragma once
// Metres in a log to the millimetre ranges of LaserScan. A reading at or beyond the maximum
// range, or zero, is the sensor's way of saying "no return" (SICK LMS logs write 81.91 m);
// readings of 1..19 mm are kept as they are: they are the error codes of LaserScan (after the
// Hokuyo SCIP protocol), which is how kestrel's writer stores them.
#include <cstdint>

#include "kestrel/core/status.hpp"

namespace kestrel::logs {

// Converts one finite reading: kOk, or kMalformed for a negative reading.
Status metres_to_range_mm(double metres, double max_range_m, uint16_t& out_mm);

// The maximum range as LaserScan::max_range_mm (saturated at 65535 mm).
uint16_t max_range_to_mm(double max_range_m);

}  // namespace kestrel::logs
