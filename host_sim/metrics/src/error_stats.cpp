#include "kestrel/metrics/error_stats.hpp"

#include <cmath>

namespace kestrel::metrics {

void ErrorAccumulator::add(double e) {
  ++n_;
  const double d = e - mean_;
  mean_ += d / static_cast<double>(n_);
  m2_ += d * (e - mean_);
  sum_sq_ += e * e;
  if (n_ == 1 || e > max_) max_ = e;
}

ErrorStats ErrorAccumulator::stats() const {
  ErrorStats s;
  s.count = n_;
  if (n_ == 0) return s;
  const double n = static_cast<double>(n_);
  s.mean = mean_;
  s.std = std::sqrt(m2_ > 0 ? m2_ / n : 0.0);
  s.rmse = std::sqrt(sum_sq_ / n);
  s.max = max_;
  return s;
}

}  // namespace kestrel::metrics
