#pragma once
// Wall following alone: the baseline paper 002 sets out to improve on (section I-B, Sobers et
// al.), whose flaws it names: it tends to track the outermost walls, may leave inner rooms
// unexplored, and the field alone has local minima where the vehicle "gets stuck" (section III).
//
// The field of equations 2-4 has no term that makes progress along a wall and gives no heading
// command, so the baseline adds the least that makes it a wall follower: a constant cruise
// speed along the nearest wall, keeping it on the right (tangent = bearing of the nearest return
// + 90 degrees), with the heading turned (yaw-rate limited) towards the direction of travel so
// the laser looks ahead. With no wall in range it cruises straight on. cruise_speed_mps = 0
// leaves the field of the paper alone, heading held.
#include "kestrel/exploration/explorer_base.hpp"

namespace kestrel::exploration {

class WallFollowExplorer final : public ExplorerBase {
 public:
  ExplorerKind kind() const override { return ExplorerKind::kWallFollow; }
  bool finished() const override { return false; }
  const SrtStarPlanner* planner() const override { return nullptr; }

 private:
  Status plan(const Pose2& pose, const LaserScan& scan, TimeUs now, GuidanceSetpoint& out,
              float& heading_target) override;
};

}  // namespace kestrel::exploration
