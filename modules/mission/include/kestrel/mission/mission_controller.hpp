#pragma once
// Mission state machine, after paper 003 section 3.4: the mission is a fixed sequence of
// phases, and each phase ends on feedback (the estimate reaching a set-point, a timer, the
// explorer reporting that no frontier is left):
//
//   idle -> takeoff -> {hover | waypoints | explore -> return} -> land -> landed
//
// with a failsafe from any airborne phase: when the state estimate is invalid or stale for
// longer than `estimate_timeout_s`, the vehicle stops and descends in place (failsafe_land).
// The controller turns each phase into a GuidanceSetpoint; in the explore phase it passes the
// explorer's set-point through, pinned to the flight altitude, and records a breadcrumb trail
// that the return phase flies back along. Return, and the landing after it, fly velocity
// set-points, which the composition bounds against the laser's returns.
//
// The trail is drawn in the estimate's frame: a correction the filter takes later (SLAM, home
// fix) moves the breadcrumbs recorded since its stamp with the estimate (estimate_moved), but
// drift no correction caught leaves them where the estimate was, so a breadcrumb can come to
// lie beyond a wall (gt-building, URG-04LX: flights with the estimate within 0.1 m at the end
// held 0.4 m off the corridor's wall beside the north-west door, its breadcrumbs behind it,
// until the stall landed them 2.7 m from home). So on the way home, given the newest scan, the
// mission leaves the trail for the breadcrumb nearest home (home itself first) to which the
// scan shows a straight way clear by shortcut_clearance_m (straight_path_clear) and which
// enters no keep-out box: one such check a step, the breadcrumbs within the laser's reach
// examined in turn; and stalled return_realign_s, it lays the next breadcrumbs onto the free
// space the scan shows (align_trail_with_scan, trail_alignment.hpp).
//
// Bad input: an invalid or non-finite NavState counts towards the failsafe; a non-finite
// explorer set-point becomes a hold (velocity zero, where the vehicle is). Time: the phase
// timers run on the mission's own clock, which follows `now` but does not move when `now`
// steps back and moves at most 1 s when it leaps ahead; the ramps move at most 0.1 s a step.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "kestrel/core/keep_out.hpp"
#include "kestrel/core/messages.hpp"
#include "kestrel/core/scan_free_space.hpp"
#include "kestrel/core/static_vector.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/mission/breadcrumb_trail.hpp"
#include "kestrel/mission/held_descent.hpp"
#include "kestrel/mission/touchdown_sense.hpp"

namespace kestrel::mission {

enum class MissionKind : uint8_t { kHover, kWaypoints, kExplore };
enum class Phase : uint8_t { kIdle, kTakeoff, kHover, kWaypoints, kExplore, kReturn, kLand, kLanded, kFailsafeLand };
inline constexpr std::size_t kPhaseCount = static_cast<std::size_t>(Phase::kFailsafeLand) + 1;
// What said the vehicle was down when the mission entered kLanded: the altimeter's readings
// (touchdown_sense.hpp), the estimate's height and speed, a descent held up by something the
// altimeter does not see (held_descent.hpp), or the failsafe's timer. kNone: not landed yet.
enum class TouchdownBy : uint8_t { kNone, kAltimeter, kEstimate, kHeldUp, kFailsafeTimer };
inline constexpr std::size_t kTouchdownByCount = static_cast<std::size_t>(TouchdownBy::kFailsafeTimer) + 1;
const char* to_string(Phase p);
const char* to_string(MissionKind k);
const char* to_string(TouchdownBy b);

struct Waypoint {
  Eigen::Vector3f position_m = Eigen::Vector3f::Zero();
  float heading_rad = 0;
  float hold_s = 0;  // time to hover at the waypoint once reached
};

struct MissionParams {
  // On the ground with a valid estimate this long before take-off: resting, the filter learns
  // the accelerometer biases on every axis (zero-velocity updates), also those the laser
  // cannot observe where the vehicle starts.
  float preflight_s = 2.0f;
  float takeoff_altitude_m = 1.0f;     // flight altitude above the floor
  float climb_rate_mps = 0.5f;         // set-point ramp during take-off
  float descent_rate_mps = 0.3f;       // set-point ramp during landing
  // Below this, and slow, the vehicle has landed: by the altimeter's readings when it gives
  // them (touchdown_sense.hpp), by the estimate's height when it does not. A descent held up
  // over it by what the altimeter does not see has landed too (held_descent.hpp).
  float landed_altitude_m = 0.12f;
  float hover_duration_s = 60.0f;      // hover mission: time at the set-point
  float arrive_radius_m = 0.15f;       // a set-point is reached within this distance...
  float arrive_speed_mps = 0.2f;       // ...and below this speed
  float estimate_timeout_s = 0.5f;     // stale or invalid estimate for longer => failsafe
  float explore_time_limit_s = 600.0f; // explore phase ends after this, frontiers or not
  float return_speed_mps = 0.6f;       // cruise speed along the breadcrumb trail
  float return_yaw_rate_radps = 0.5f;  // heading turns towards the way home at most this fast
  // Explore missions: at altitude, before exploring, turn on the spot this much (at
  // return_yaw_rate_radps), so that the laser has looked all round home. 0: no turn. The
  // composition sets it for the home re-localisation (autonomy/home_fix.hpp): a 240 degree
  // laser taking off facing east never sees the wall west of home, where flights come back.
  float takeoff_survey_rad = 0.0f;
  // Explore missions: home again by the estimate, turn on the spot this much at altitude
  // before descending, so that the home re-localisation looks all round from where the
  // vehicle believes home is. 0: descend at once.
  float home_survey_rad = 0.0f;
  float return_stall_s = 30.0f;        // no progress home for this long: land where it is
  // Explore missions: a flight home stalled within this distance of home (by the estimate)
  // turns home_survey_rad on the spot before it lands there, once. Stalled near home, the trail
  // runs into a wall because the estimate has drifted; hovering still, the home re-localisation
  // finds where it is but never from a second view, which it needs to confirm (home_fix.hpp).
  // A fix that moves the vehicle 0.6 m or more re-opens the flight home. 0: land at once.
  float stall_survey_radius_m = 0.0f;
  float breadcrumb_spacing_m = 0.4f;
  bool return_shortcut = true;         // leave the trail where the scan shows a way nearer home
  float shortcut_clearance_m = 0.45f;  // ... clear by this (the approach limiter stops at 0.4 m)
  // Stalled on the way home this long, the next breadcrumbs (up to 8, within 3.1 m of the
  // vehicle less realign_max_offset_m) are laid back onto the free space the newest scan shows,
  // moved by at most realign_max_offset_m (mission/trail_alignment.hpp); again after as long
  // again while the stall lasts. 0: never (as is anything from return_stall_s on: the stall
  // lands the vehicle first).
  float return_realign_s = 5.0f;
  float realign_max_offset_m = 0.8f;  // at most 1
  // ... and entering none of these boxes grown by that clearance: the laser sees through glass,
  // the trail was flown. The composition sets them to the explorer's (iarc-arena's window: a
  // UTM-30LX flight home cut through it where the estimate had drifted 0.8 m).
  std::array<KeepOut, kMaxKeepOuts> keep_out{};
  uint8_t keep_out_count = 0;
};

// What the explorer says at this guidance step.
struct ExplorerOutput {
  GuidanceSetpoint setpoint;
  bool finished = false;  // no frontier is left
};

class MissionController {
 public:
  static constexpr std::size_t kMaxWaypoints = 64;

  // Checks parameters and waypoints (finite, positive altitudes, within capacity).
  Status configure(MissionKind kind, const MissionParams& params, const IVector<Waypoint>* waypoints = nullptr);

  // One guidance step: the set-point to fly now. `explorer` is read only in the explore phase,
  // `scan` (the newest, its laser at the vehicle's origin; nullptr: none recent) only on the way
  // home, its pose the estimate's carried back to when it was taken. `altitude` is the
  // altimeter's newest reading (nullptr: none; stamped on now's clock, older than
  // estimate_timeout_s it is stale): landing, it says when the vehicle is down.
  GuidanceSetpoint step(TimeUs now, const NavState& nav, const ExplorerOutput* explorer,
                        const LaserScan* scan = nullptr, const AltimeterSample* altitude = nullptr);

  // The estimate was corrected late: its path from `since` (the estimate's time) on moved by
  // `delta` (NavFilter::frame_correction() after * before^-1). The breadcrumbs recorded since
  // move with it. Home does not: it was taken on the ground, before any time a correction
  // reaches back to.
  void estimate_moved(TimeUs since, const Pose2& delta) { trail_.shift_since(since, delta); }

  const MissionParams& params() const { return params_; }
  Phase phase() const { return phase_; }
  bool finished() const { return phase_ == Phase::kLanded; }
  TouchdownBy touchdown_by() const { return touchdown_by_; }
  // The flight home reached home (false while under way, and after landing short of it).
  bool returned_home() const { return returned_home_; }
  // Flying home, or over where it lands after that flight (home, or where the flight home
  // stalled near it): where the home re-localisation searches (autonomy/home_fix.hpp).
  bool homing() const;
  // True while the motors should run (take-off until touchdown).
  bool wants_armed() const { return phase_ != Phase::kIdle && phase_ != Phase::kLanded; }
  // True while the vehicle rests on the ground (before take-off, after touchdown).
  bool at_rest() const { return !wants_armed(); }
  // On the mission's clock (equal to the steps' `now` unless time jumped).
  TimeUs phase_started() const { return phase_start_; }
  // When the mission first entered phase p since configure(), on the same clock; false for a
  // phase it has not entered. The flight's account: an explore phase that ended well before
  // its limit ran out of frontiers, a land soon after return began stalled on the way home.
  bool first_entered(Phase p, TimeUs& at) const;
  const Eigen::Vector3f& home() const { return home_; }
  std::size_t waypoint_index() const { return waypoint_index_; }
  const BreadcrumbTrail& trail() const { return trail_; }
  uint32_t shortcuts() const { return shortcuts_; }  // breadcrumbs skipped on the scan's word
  uint32_t realignments() const { return realignments_; }  // stretches of trail laid onto a scan
  // Time the hover phase began: the hover metric is measured from here.
  bool hovering() const { return phase_ == Phase::kHover; }

 private:
  void enter(Phase p, TimeUs now);
  void land(TouchdownBy by, TimeUs now);  // enters kLanded, saying why
  // Down by the altimeter's word when it has one (touchdown_sense.hpp), by `by_estimate` (the
  // estimate's height says so) when it has none; nullopt: not down.
  std::optional<TouchdownBy> touchdown_word(bool by_estimate) const;
  // The flight home ended over home, or stalled near it and turned there: what lands now
  // lands where the home re-localisation searches.
  bool landing_after_flight_home() const { return returned_home_ || stall_surveyed_; }
  bool arrived(const NavState& nav, const Eigen::Vector3f& target) const;
  // Landing: moves the height set-point ramp down at the descent rate to its aim below the floor.
  void descend(const NavState& nav, bool estimate_ok, float dt);
  GuidanceSetpoint hold(TimeUs now, const Eigen::Vector3f& p, float heading) const;
  // Flying home and landing there: the horizontal velocity towards a point `offset` away, at
  // the return speed until one second from it, then in proportion (arrived at, not overflown).
  Eigen::Vector2f homing_velocity(const Eigen::Vector2f& offset) const;
  // Flying home: breadcrumb i at the flight altitude, home for i = 0.
  Eigen::Vector3f breadcrumb(std::size_t i) const;
  // Examines the next breadcrumbs nearer home than return_index_ and checks the first within
  // the scan's reach; a clear way makes it the target.
  void look_for_shortcut(const NavState& nav, const LaserScan& scan);
  // Moves the next breadcrumbs to where the scan shows free space (trail_alignment.hpp); true
  // when it moved them.
  bool align_trail_with_scan(const NavState& nav, const LaserScan& scan);

  MissionKind kind_ = MissionKind::kHover;
  MissionParams params_;
  StaticVector<Waypoint, kMaxWaypoints> waypoints_;
  BreadcrumbTrail trail_;
  Phase phase_ = Phase::kIdle;
  TimeUs phase_start_;
  // When each phase was first entered since configure(); empty: not yet (first_entered).
  std::array<std::optional<TimeUs>, kPhaseCount> first_entered_at_{};
  TimeUs last_valid_estimate_;
  TimeUs last_step_;
  TimeUs clock_;  // the timers' clock: see the header comment
  bool clock_started_ = false;
  bool seen_estimate_ = false;
  TimeUs first_estimate_;
  Eigen::Vector3f last_position_ = Eigen::Vector3f::Zero();  // of the last valid estimate
  float last_heading_ = 0;
  Eigen::Vector3f home_ = Eigen::Vector3f::Zero();
  Eigen::Vector3f hold_point_ = Eigen::Vector3f::Zero();
  float hold_heading_ = 0;
  float survey_left_rad_ = 0;  // of the take-off or the home survey turn
  float ramp_z_ = 0;
  TouchdownSense touchdown_;  // the altimeter's readings since the landing began
  HeldDescent held_;          // the estimate and the ramp since the landing began
  TouchdownBy touchdown_by_ = TouchdownBy::kNone;
  std::size_t waypoint_index_ = 0;
  TimeUs arrived_at_;
  bool at_waypoint_ = false;
  std::size_t return_index_ = 0;
  std::size_t progress_index_ = 0;  // flight home: breadcrumb and carrot distance at the last progress
  float progress_distance_ = 0;
  TimeUs progress_at_;
  bool returned_home_ = false;
  bool stall_surveyed_ = false;  // the stalled flight home's turn has begun (once a mission)
  std::size_t shortcut_cursor_ = 0;  // the breadcrumb look_for_shortcut examines next
  uint32_t shortcuts_ = 0;
  TimeUs realigned_at_;
  uint32_t realignments_ = 0;
  ScanFreeSpace free_space_;  // align_trail_with_scan's, kept here: 4 kB
  bool configured_ = false;
};

}  // namespace kestrel::mission
