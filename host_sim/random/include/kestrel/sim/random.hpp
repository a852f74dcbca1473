#pragma once
// Seeded random numbers that are bit-identical on the host and on both ARM targets, so that a
// simulated run (world + config + seed) gives the same bytes everywhere.
//
// Why our own: std::normal_distribution and friends are implementation-defined, and libm's
// log/sin/cos may differ in the last bit between glibc builds (FMA variants on x86-64, soft
// float on the Verdex). The generator is xoshiro256** (Blackman & Vigna), seeded through
// SplitMix64; Gaussians use Marsaglia's polar method with a logarithm built only from
// + - * / and sqrt, which IEEE 754 rounds identically on every target.
#include <cstdint>

namespace kestrel::sim {

class Rng {
 public:
  explicit Rng(uint64_t seed = 1) { reseed(seed); }

  void reseed(uint64_t seed);
  // An independent stream for a sub-system (laser, IMU, gusts, ...): adding a consumer of
  // randomness to one sub-system does not perturb the others.
  Rng fork(uint64_t stream_id) const;

  uint64_t next_u64();
  // Uniform in [0, 1) with 53 random bits.
  double uniform();
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Standard normal N(0, 1).
  double gaussian();
  double gaussian(double mean, double stddev) { return mean + stddev * gaussian(); }
  bool bernoulli(double p) { return uniform() < p; }

 private:
  uint64_t s_[4]{};
  uint64_t seed_ = 0;
  double spare_ = 0;
  bool has_spare_ = false;
};

// Natural logarithm of a positive finite x using only IEEE-exact operations (see above).
// Accurate to a few ulp; returns -infinity for 0 and NaN for negative or NaN input.
double portable_log(double x);

}  // namespace kestrel::sim
