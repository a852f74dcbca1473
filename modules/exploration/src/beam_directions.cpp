#include "kestrel/exploration/beam_directions.hpp"

#include <cmath>

namespace kestrel::exploration {

void BeamDirections::build(const BeamGeometry& geometry) {
  for (std::size_t i = 0; i < geometry.beam_count && i < kMaxBeams; ++i) {
    // In double: the angle of beam 1080 accumulates no float rounding.
    const double a = static_cast<double>(geometry.first_angle_rad) +
                     static_cast<double>(geometry.angle_step_rad) * static_cast<double>(i);
    cos[i] = Trig::from_double(std::cos(a));
    sin[i] = Trig::from_double(std::sin(a));
  }
}

}  // namespace kestrel::exploration
