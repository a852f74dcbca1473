#pragma once
// The vehicle's monotonic clock. Implemented by platform/linux (CLOCK_MONOTONIC) and by the
// simulator's lockstep clock.
#include "kestrel/core/status.hpp"
#include "kestrel/core/time.hpp"

namespace kestrel::hal {

class Clock : public TimeSource {
 public:
  // Blocks (or, in simulation, steps the world) until `t`. Returns at once if `t` has passed.
  virtual Status sleep_until(TimeUs t) = 0;

 protected:
  ~Clock() = default;
};

}  // namespace kestrel::hal
