#pragma once
// SRT-Star alone (Freda and Oriolo, ICRA 2005), the way paper 002 section IV says the original
// works: the waypoints go straight to the controller as position set-points (kPosition), the
// heading points at the waypoint under the yaw-rate limit, and the waypoint time limit of
// section V applies. No wall-following contribution.
#include "kestrel/exploration/explorer_base.hpp"

namespace kestrel::exploration {

class SrtExplorer final : public ExplorerBase {
 public:
  ExplorerKind kind() const override { return ExplorerKind::kSrt; }
  bool finished() const override { return planner_.finished(); }
  const SrtStarPlanner* planner() const override { return &planner_; }

 private:
  Status plan(const Pose2& pose, const LaserScan& scan, TimeUs now, GuidanceSetpoint& out,
              float& heading_target) override;
  Status configure_strategy() override { return planner_.configure(params_.srt, params_.guidance); }
  void reset_strategy() override { planner_.reset(); }

  SrtStarPlanner planner_;
};

}  // namespace kestrel::exploration
