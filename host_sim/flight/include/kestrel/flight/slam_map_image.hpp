#pragma once
// The compact SLAM's map as map.pgm / map.yaml (DESIGN.md's outputs, the ROS map_server
// convention): the part of the 1024-cell map the laser has touched, with a metre of margin,
// in map_server's trinary mode. A cell is a wall at or below kSlamWallLevel, free at or above
// kSlamFreeLevel, unknown between: the V drawn across each return leaves its slopes in
// between, and a cell cleared once and never seen again stays near unknown.
#include <cstdint>

#include "kestrel/output/pgm_map.hpp"
#include "kestrel/slam/slam_map.hpp"

namespace kestrel::flight {

inline constexpr uint8_t kSlamWallLevel = 60;
inline constexpr uint8_t kSlamFreeLevel = 200;

// An empty image (width 0) when the map holds nothing.
output::GridImage slam_map_image(const slam::SlamMap& map);

}  // namespace kestrel::flight
