#pragma once
// Small deterministic pseudo-random generator (xorshift32, Marsaglia 2003) for SRT-Star's
// random waypoints and the compact SLAM's search: seeded, no state outside the object,
// identical on every target.
#include <cstdint>

namespace kestrel {

class Prng {
 public:
  explicit Prng(uint32_t seed = 1) { reseed(seed); }
  // Zero is a fixed point of xorshift, so it is mapped to another constant.
  void reseed(uint32_t seed) { state_ = seed != 0 ? seed : 0x9E3779B9u; }
  uint32_t next() {
    uint32_t x = state_;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return state_ = x;
  }
  // Uniform in [0, 1).
  float uniform() { return static_cast<float>(next() >> 8) * (1.0f / 16777216.0f); }
  // Uniform integer in [0, n), n > 0 (the modulo bias is below 1e-7 for our small n).
  uint32_t below(uint32_t n) { return n == 0 ? 0 : next() % n; }

 private:
  uint32_t state_ = 1;
};

}  // namespace kestrel
