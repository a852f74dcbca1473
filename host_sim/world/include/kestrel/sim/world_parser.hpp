#pragma once
// The world text format: one primitive per line, `#` starts a comment, numbers in metres and
// degrees. A newcomer can write a world in an editor:
//
//   name        my-lab
//   start       X Y Z YAW_DEG         # where the vehicle stands at t = 0
//   wall_height H                     # default top of walls (default 2.5 m)
//   wall_thickness T                  # for collisions (default 0.1 m)
//   ceiling     H                     # laser returns from a ceiling at H (default: none)
//   wall        X1 Y1 X2 Y2 [OPTIONS]
//   box         CX CY SIZE_X SIZE_Y [yaw=DEG] [OPTIONS]  # rectangular obstacle
//   pillar      CX CY RADIUS [OPTIONS]                   # 16-sided prism
//   poly        X1 Y1 X2 Y2 X3 Y3 ... [OPTIONS]          # convex obstacle
//   room        NAME X1 Y1 X2 Y2 X3 Y3 ...               # named area for rooms_entered
//
// OPTIONS: `z=ZMIN:ZMAX` (height range in m; walls default to 0:wall_height, obstacles to
// 0:wall_height), `glass` (no return, the beam passes), `railing=P` (a beam returns with
// probability P), `opaque`.
// Every point (start, wall ends, obstacle corners, room corners) has |x| and |y| at most 500 m,
// and wall_thickness is at most 10 m: a world beyond that is an error, not a grid the
// simulator cannot allocate.
// Errors name the source, the line and the reason: "lab.world:12: box needs 4 numbers".
#include <string>
#include <string_view>

#include "kestrel/sim/world.hpp"

namespace kestrel::sim {

struct WorldParseResult {
  bool ok = false;
  World world;
  std::string error;  // "SOURCE:LINE: reason" when !ok
};

WorldParseResult parse_world(std::string_view text, std::string_view source_name);
// Reads and parses a file; a missing or unreadable file is an error naming the path.
WorldParseResult load_world_file(const std::string& path);

}  // namespace kestrel::sim
