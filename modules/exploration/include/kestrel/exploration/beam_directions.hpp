#pragma once
// cos and sin of every beam's body-frame angle in Q14 (core Fixed<14>), tabled once per laser
// geometry so that the per-scan loops of the FPU-less Verdex stay integer: the wall-following
// field (equations 2-3) and the approach limiter both walk the scan with these.
#include <array>
#include <cstddef>

#include "kestrel/core/fixed_point.hpp"
#include "kestrel/core/messages.hpp"
#include "kestrel/exploration/beam_geometry.hpp"

namespace kestrel::exploration {

struct BeamDirections {
  static constexpr int kFracBits = 14;
  using Trig = Fixed<kFracBits>;

  std::array<Trig, kMaxBeams> cos{};
  std::array<Trig, kMaxBeams> sin{};

  // Fills the first geometry.beam_count entries; the geometry must be valid.
  void build(const BeamGeometry& geometry);
};

}  // namespace kestrel::exploration
