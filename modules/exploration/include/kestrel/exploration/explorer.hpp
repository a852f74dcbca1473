#pragma once
// One small interface over the four exploration strategies the closed-loop mission compares
// side by side on the same worlds and seeds:
//   blend      paper 002 Algorithm 1: wall-following field + SRT-Star frontier velocity,
//              heading towards the waypoint (GuidanceSetpoint kVelocity);
//   wallfollow the wall-following field alone (section III), the baseline paper 002 improves
//              on (kVelocity);
//   srt        SRT-Star alone, its waypoints sent straight to the controller as position
//              set-points, as in Freda and Oriolo's original (kPosition);
//   frontier   paper 003's grid frontier exploration with a Dijkstra path to the nearest
//              frontier, flown as the blend flies (kVelocity; its grid and planner run at
//              level 3, background_step()).
// An explorer is configured once at start-up and then stepped once per laser scan with the
// newest navigation state; it never allocates after configuration.
#include <Eigen/Core>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/exploration/approach_limiter.hpp"
#include "kestrel/exploration/beam_geometry.hpp"
#include "kestrel/exploration/look_across.hpp"
#include "kestrel/exploration/params.hpp"
#include "kestrel/exploration/srt_star_planner.hpp"
#include "kestrel/exploration/wall_follow_field.hpp"

namespace kestrel::exploration {

enum class ExplorerKind : uint8_t { kBlend, kWallFollow, kSrt, kFrontier };
inline constexpr ExplorerKind kExplorerKinds[] = {ExplorerKind::kBlend, ExplorerKind::kWallFollow, ExplorerKind::kSrt,
                                                ExplorerKind::kFrontier};
const char* to_string(ExplorerKind k);
// "blend", "wallfollow", "srt" or "frontier"; kInvalidArgument otherwise.
Result<ExplorerKind> parse_explorer_kind(const char* name);

// What the last step did, for telemetry, tests and render.png.
struct ExplorerStatus {
  Status last = Status::kOk;  // of the last step (not kOk: the output was a hold)
  uint32_t steps = 0;         // steps with usable input
  uint32_t rejected = 0;      // steps answered with a hold
  bool has_target = false;
  Point2 target;                                   // current waypoint (blend, srt)
  FieldResult field;                               // wall-following field of the last scan (blend, wallfollow)
  Eigen::Vector2f v_wf = Eigen::Vector2f::Zero();  // world frame, m/s, before the speed limit
  Eigen::Vector2f v_fr = Eigen::Vector2f::Zero();  // world frame, m/s (blend)
  float heading_target_rad = 0;                    // before the yaw-rate limit (across, when looking_across)
  bool looking_across = false;                     // the heading is across a degenerate match's axis
  uint32_t look_across_turns = 0;                  // times it turned across (LookAcross), since reset
  ApproachResult approach;                         // the approach limiter on the last command
  uint32_t approach_scaled = 0;                    // commands the limiter scaled (not settled), since reset
  uint32_t approach_stops = 0;                     // ... of those, to zero
};

class Explorer {
 public:
  virtual ExplorerKind kind() const = 0;
  // kInvalidArgument for invalid parameters or geometry; the explorer is then unconfigured and
  // every step holds.
  virtual Status configure(const Params& params, const BeamGeometry& geometry) = 0;
  // Forget everything learned (tree, timers, heading command); keep the configuration.
  virtual void reset() = 0;
  // One guidance cycle on the scan just received and the newest navigation state. Always
  // writes a set-point. On bad input (unconfigured: kNotFound; invalid or non-finite NavState:
  // kNotFinite; a position beyond kMaxNavCoordinateM, messages.hpp: kOutOfRange; empty scan:
  // kNoData; scan of another geometry: kInvalidArgument; time going backwards: kTimeJump) it
  // writes a hold: kVelocity with zero velocity at the last good position, heading held, and
  // leaves the exploration state untouched.
  virtual Status step(const NavState& nav, const LaserScan& scan, GuidanceSetpoint& out) = 0;
  // The newest scan match's constraint, before the step on that scan: with
  // LookAcrossParams::after_s > 0 a long degenerate spell turns the heading across its axis
  // (look_across.hpp). Ignored otherwise.
  virtual void note_match(const MatchConstraint& m) = 0;
  // Bounds a velocity set-point from elsewhere (the flight home along the trail) with this
  // explorer's approach limiter, against the scan and the heading of nav. kOk also when the
  // limiter is off or the set-point is not kVelocity (left as it is); kInvalidArgument for an
  // unconfigured explorer, a scan of another geometry or a non-finite heading, and then the
  // horizontal velocity is zeroed: unbounded it could not be trusted near a wall.
  virtual Status bound_velocity(const NavState& nav, const LaserScan& scan, GuidanceSetpoint& setpoint) = 0;
  // Level 3 (paper 000 Figure 4): the explorer's background work, if it has any (the frontier
  // explorer's grid and planner). Called from one background thread, or in lockstep after each
  // poll in the simulator; step() never waits for it.
  virtual void background_step() {}
  // Nothing left to explore (the SRT root owns no frontier; no accessible grid frontier, and
  // the frontier explorer home again, or with no way home on its grid); never for wallfollow.
  virtual bool finished() const = 0;
  // The SRT-Star planner (tree, frontiers, waypoint) for introspection; nullptr for wallfollow
  // and frontier.
  virtual const SrtStarPlanner* planner() const = 0;
  virtual const ExplorerStatus& status() const = 0;

 protected:
  ~Explorer() = default;
};

}  // namespace kestrel::exploration
