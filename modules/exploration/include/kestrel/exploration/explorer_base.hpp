#pragma once
// What the four explorers share: input checks with a defined hold for every bad input, the
// wall-following field, the yaw-rate and speed limits of paper 002 section V, the approach
// limiter on every velocity command, the heading across a degenerate match (off by default),
// and the status.
// A derived explorer only writes its strategy in plan().
#include "kestrel/core/time.hpp"
#include "kestrel/exploration/explorer.hpp"
#include "kestrel/exploration/guidance_limits.hpp"

namespace kestrel::exploration {

class ExplorerBase : public Explorer {
 public:
  Status configure(const Params& params, const BeamGeometry& geometry) override;
  void reset() override;
  Status step(const NavState& nav, const LaserScan& scan, GuidanceSetpoint& out) final;
  Status bound_velocity(const NavState& nav, const LaserScan& scan, GuidanceSetpoint& setpoint) final;
  void note_match(const MatchConstraint& m) final { look_.note(m); }
  const ExplorerStatus& status() const override { return status_; }
  const Params& params() const { return params_; }

 protected:
  ~ExplorerBase() = default;
  // The strategy on checked input (finite pose, scan of the configured geometry, time not
  // going backwards). Writes out.mode, the x/y of out.position_m or out.velocity_mps, and the
  // heading target; the base adds altitude and time stamp and applies the limits.
  virtual Status plan(const Pose2& pose, const LaserScan& scan, TimeUs now, GuidanceSetpoint& out,
                      float& heading_target) = 0;
  virtual Status configure_strategy() { return Status::kOk; }
  bool configured() const { return configured_; }
  virtual void reset_strategy() {}

  // The field of equations 2-4 in the world frame, recorded in the status.
  Eigen::Vector2f wall_following_velocity(const LaserScan& scan, float heading_rad);

  Params params_{};
  WallFollowField field_;
  ExplorerStatus status_{};

 private:
  void hold(const NavState& nav, TimeUs now, GuidanceSetpoint& out) const;
  // The approach limiter on a world-frame command, recorded in the status.
  Eigen::Vector2f limit_approach(const LaserScan& scan, const Pose2& pose, const Eigen::Vector2f& v);

  ApproachLimiter approach_;
  YawRateLimiter yaw_;
  LookAcross look_;
  Point2 last_position_{};
  bool have_position_ = false;
  TimeUs last_time_{};
  bool have_time_ = false;
  bool configured_ = false;
};

}  // namespace kestrel::exploration
