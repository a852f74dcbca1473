#pragma once
// Paper 002's exploration strategy, Algorithm 1: every scan gives the wall-following velocity
// v_wf (section III, equations 2-4); on arrival within d of the waypoint SRT-Star grows its tree
// and draws the next waypoint or backtracks (section IV); the frontier velocity is
// v_fr = K_fr (x_waypoint - x) (equation 5), the heading command points at the waypoint
// (equation 6), and the command is v_cmd = v_wf + v_fr (equation 1), then the speed and
// yaw-rate limits of section V. Output: GuidanceSetpoint kVelocity.
#include "kestrel/exploration/explorer_base.hpp"

namespace kestrel::exploration {

class BlendExplorer final : public ExplorerBase {
 public:
  ExplorerKind kind() const override { return ExplorerKind::kBlend; }
  bool finished() const override { return planner_.finished(); }
  const SrtStarPlanner* planner() const override { return &planner_; }

 private:
  Status plan(const Pose2& pose, const LaserScan& scan, TimeUs now, GuidanceSetpoint& out,
              float& heading_target) override;
  Status configure_strategy() override {
    return planner_.configure(params_.srt, params_.guidance, params_.approach.enabled);
  }
  void reset_strategy() override { planner_.reset(); }

  SrtStarPlanner planner_;
};

}  // namespace kestrel::exploration
