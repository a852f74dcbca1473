#pragma once
// A LaserScanner that hands each scan on `delay` after it arrived: the wireless link and
// processing latency of paper 000 section 5.2, for the delay study of its Figure 3b. The scan
// keeps the stamp of its measurement; only its delivery is late. Fixed capacity: when more
// than kCapacity scans are in flight, the oldest is dropped and counted.
#include <cstdint>

#include "kestrel/core/ring_buffer.hpp"
#include "kestrel/hal/laser_scanner.hpp"

namespace kestrel::flight {

class DelayedLaser final : public hal::LaserScanner {
 public:
  static constexpr std::size_t kCapacity = 64;

  DelayedLaser(hal::LaserScanner& inner, const TimeSource& clock, Duration delay)
      : inner_(inner), clock_(clock), delay_(delay) {}

  hal::LaserGeometry geometry() const override { return inner_.geometry(); }
  Status poll(LaserScan& out) override;
  uint32_t dropped() const { return dropped_; }

 private:
  struct Pending {
    TimeUs release;
    LaserScan scan;
  };
  hal::LaserScanner& inner_;
  const TimeSource& clock_;
  Duration delay_;
  RingBuffer<Pending, kCapacity> queue_;
  LaserScan incoming_;
  uint32_t dropped_ = 0;
};

}  // namespace kestrel::flight
