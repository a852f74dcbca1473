#pragma once
// An operator's keep-out box: a region the vehicle is never sent into or through, in the
// navigation frame (m). A laser-only vehicle cannot tell a glass window from a doorway (the beams
// pass through), so, like paper 004's explorer, whose operator marks the nodes "south of window"
// off limits, it is told. Axis-aligned; the explorer and the flight home grow it by their
// clearance when they use it.
#include <cstddef>

#include "kestrel/core/se2.hpp"

namespace kestrel {

inline constexpr std::size_t kMaxKeepOuts = 4;

struct KeepOut {
  float x_min = 0, y_min = 0, x_max = 0, y_max = 0;
  // Finite corners, the minimum no larger than the maximum.
  bool valid() const;
  // Whether the segment a-b enters the box grown by `grow` on every side (false for a
  // non-finite point).
  bool crossed_by(Point2 a, Point2 b, float grow) const;
  // A strip (a window in a wall: kMinStripLengthM or longer, three times its width or more)
  // lengthened by `along` at each end of its long side, as far as an estimate that places it may
  // have drifted along the wall; any other box as it is: widened, a strip would cover the
  // corridor beside its wall, and a pillar's, a post's or a room's box has no wall to be
  // lengthened along.
  KeepOut lengthened(float along) const;
  static constexpr float kMinStripLengthM = 0.5f;
};

}  // namespace kestrel
