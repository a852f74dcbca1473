#include "kestrel/sim/builtin_worlds.hpp"

#include <string>

namespace kestrel::sim {
namespace {

// Hallway along x (y 6..9), rooms A, B south and C, D north, doorways 1.2 m wide.
constexpr std::string_view kIarcArena = R"(# iarc-arena: office-like arena, paper 004 Figures 3 and 10-11
name iarc-arena
start 2.0 7.5 0 0
wall_height 2.5
ceiling 2.6
# outer walls
wall 0 0 30 0
wall 30 0 30 15
wall 30 15 0 15
wall 0 15 0 0
# south side of the hallway, doorways into room A (x 6-7.2) and room B (x 21-22.2)
wall 0 6 6 6
wall 7.2 6 21 6
wall 22.2 6 30 6
# north side, doorways into room C (x 9-10.2) and room D (x 24-25.2), a glass window in C
wall 0 9 2 9
wall 2 9 5 9 glass
wall 5 9 9 9
wall 10.2 9 24 9
wall 25.2 9 30 9
# walls between the rooms
wall 15 0 15 6
wall 15 9 15 15
# room A: desks and a tall shelf
box 3 2 1.6 0.8 z=0:0.75
box 8 1.5 1.6 0.8 z=0:0.75
box 12.5 0.4 2.0 0.5 z=0:2.0
pillar 10 4 0.3
# room B: a table, low crates, a cabinet
box 19 3 2.0 1.0 z=0:0.75
box 25 1.5 0.6 0.6 z=0:0.4
box 26 1.5 0.6 0.6 z=0:0.4
box 28.5 4.5 0.5 2.0 z=0:1.8
# room C: shelves along the wall, a sofa
box 2 14.5 3.0 0.5 z=0:2.0
box 11 12 2.0 0.9 z=0:0.8 yaw=20
# room D: a railing around a stair opening, a desk
wall 19 11 22 11 z=0:1.0 railing=0.3
wall 22 11 22 13 z=0:1.0 railing=0.3
wall 22 13 19 13 z=0:1.0 railing=0.3
box 27 13 1.6 0.8 z=0:0.75
# hallway: a column and a low bench
pillar 15 8.65 0.2
box 20 8.6 1.5 0.4 z=0:0.45
room hallway 0 6 30 6 30 9 0 9
room room-A 0 0 15 0 15 6 0 6
room room-B 15 0 30 0 30 6 15 6
room room-C 0 9 15 9 15 15 0 15
room room-D 15 9 30 9 30 15 15 15
)";

// A corridor (y 7..9) with three rooms south, two large rooms north; inside the north-east
// room an inner room whose only entry is a 0.95 m gap in its west wall (paper 002 Fig. 5).
constexpr std::string_view kGtBuilding =
    R"(# gt-building: rooms and an inner room reached through a narrow gap, paper 002 Figure 5
name gt-building
start 1.5 8.0 0 0
wall_height 2.7
ceiling 2.8
wall 0 0 24 0
wall 24 0 24 16
wall 24 16 0 16
wall 0 16 0 0
# corridor south wall with three doors
wall 0 7 3 7
wall 4.2 7 11 7
wall 12.2 7 19 7
wall 20.2 7 24 7
wall 8 0 8 7
wall 16 0 16 7
# corridor north wall with two doors
wall 0 9 5 9
wall 6.2 9 15 9
wall 16.2 9 24 9
wall 12 9 12 16
# inner room x 16..21, y 11..15, entered only through the gap y 12.5..13.45 in its west wall
wall 16 11 21 11
wall 21 11 21 15
wall 21 15 16 15
wall 16 15 16 13.45
wall 16 12.5 16 11
# furniture
box 2 2 1.5 0.8 z=0:0.75
box 6 5.5 1.2 0.6 z=0:1.2
box 12 3.5 2.0 1.0 z=0:0.75
box 20 1 3.0 0.5 z=0:2.0
box 3 13 2.0 1.0 z=0:0.75
box 9 15.5 3.0 0.5 z=0:2.0
box 18.5 13 1.0 1.0 z=0:0.9
box 23 12 0.8 2.0 z=0:1.5
room corridor 0 7 24 7 24 9 0 9
room south-west 0 0 8 0 8 7 0 7
room south-middle 8 0 16 0 16 7 8 7
room south-east 16 0 24 0 24 7 16 7
room north-west 0 9 12 9 12 16 0 16
room north-east 12 9 24 9 24 16 12 16
room inner 16 11 21 11 21 15 16 15
)";

// 40 x 30 m open lobby: pillars on an 8 m grid, a glass front, a reception desk and a railed
// atrium. From the middle most walls are beyond the URG-04LX's 4 m (paper 000, 6.1).
constexpr std::string_view kLobby = R"(# lobby: large open space with pillars, paper 000 section 6.1
name lobby
start 5 15 0 0
wall_height 4.0
ceiling 0
wall 0 0 40 0
wall 40 0 40 30
wall 40 30 0 30
# the front (west) is a glass facade with an opaque door frame
wall 0 30 0 16 glass
wall 0 16 0 14
wall 0 14 0 0 glass
pillar 8 6 0.4
pillar 8 14 0.4
pillar 8 22 0.4
pillar 16 6 0.4
pillar 16 22 0.4
pillar 24 6 0.4
pillar 24 14 0.4
pillar 24 22 0.4
pillar 32 6 0.4
pillar 32 14 0.4
pillar 32 22 0.4
# reception desk
box 34 15 1.0 5.0 z=0:1.1
# atrium railing around (14..18, 12..16)
wall 14 12 18 12 z=0:1.0 railing=0.25
wall 18 12 18 16 z=0:1.0 railing=0.25
wall 18 16 14 16 z=0:1.0 railing=0.25
wall 14 16 14 12 z=0:1.0 railing=0.25
# benches
box 12 26 2.0 0.5 z=0:0.45
box 28 26 2.0 0.5 z=0:0.45
room lobby 0 0 40 0 40 30 0 30
)";

// A 60 m x 2.4 m corridor with nothing on its walls.
constexpr std::string_view kHallway = R"(# hallway: long featureless corridor, the scan matcher's degenerate case
name hallway
start 2 1.2 0 0
wall_height 2.5
ceiling 2.6
wall 0 0 60 0
wall 60 0 60 2.4
wall 60 2.4 0 2.4
wall 0 2.4 0 0
room hallway 0 0 60 0 60 2.4 0 2.4
)";

// A 12 x 10 m lab and a 4 x 10 m store room: desks, chairs, shelves, crates and a wall
// cabinet hanging at 1.4-2.2 m that a low flight does not see (paper 000, 6.2).
constexpr std::string_view kClutteredLab = R"(# cluttered-lab: furniture of different heights, paper 000 section 6.2
name cluttered-lab
start 1.0 1.0 0 45
wall_height 2.6
ceiling 2.7
wall 0 0 16 0
wall 16 0 16 10
wall 16 10 0 10
wall 0 10 0 0
# partition to the store room with a door at y 4..5
wall 12 0 12 4
wall 12 5 12 10
# desks (0.75 m) in two rows, chairs (0.9 m)
box 3 3 1.6 0.8 z=0:0.75
box 6 3 1.6 0.8 z=0:0.75
box 9 3 1.6 0.8 z=0:0.75
box 3 6.5 1.6 0.8 z=0:0.75
box 6 6.5 1.6 0.8 z=0:0.75
box 9 6.5 1.6 0.8 z=0:0.75
box 3 2.2 0.45 0.45 z=0:0.9
box 6.2 2.2 0.45 0.45 z=0:0.9
box 3.1 7.3 0.45 0.45 z=0:0.9
box 8.8 7.3 0.45 0.45 z=0:0.9
# tall shelves along the north wall, a wall cabinet on the east wall above head height
box 2 9.7 3.0 0.5 z=0:2.1
box 7 9.7 3.0 0.5 z=0:2.1
box 11.7 2 0.5 2.5 z=1.4:2.2
# a workbench and a rack of instruments
box 10 8.5 1.2 1.2 z=0:1.0
poly 5 4.6 6 4.6 6.3 5.0 5.5 5.3 z=0:0.5
# store room: crates and a high rack
box 13.5 1 1.0 1.0 z=0:0.6
box 14.5 1 1.0 1.0 z=0:1.2
box 15.6 6 0.7 3.5 z=0:2.2
box 13.5 9 1.5 1.0 z=0:0.4
room lab 0 0 12 0 12 10 0 10
room store 12 0 16 0 16 10 12 10
)";

struct Entry {
  std::string_view name;
  std::string_view text;
};
constexpr Entry kWorlds[] = {{"iarc-arena", kIarcArena},
                             {"gt-building", kGtBuilding},
                             {"lobby", kLobby},
                             {"hallway", kHallway},
                             {"cluttered-lab", kClutteredLab}};

}  // namespace

const std::vector<std::string_view>& builtin_world_names() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> v;
    for (const Entry& e : kWorlds) v.push_back(e.name);
    return v;
  }();
  return names;
}

std::string_view builtin_world_text(std::string_view name) {
  for (const Entry& e : kWorlds)
    if (e.name == name) return e.text;
  return {};
}

WorldParseResult load_builtin_world(std::string_view name) {
  const std::string_view text = builtin_world_text(name);
  if (text.empty()) {
    WorldParseResult r;
    std::string msg = "unknown world '";
    msg.append(name).append("' (known:");
    for (const Entry& e : kWorlds) msg.append(" ").append(e.name);
    msg.append("; or give a path to a world file)");
    r.error = msg;
    return r;
  }
  std::string source = "<builtin ";
  source.append(name).append(">");
  return parse_world(text, source);
}

WorldParseResult load_world(const std::string& name_or_path) {
  if (!builtin_world_text(name_or_path).empty()) return load_builtin_world(name_or_path);
  // Anything that looks like a path is read as a file; a bare word is an unknown name.
  if (name_or_path.find('/') != std::string::npos || name_or_path.find('.') != std::string::npos)
    return load_world_file(name_or_path);
  return load_builtin_world(name_or_path);
}

}  // namespace kestrel::sim
