#pragma once
// iarc-arena's west end as the laser sees it: a hallway (y 6..9) whose north wall has a glass
// window (x 2..5) the laser sees through, so it is not drawn, and room A south of the hallway
// (door x 6..7.2). Home is (2, 7.5), 1.5 m south of the window. Facing north 1.5 m from room
// A's north wall, the vehicle sees that wall and the west wall: the hallway's end as a
// take-off turn at home saw it, save the window (EXPERIMENTS.md, *A home fix must not put walls
// where the take-off turn saw through*).
#include "synthetic_world.hpp"

namespace kestrel::test {

inline SegmentWorld glass_window_world() {
  SegmentWorld w;
  w.add(0, 0, 0, 15);    // west wall
  w.add(0, 6, 6, 6);     // hallway south wall = room A's north wall
  w.add(7.2, 6, 15, 6);
  w.add(0, 9, 2, 9);     // hallway north wall, the window between
  w.add(5, 9, 9, 9);
  w.add(0, 0, 15, 0);
  w.add(0, 15, 15, 15);
  return w;
}

}  // namespace kestrel::test
