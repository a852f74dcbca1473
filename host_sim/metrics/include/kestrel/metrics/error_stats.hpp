#pragma once
// Summary of a set of non-negative error magnitudes: mean and standard deviation (as the
// tables of Kümmerle et al. 2009 report them), RMSE and maximum.
#include <cstddef>

namespace kestrel::metrics {

struct ErrorStats {
  std::size_t count = 0;
  double mean = 0;
  double std = 0;   // population standard deviation (divides by count)
  double rmse = 0;
  double max = 0;
};

// Accumulates samples one at a time (Welford's update: stable over long runs), no storage.
class ErrorAccumulator {
 public:
  void add(double e);
  ErrorStats stats() const;
  std::size_t count() const { return n_; }

 private:
  std::size_t n_ = 0;
  double mean_ = 0;
  double m2_ = 0;       // sum of squared deviations from the mean
  double sum_sq_ = 0;
  double max_ = 0;
};

}  // namespace kestrel::metrics
