#pragma once
// The small worlds the frontier explorer's tests fly in.
#include "synthetic_world.hpp"

namespace kestrel::exploration::test_worlds {

// A 4 x 4 m room with a 1.2 m door in its east wall to a corridor running north-south.
inline kestrel::test::SegmentWorld room_and_corridor() {
  kestrel::test::SegmentWorld w;
  w.add(0, 0, 4, 0);
  w.add(4, 0, 4, 1.4);
  w.add(4, 2.6, 4, 4);
  w.add(4, 4, 0, 4);
  w.add(0, 4, 0, 0);
  w.add(6, -8, 6, 12);  // the corridor's far wall
  return w;
}

}  // namespace kestrel::exploration::test_worlds
