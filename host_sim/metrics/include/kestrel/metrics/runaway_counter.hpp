#pragma once
// Runaways of the estimate: times the horizontal error grew by more than `rise_m` within
// `window_s` (1 m in 10 s by default). A flight ends in a contact or not, which is a chaotic
// draw; how often its estimate runs away is a steadier measure of the same failure, and the one
// that separated the URG-04LX's filter settings (modules/exploration/EXPERIMENTS.md, *A quieter
// accelerometer model*). After a runaway is counted the next one counts only a window later.
// In metrics.json: `estimate_runaways`.
#include <cstddef>
#include <deque>
#include <utility>

#include "kestrel/core/status.hpp"

namespace kestrel::metrics {

class RunawayCounter {
 public:
  // A negative or non-finite window is taken as 0 (each sample compared with itself: no
  // runaway), a non-finite rise as never reached.
  explicit RunawayCounter(double rise_m = 1.0, double window_s = 10.0);
  // kNotFinite (ignored) for a non-finite sample; kInvalidArgument (ignored) for a time before
  // the previous sample's.
  Status add(double t_s, double error_m);
  std::size_t runaways() const { return runaways_; }

 private:
  double rise_m_, window_s_;
  std::deque<std::pair<double, double>> minima_;  // (t, error), errors rising from front to back
  double last_t_ = 0, last_runaway_t_ = 0;
  bool any_ = false, counted_ = false;
  std::size_t runaways_ = 0;
};

}  // namespace kestrel::metrics
