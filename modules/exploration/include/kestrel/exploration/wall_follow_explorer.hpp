#pragma once
// Wall following alone: the baseline paper 002 sets out to improve on (section I-B, Sobers et
// al.), whose flaws it names: it tends to track the outermost walls, may leave inner rooms
// unexplored, and the field alone has local minima where the vehicle "gets stuck" (section III).
//
// The field of equations 2-4 has no term that makes progress along a wall, gives no heading
// command, and in a room its pulls towards opposite walls cancel (it settles mid-room), so the
// baseline adds the least that makes it a wall follower in the manner of Sobers et al.: a pull
// wall_hold_gain * (r_min - r_t) towards the nearest return, a constant cruise speed along that
// wall keeping it on the right (tangent = bearing of the nearest return + 90 degrees), and the
// heading turned (yaw-rate limited) towards the direction of travel so the laser looks ahead.
// With no wall in range it cruises straight on. cruise_speed_mps = 0 and wall_hold_gain = 0
// leave the field of the paper alone, heading held.
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
