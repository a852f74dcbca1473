#pragma once
// The named worlds compiled into the simulator, written in the world text format (see
// world_parser.hpp) so that each one is also an example of it:
//   iarc-arena     ~30 x 15 m office arena, a main hallway and four rooms behind doorways
//                  (paper 004, Figures 3 and 10-11)
//   gt-building    several rooms and an inner room reached only through a 0.95 m gap
//                  (paper 002, Figure 5)
//   lobby          a large open lobby with pillars, walls mostly beyond 4 m (paper 000, 6.1)
//   hallway        a 60 m featureless corridor: the scan matcher's degenerate case
//   cluttered-lab  furniture of many heights: the scan slice changes with altitude (000, 6.2)
#include <string_view>
#include <vector>

#include "kestrel/sim/world_parser.hpp"

namespace kestrel::sim {

// Names of the compiled-in worlds, in a fixed order.
const std::vector<std::string_view>& builtin_world_names();
// The source text of a named world, or an empty view if the name is unknown.
std::string_view builtin_world_text(std::string_view name);
// Parses a named world; an unknown name is an error that lists the known names.
WorldParseResult load_builtin_world(std::string_view name);
// A name of a compiled-in world, or else a path to a world file.
WorldParseResult load_world(const std::string& name_or_path);

}  // namespace kestrel::sim
