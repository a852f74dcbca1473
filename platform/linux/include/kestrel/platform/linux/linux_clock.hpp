#pragma once
// hal::Clock on CLOCK_MONOTONIC.
#include "kestrel/hal/clock.hpp"

namespace kestrel::platform {

class LinuxClock final : public hal::Clock {
 public:
  TimeUs now() const override;
  Status sleep_until(TimeUs t) override;
};

}  // namespace kestrel::platform
