#pragma once
// A 3-axis accelerometer and gyroscope.
#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel::hal {

class Imu {
 public:
  virtual Duration sample_period() const = 0;
  // Oldest unread sample into `out`: kOk, kNoData when none is waiting, or an error.
  virtual Status poll(ImuSample& out) = 0;

 protected:
  ~Imu() = default;
};

}  // namespace kestrel::hal
