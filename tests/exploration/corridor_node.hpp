#pragma once
// A tree's root standing in a 2 m wide corridor along x (walls at y = +-1), facing its north
// wall: the laser sees both ways along the corridor at +-90 degrees, so the node owns
// frontiers east and west. The scene of the frontier-draw tests (draw_frontier,
// draw_toward_unflown).
#include <memory>

#include "kestrel/exploration/sector_scan.hpp"
#include "kestrel/exploration/srt_star_tree.hpp"
#include "synthetic_world.hpp"

namespace kestrel::exploration::test_scenes {

inline constexpr float kFacingNorth = static_cast<float>(M_PI / 2);

inline ::kestrel::test::SegmentWorld corridor(float x_from, float x_to) {
  ::kestrel::test::SegmentWorld w;
  w.add(x_from, 1, x_to, 1);
  w.add(x_from, -1, x_to, -1);
  return w;
}

struct CorridorNode {
  std::unique_ptr<SectorScan> sectors = std::make_unique<SectorScan>();
  std::unique_ptr<SrtStarTree> tree = std::make_unique<SrtStarTree>();
  Pose2 pose{};
  uint16_t id = kNoNode;
};

// The root at (x, 0) of a corridor from x_from to x_to, URG-04LX, default SrtParams. kOk, or
// the status of the step that failed.
inline Status corridor_node(float x_from, float x_to, float x, CorridorNode& out) {
  out.pose = {x, 0, kFacingNorth};
  const SrtParams params;
  const Status built = out.sectors->build(
      corridor(x_from, x_to).scan(::kestrel::test::LaserModel::urg04lx(), x, 0, kFacingNorth), params);
  if (built != Status::kOk) return built;
  return out.tree->add_node(out.pose, *out.sectors, kNoNode, out.id);
}

}  // namespace kestrel::exploration::test_scenes
