#pragma once
// The lockstep clock: time moves only when the simulation steps, so every run is exactly
// repeatable and as fast as the host allows. sleep_until() steps the world to the given time.
#include "kestrel/hal/clock.hpp"

namespace kestrel::sim {

class Simulation;

class SimClock final : public hal::Clock {
 public:
  explicit SimClock(Simulation& sim) : sim_(sim) {}
  TimeUs now() const override;
  Status sleep_until(TimeUs t) override;

 private:
  Simulation& sim_;
};

}  // namespace kestrel::sim
