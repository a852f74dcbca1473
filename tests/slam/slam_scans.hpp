#pragma once
// The compact SLAM's test worlds; their scans as ScanPoints come from synthetic_points.hpp.
#include "synthetic_points.hpp"

namespace kestrel::test {

// An 8 x 6 m room with a pillar and an alcove: every direction constrained.
inline SegmentWorld slam_room() {
  SegmentWorld w;
  w.add(-4, -3, 4, -3);
  w.add(4, -3, 4, 3);
  w.add(4, 3, 1, 3);
  w.add(1, 3, 1, 2.2);
  w.add(1, 2.2, -1, 2.2);
  w.add(-1, 2.2, -1, 3);
  w.add(-1, 3, -4, 3);
  w.add(-4, 3, -4, -3);
  w.add_box(1.5, -1.2, 2.1, -0.6);
  return w;
}

// Two parallel walls 2 m apart, 200 m long: nothing fixes the position along x.
inline SegmentWorld slam_corridor() {
  SegmentWorld w;
  w.add(-100, -1, 100, -1);
  w.add(-100, 1, 100, 1);
  return w;
}

}  // namespace kestrel::test
