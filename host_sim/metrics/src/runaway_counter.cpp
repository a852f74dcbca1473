#include "kestrel/metrics/runaway_counter.hpp"

#include <cmath>

namespace kestrel::metrics {

RunawayCounter::RunawayCounter(double rise_m, double window_s)
    : rise_m_(std::isfinite(rise_m) ? rise_m : INFINITY),
      window_s_(std::isfinite(window_s) && window_s > 0 ? window_s : 0.0) {}

Status RunawayCounter::add(double t_s, double error_m) {
  if (!std::isfinite(t_s) || !std::isfinite(error_m)) return Status::kNotFinite;
  if (any_ && t_s < last_t_) return Status::kInvalidArgument;
  any_ = true;
  last_t_ = t_s;
  // The window's minimum is at the front: a sample drops every later-or-equal one it is below.
  while (!minima_.empty() && minima_.back().second >= error_m) minima_.pop_back();
  minima_.emplace_back(t_s, error_m);
  while (minima_.size() > 1 && minima_.front().first < t_s - window_s_) minima_.pop_front();
  if (error_m - minima_.front().second > rise_m_ && (!counted_ || t_s - last_runaway_t_ > window_s_)) {
    ++runaways_;
    counted_ = true;
    last_runaway_t_ = t_s;
  }
  return Status::kOk;
}

}  // namespace kestrel::metrics
