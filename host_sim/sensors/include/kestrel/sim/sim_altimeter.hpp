#pragma once
// Height from laser beams deflected straight down by a mirror (paper 000, Figure 1): the
// simulated laser feeds it one sample per sweep (the mean of the deflected beams' ranges,
// minus the scanner's mounting height, so it reads the body's height when level). Like the
// real device it is not corrected for tilt: that is the estimator's job.
#include "kestrel/core/ring_buffer.hpp"
#include "kestrel/hal/altimeter.hpp"

namespace kestrel::sim {

class SimAltimeter final : public hal::Altimeter {
 public:
  // Oldest unread sample: kOk, or kNoData.
  Status poll(AltimeterSample& out) override;
  // Producer side (the laser). Returns false when the queue is full (sample dropped).
  bool push(const AltimeterSample& s) { return queue_.push(s); }
  bool has_source() const { return has_source_; }
  void set_has_source(bool v) { has_source_ = v; }

 private:
  RingBuffer<AltimeterSample, 64> queue_;
  bool has_source_ = false;
};

}  // namespace kestrel::sim
