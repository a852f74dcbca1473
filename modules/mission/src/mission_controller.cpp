#include "kestrel/mission/mission_controller.hpp"

#include <algorithm>
#include <cmath>

#include "kestrel/core/angle.hpp"
#include "kestrel/core/clear_path.hpp"
#include "kestrel/mission/mission_step.hpp"
#include "kestrel/mission/trail_alignment.hpp"

namespace kestrel::mission {

const char* to_string(Phase p) {
  switch (p) {
    case Phase::kIdle: return "idle";
    case Phase::kTakeoff: return "takeoff";
    case Phase::kHover: return "hover";
    case Phase::kWaypoints: return "waypoints";
    case Phase::kExplore: return "explore";
    case Phase::kReturn: return "return";
    case Phase::kLand: return "land";
    case Phase::kLanded: return "landed";
    case Phase::kFailsafeLand: return "failsafe_land";
  }
  return "?";
}

const char* to_string(TouchdownBy b) {
  switch (b) {
    case TouchdownBy::kNone: return "none";
    case TouchdownBy::kAltimeter: return "altimeter";
    case TouchdownBy::kEstimate: return "estimate";
    case TouchdownBy::kHeldUp: return "held_up";
    case TouchdownBy::kFailsafeTimer: return "failsafe_timer";
  }
  return "?";
}

const char* to_string(MissionKind k) {
  switch (k) {
    case MissionKind::kHover: return "hover";
    case MissionKind::kWaypoints: return "waypoints";
    case MissionKind::kExplore: return "explore";
  }
  return "?";
}

namespace {
bool positive_finite(float v) { return std::isfinite(v) && v > 0; }
// Flying home: nearer than this to the carrot its bearing is noise, so the heading holds.
constexpr float kReturnFacingMinM = 0.1f;
// Flying home and landing: speed per metre to the target when nearer than one second of travel.
constexpr float kReturnGainPerS = 1.0f;
// Flying home: coming this much nearer the carrot counts as progress.
constexpr float kReturnProgressM = 0.1f;
// The flight home's shortcut: a scan older than this is taken as this old (its pose carried
// back no further; the composition passes only recent ones).
constexpr float kMaxScanAgeS = 0.5f;
// Landing at home after exploring, the estimate moved this far from home (a home
// re-localisation's fix): fly home again, facing the way, rather than sidle there descending.
constexpr float kRehomeM = 0.6f;
// Landing: the set-point ramp ends this far under the floor, so that the vehicle settles on it.
constexpr float kSettleBelowFloorM = 0.2f;
// The most one step advances the mission's clock (timers): see step().
constexpr Duration kMaxClockStep = Duration::from_us(1'000'000);
// Laying the trail back onto the scan (trail_alignment.hpp): a breadcrumb counts where it is
// this far from every return; among offsets that free as many, those that put more of them the
// wide distance from the returns win (a 1.2 m door's middle 0.2 m, where the approach limiter's
// 0.4 m leaves room either side). At most this many breadcrumbs ahead are laid, and at most
// kMaxRealignments times a mission (the flights that needed it needed it once).
constexpr float kAlignNearM = 0.3f;
constexpr float kAlignWideM = 0.5f;
constexpr std::size_t kAlignWindow = 8;
constexpr uint32_t kMaxRealignments = 8;

// Where the laser was when the scan was taken (its middle beam): the estimate carried back at
// its own rates. Turning at the return's 0.5 rad/s, a scan 0.1 s old is 0.05 rad off the
// heading now, 0.17 m at 3.5 m: too much to ignore against the clearance.
Pose2 laser_at_scan(const NavState& nav, const LaserScan& scan) {
  const TimeUs mid = scan.stamp + scan.beam_interval * static_cast<int64_t>(scan.beam_count / 2);
  const float age = std::clamp(static_cast<float>((nav.stamp - mid).seconds()), 0.0f, kMaxScanAgeS);
  return {nav.position_m.x() - nav.velocity_mps.x() * age, nav.position_m.y() - nav.velocity_mps.y() * age,
          wrap_angle(nav.heading_rad - nav.yaw_rate_radps * age)};
}
}  // namespace

bool MissionController::homing() const {
  return phase_ == Phase::kReturn || (phase_ == Phase::kLand && landing_after_flight_home());
}

Status MissionController::configure(MissionKind kind, const MissionParams& p, const IVector<Waypoint>* waypoints) {
  if (!positive_finite(p.takeoff_altitude_m) || !positive_finite(p.climb_rate_mps) ||
      !positive_finite(p.descent_rate_mps) || !positive_finite(p.arrive_radius_m) ||
      !positive_finite(p.arrive_speed_mps) || !positive_finite(p.estimate_timeout_s) ||
      !positive_finite(p.return_speed_mps) || !positive_finite(p.breadcrumb_spacing_m) ||
      !positive_finite(p.return_yaw_rate_radps) || !positive_finite(p.return_stall_s) ||
      !positive_finite(p.shortcut_clearance_m) ||
      !(std::isfinite(p.return_realign_s) && p.return_realign_s >= 0) ||
      !(std::isfinite(p.realign_max_offset_m) && p.realign_max_offset_m >= 0 && p.realign_max_offset_m <= 1.0f) ||
      !(std::isfinite(p.home_survey_rad) && p.home_survey_rad >= 0 && p.home_survey_rad <= 4.0f * kPi<float>) ||
      !(std::isfinite(p.stall_survey_radius_m) && p.stall_survey_radius_m >= 0) ||
      !(std::isfinite(p.takeoff_survey_rad) && p.takeoff_survey_rad >= 0 &&
        p.takeoff_survey_rad <= 4.0f * kPi<float>) ||
      !(std::isfinite(p.hover_duration_s) && p.hover_duration_s >= 0) ||
      !(std::isfinite(p.preflight_s) && p.preflight_s >= 0) ||
      !(std::isfinite(p.explore_time_limit_s) && p.explore_time_limit_s >= 0) ||
      !(std::isfinite(p.landed_altitude_m) && p.landed_altitude_m >= 0 && p.landed_altitude_m < p.takeoff_altitude_m))
    return Status::kInvalidArgument;
  if (p.keep_out_count > kMaxKeepOuts) return Status::kInvalidArgument;
  for (std::size_t i = 0; i < p.keep_out_count; ++i)
    if (!p.keep_out[i].valid()) return Status::kInvalidArgument;
  waypoints_.clear();
  if (kind == MissionKind::kWaypoints) {
    if (waypoints == nullptr || waypoints->empty()) return Status::kInvalidArgument;
    if (waypoints->size() > kMaxWaypoints) return Status::kCapacityExceeded;
    for (const Waypoint& w : *waypoints) {
      if (!w.position_m.allFinite() || !std::isfinite(w.heading_rad) ||
          !(std::isfinite(w.hold_s) && w.hold_s >= 0) || !(w.position_m.z() > 0))
        return Status::kInvalidArgument;
      (void)waypoints_.push_back(w);
    }
  }
  kind_ = kind;
  params_ = p;
  trail_ = BreadcrumbTrail(p.breadcrumb_spacing_m);
  phase_ = Phase::kIdle;
  touchdown_by_ = TouchdownBy::kNone;
  first_entered_at_.fill(std::nullopt);
  returned_home_ = false;
  stall_surveyed_ = false;
  shortcuts_ = 0;
  realignments_ = 0;
  seen_estimate_ = false;
  configured_ = true;
  return Status::kOk;
}

void MissionController::enter(Phase p, TimeUs now) {
  if (p != phase_ && (p == Phase::kLand || p == Phase::kFailsafeLand)) {
    touchdown_.reset();
    held_.reset();
  }
  phase_ = p;
  phase_start_ = now;
  const auto i = static_cast<std::size_t>(p);
  if (!first_entered_at_[i]) first_entered_at_[i] = now;
}

std::optional<TouchdownBy> MissionController::touchdown_word(bool by_estimate) const {
  if (const std::optional<bool> down = touchdown_.on_ground()) {
    return *down ? std::optional<TouchdownBy>(TouchdownBy::kAltimeter) : std::nullopt;
  }
  return by_estimate ? std::optional<TouchdownBy>(TouchdownBy::kEstimate) : std::nullopt;
}

void MissionController::land(TouchdownBy by, TimeUs now) {
  touchdown_by_ = by;
  enter(Phase::kLanded, now);
}

void MissionController::descend(const NavState& nav, bool estimate_ok, float dt) {
  // Aim below the floor, so that the vehicle settles on it: the take-off floor, or lower where
  // the altimeter shows the floor lower than the estimate puts it (its height off: landing by
  // it, the vehicle would hover over the floor). Never higher: a desk under the vehicle is met
  // on the way down. Once at its aim the ramp holds there; it never climbs back.
  float aim = -kSettleBelowFloorM;
  if (estimate_ok) {
    if (const std::optional<float> floor = touchdown_.floor_under(nav.position_m.z(), nav.velocity_mps.z()))
      aim = std::min(aim, *floor - kSettleBelowFloorM);
  }
  ramp_z_ = std::max(ramp_z_ - params_.descent_rate_mps * dt, std::min(ramp_z_, aim));
}

bool MissionController::first_entered(Phase p, TimeUs& at) const {
  const auto i = static_cast<std::size_t>(p);
  if (i >= kPhaseCount || !first_entered_at_[i]) return false;
  at = *first_entered_at_[i];
  return true;
}

bool MissionController::arrived(const NavState& nav, const Eigen::Vector3f& target) const {
  return (nav.position_m - target).norm() < params_.arrive_radius_m &&
         nav.velocity_mps.norm() < params_.arrive_speed_mps;
}

GuidanceSetpoint MissionController::hold(TimeUs now, const Eigen::Vector3f& p, float heading) const {
  GuidanceSetpoint s;
  s.stamp = now;
  s.mode = GuidanceSetpoint::Mode::kPosition;
  s.position_m = p;
  s.heading_rad = heading;
  return s;
}

GuidanceSetpoint MissionController::step(TimeUs now, const NavState& nav, const ExplorerOutput* explorer,
                                         const LaserScan* scan, const AltimeterSample* altitude) {
  touchdown_.observe(now, altitude, params_.landed_altitude_m, params_.estimate_timeout_s);
  const bool estimate_ok = nav.valid && nav.position_m.allFinite() && nav.velocity_mps.allFinite() &&
                           std::isfinite(nav.heading_rad);
  // The ramps integrate time between steps; a long gap (a stalled loop) must not make the
  // set-point leap, so each step advances them by at most kMaxStepS. The timers run on the
  // mission's clock t, which a step back in time does not move and a leap moves by at most
  // kMaxClockStep (more than estimate_timeout_s could usefully be: a stall still trips it).
  const Duration gap = clock_started_ ? now - last_step_ : Duration{};
  const float dt = seen_estimate_ ? std::clamp(static_cast<float>(gap.seconds()), 0.0f, kMaxStepS) : 0.0f;
  clock_ = clock_started_ ? clock_ + std::clamp(gap, Duration{}, kMaxClockStep) : now;
  clock_started_ = true;
  last_step_ = now;
  const TimeUs t = clock_;
  if (estimate_ok) {
    if (!seen_estimate_) first_estimate_ = t;
    last_valid_estimate_ = t;
    last_position_ = nav.position_m;
    last_heading_ = nav.heading_rad;
    seen_estimate_ = true;
  }
  if (!configured_ || !seen_estimate_) return hold(now, Eigen::Vector3f::Zero(), 0);

  const bool airborne = phase_ != Phase::kIdle && phase_ != Phase::kLanded && phase_ != Phase::kFailsafeLand;
  if (airborne && (t - last_valid_estimate_).seconds() > params_.estimate_timeout_s) {
    // Descend from the last height we believed in; a set-point ramp that starts elsewhere would
    // make the vehicle climb or drop.
    if (phase_ != Phase::kTakeoff && phase_ != Phase::kLand) ramp_z_ = params_.takeoff_altitude_m;
    enter(Phase::kFailsafeLand, t);
  }
  const float alt = params_.takeoff_altitude_m;

  switch (phase_) {
    case Phase::kIdle:
      // The rest before take-off is preflight_s of valid estimate without a break: an estimate
      // gone stale on the ground (a silent device) starts it again, and nothing takes off on it.
      if (!estimate_ok) {
        first_estimate_ = t;
        return hold(now, Eigen::Vector3f::Zero(), 0);
      }
      if ((t - first_estimate_).seconds() < params_.preflight_s) {
        return hold(now, {nav.position_m.x(), nav.position_m.y(), nav.position_m.z()}, nav.heading_rad);
      }
      home_ = nav.position_m;
      hold_point_ = {home_.x(), home_.y(), alt};
      hold_heading_ = nav.heading_rad;
      survey_left_rad_ = params_.takeoff_survey_rad;
      ramp_z_ = nav.position_m.z();
      enter(Phase::kTakeoff, t);
      [[fallthrough]];
    case Phase::kTakeoff: {
      ramp_z_ = std::min(alt, ramp_z_ + params_.climb_rate_mps * dt);
      const bool at_altitude = ramp_z_ >= alt && arrived(nav, hold_point_);
      if (at_altitude && kind_ == MissionKind::kExplore && survey_left_rad_ > 0) {
        const float turn = std::min(survey_left_rad_, params_.return_yaw_rate_radps * dt);
        hold_heading_ = wrap_angle(hold_heading_ + turn);
        survey_left_rad_ -= turn;
      } else if (at_altitude) {
        if (kind_ == MissionKind::kHover) {
          enter(Phase::kHover, t);
        } else if (kind_ == MissionKind::kWaypoints) {
          waypoint_index_ = 0;
          at_waypoint_ = false;
          enter(Phase::kWaypoints, t);
        } else {
          trail_.clear();
          trail_.record(nav.position_m, nav.stamp);
          enter(Phase::kExplore, t);
        }
      }
      return hold(now, {hold_point_.x(), hold_point_.y(), ramp_z_}, hold_heading_);
    }
    case Phase::kHover:
      if ((t - phase_start_).seconds() >= params_.hover_duration_s) {
        ramp_z_ = hold_point_.z();
        enter(Phase::kLand, t);
      }
      return hold(now, hold_point_, hold_heading_);
    case Phase::kWaypoints: {
      const Waypoint& w = waypoints_[waypoint_index_];
      if (arrived(nav, w.position_m)) {
        if (!at_waypoint_) {
          at_waypoint_ = true;
          arrived_at_ = t;
        }
        if ((t - arrived_at_).seconds() >= w.hold_s) {
          at_waypoint_ = false;
          if (++waypoint_index_ == waypoints_.size()) {
            hold_point_ = w.position_m;
            hold_heading_ = w.heading_rad;
            ramp_z_ = w.position_m.z();
            enter(Phase::kLand, t);
            return hold(now, hold_point_, hold_heading_);
          }
        }
      }
      const Waypoint& target = waypoints_[waypoint_index_];
      return hold(now, target.position_m, target.heading_rad);
    }
    case Phase::kExplore: {
      if (estimate_ok) trail_.record(nav.position_m, nav.stamp);
      const bool timed_out = (t - phase_start_).seconds() >= params_.explore_time_limit_s;
      if (explorer == nullptr || explorer->finished || timed_out) {
        return_index_ = trail_.size() == 0 ? 0 : trail_.size() - 1;
        progress_index_ = return_index_ + 1;  // the first return step counts as progress
        shortcut_cursor_ = 0;
        progress_at_ = t;
        // The estimate believed last: the heading is held through the flight home and landing.
        hold_heading_ = last_heading_;
        enter(Phase::kReturn, t);
        return hold(now, last_position_, hold_heading_);
      }
      GuidanceSetpoint s = explorer->setpoint;
      if (!s.position_m.allFinite() || !s.velocity_mps.allFinite() || !std::isfinite(s.heading_rad)) {
        // Not passed on: hold where the vehicle is (or home, with no estimate), velocity zero.
        const Eigen::Vector3f here = estimate_ok ? nav.position_m : home_;
        s = hold(now, {here.x(), here.y(), alt}, estimate_ok ? nav.heading_rad : hold_heading_);
        s.mode = GuidanceSetpoint::Mode::kVelocity;
        return s;
      }
      s.stamp = now;
      s.position_m.z() = alt;  // the explorer plans in the plane
      s.velocity_mps.z() = 0;
      return s;
    }
    case Phase::kReturn: {
      // Fly the trail backwards, breadcrumb by breadcrumb; the first one is where exploring
      // began, near home, so the last leg is to home itself.
      const float pass_radius = std::max(0.3f, params_.arrive_radius_m);
      // Home, wherever on the trail: an explorer may have brought the vehicle back itself (the
      // frontier explorer flies its grid's path home), and the rest of the trail would lead
      // out again. The last leg is to home itself.
      if ((nav.position_m - home_).head<2>().norm() < pass_radius) return_index_ = 0;
      Eigen::Vector3f target = breadcrumb(return_index_);
      while (return_index_ > 0 && (nav.position_m - target).head<2>().norm() < pass_radius) {
        --return_index_;
        target = breadcrumb(return_index_);
      }
      if (params_.return_shortcut && scan != nullptr && estimate_ok) {
        look_for_shortcut(nav, *scan);
        target = breadcrumb(return_index_);
      }
      if (return_index_ == 0 && arrived(nav, {home_.x(), home_.y(), alt})) {
        hold_point_ = {home_.x(), home_.y(), alt};
        ramp_z_ = alt;
        // The home survey once: home again after a fix moved it, the vehicle lands.
        survey_left_rad_ = kind_ == MissionKind::kExplore && !returned_home_ ? params_.home_survey_rad : 0.0f;
        returned_home_ = true;
        enter(Phase::kLand, t);
        return hold(now, hold_point_, hold_heading_);
      }
      // Progress is a breadcrumb passed or the carrot come nearer. Without it for
      // return_stall_s the way is blocked (the trail, drawn in the estimate's frame, now runs
      // into a wall the approach limiter will not let the vehicle hit): land where it is
      // rather than hover until the battery is gone.
      const float to_carrot = (target - nav.position_m).head<2>().norm();
      if (!estimate_ok) {
        // No position to judge progress by (or to land at): the failsafe takes over if this lasts.
      } else if (return_index_ < progress_index_ || to_carrot < progress_distance_ - kReturnProgressM) {
        progress_index_ = return_index_;
        progress_distance_ = to_carrot;
        progress_at_ = t;
      } else if ((t - progress_at_).seconds() > params_.return_stall_s) {
        hold_point_ = {nav.position_m.x(), nav.position_m.y(), alt};
        ramp_z_ = alt;
        if (kind_ == MissionKind::kExplore && !stall_surveyed_ &&
            (nav.position_m - home_).head<2>().norm() <= params_.stall_survey_radius_m) {
          survey_left_rad_ = params_.home_survey_rad;
          stall_surveyed_ = true;
        }
        enter(Phase::kLand, t);
        return hold(now, hold_point_, hold_heading_);
      }
      // Stalled a while: the trail ahead may lie off where it was flown; lay it back onto what
      // the scan shows free, once each return_realign_s. The move itself is not progress (the
      // carrot is measured afresh, the stall's clock runs on), so the stall still lands a
      // vehicle that does not move, and at most kMaxRealignments moves a mission bound the rest.
      if (params_.return_realign_s > 0 && params_.realign_max_offset_m > 0 && scan != nullptr && estimate_ok &&
          realignments_ < kMaxRealignments && (t - progress_at_).seconds() >= params_.return_realign_s &&
          (t - realigned_at_).seconds() >= params_.return_realign_s) {
        realigned_at_ = t;
        if (align_trail_with_scan(nav, *scan)) {
          target = breadcrumb(return_index_);
          progress_index_ = return_index_;
          progress_distance_ = (target - nav.position_m).head<2>().norm();
        }
      }
      // Velocity set-points, so that the composition can bound them against the laser's
      // returns (the trail was drawn in the estimate's frame, which may have drifted since), and
      // the heading turns towards the way ahead at a bounded rate, so that the laser looks
      // where the vehicle goes and the scan matcher is not shaken by a fast turn.
      const Eigen::Vector2f to_target = (target - nav.position_m).head<2>();
      const float dist = to_target.norm();
      if (dist > kReturnFacingMinM) {
        const float turn = angle_diff(std::atan2(to_target.y(), to_target.x()), hold_heading_);
        const float max_turn = params_.return_yaw_rate_radps * dt;
        hold_heading_ = wrap_angle(hold_heading_ + std::clamp(turn, -max_turn, max_turn));
      }
      // Without an estimate this step the velocity is zero (homing_velocity) and the set-point's
      // position the last one believed, never the estimate's NaN.
      GuidanceSetpoint s = hold(now, {last_position_.x(), last_position_.y(), alt}, hold_heading_);
      s.mode = GuidanceSetpoint::Mode::kVelocity;
      s.velocity_mps.setZero();
      s.velocity_mps.head<2>() = homing_velocity(to_target);
      return s;
    }
    case Phase::kLand: {
      const bool surveyed = landing_after_flight_home();
      if (kind_ == MissionKind::kExplore && surveyed && estimate_ok &&
          (nav.position_m - hold_point_).head<2>().norm() > kRehomeM) {
        // Home is a point of the estimate's frame; a fix of the estimate moved it metres off
        // (autonomy/home_fix.hpp). Turning, or descending towards it, the vehicle would move
        // there partly blind (the laser's rear arc): the flight home faces the way instead.
        // Landing short of home after a stall, the same fix shows the way home no longer runs
        // into the wall.
        return_index_ = 0;
        progress_index_ = 1;
        shortcut_cursor_ = 0;
        progress_at_ = t;
        survey_left_rad_ = 0;
        enter(Phase::kReturn, t);
        return hold(now, {nav.position_m.x(), nav.position_m.y(), alt}, hold_heading_);
      }
      if (surveyed && survey_left_rad_ > 0) {
        const float turn = std::min(survey_left_rad_, params_.return_yaw_rate_radps * dt);
        hold_heading_ = wrap_angle(hold_heading_ + turn);
        survey_left_rad_ -= turn;
      } else {
        descend(nav, estimate_ok, dt);
      }
      // Touchdown only on an estimate believed: an invalid one (zeros before the filter runs)
      // must not stop the motors in the air; if it lasts, the failsafe lands on a timer. The
      // altimeter, when it has spoken, says whether the vehicle is down: still, or low for long
      // (touchdown_sense.hpp); otherwise the estimate's height and vertical speed do. Either
      // way, a descent held up by what the altimeter does not see is down (held_descent.hpp).
      if (!estimate_ok) {
        held_.interrupt();
      } else {
        held_.observe(dt, nav.stamp, nav.position_m.z(), nav.velocity_mps.z(), ramp_z_, touchdown_.recent_height());
        const bool by_estimate =
            nav.position_m.z() < params_.landed_altitude_m && std::fabs(nav.velocity_mps.z()) < 0.2f;
        if (const std::optional<TouchdownBy> by = touchdown_word(by_estimate)) {
          land(*by, t);
        } else if (held_.held()) {
          land(TouchdownBy::kHeldUp, t);
        }
      }
      GuidanceSetpoint s = hold(now, {hold_point_.x(), hold_point_.y(), ramp_z_}, hold_heading_);
      if (kind_ != MissionKind::kExplore) return s;
      // After exploring, home is a point of the estimate's drifted frame: held as a position it
      // can lie against a wall (a landing drifted 1.4 m touched one). Velocity set-points
      // towards it let the composition bound them against the scan, as on the way home.
      s.mode = GuidanceSetpoint::Mode::kVelocity;
      s.velocity_mps.setZero();
      if (estimate_ok) s.velocity_mps.head<2>() = homing_velocity((hold_point_ - nav.position_m).head<2>());
      return s;
    }
    case Phase::kFailsafeLand: {
      // No trustworthy position: stop moving and descend; time bounds the descent because the
      // altitude estimate may be what failed.
      GuidanceSetpoint s;
      s.stamp = now;
      s.mode = GuidanceSetpoint::Mode::kVelocity;
      descend(nav, estimate_ok, dt);
      s.position_m = {last_position_.x(), last_position_.y(), ramp_z_};
      s.heading_rad = hold_heading_;
      const float fall_time = params_.takeoff_altitude_m / params_.descent_rate_mps + 3.0f;
      if (const std::optional<TouchdownBy> by =
              touchdown_word(estimate_ok && nav.position_m.z() < params_.landed_altitude_m)) {
        land(*by, t);
      } else if ((t - phase_start_).seconds() > fall_time) {
        land(TouchdownBy::kFailsafeTimer, t);
      }
      return s;
    }
    case Phase::kLanded:
      return hold(now, {hold_point_.x(), hold_point_.y(), 0}, hold_heading_);
  }
  return hold(now, hold_point_, hold_heading_);
}

bool MissionController::align_trail_with_scan(const NavState& nav, const LaserScan& scan) {
  if (return_index_ == 0) return false;  // home itself is next: it does not move
  if (free_space_.build(scan, laser_at_scan(nav, scan), kAlignNearM, kAlignWideM) != Status::kOk) return false;
  // The next breadcrumbs, while near enough that the scan can show them free at any offset.
  const float reach = ScanFreeSpace::kReachM - params_.realign_max_offset_m;
  std::array<Point2, kAlignWindow> ahead;
  std::size_t n = 0;
  for (std::size_t i = return_index_; i >= 1 && n < ahead.size(); --i) {
    const Eigen::Vector3f& p = trail_.point(i);
    if ((p - nav.position_m).head<2>().squaredNorm() > reach * reach) break;
    ahead[n++] = {p.x(), p.y()};
  }
  Point2 offset;
  if (n == 0 || !find_trail_offset(free_space_, {ahead.data(), n}, params_.realign_max_offset_m,
                                   {params_.keep_out.data(), params_.keep_out_count}, params_.shortcut_clearance_m,
                                   offset))
    return false;
  trail_.move_points(return_index_ + 1 - n, return_index_, offset);
  ++realignments_;
  return true;
}

Eigen::Vector3f MissionController::breadcrumb(std::size_t i) const {
  Eigen::Vector3f p = trail_.size() > 0 && i > 0 ? trail_.point(i) : home_;
  p.z() = params_.takeoff_altitude_m;
  return p;
}

void MissionController::look_for_shortcut(const NavState& nav, const LaserScan& scan) {
  // Out of reach a breadcrumb costs a distance, in reach a pass over the beams: at most
  // kExaminedPerStep of the one and one of the other per step (the Verdex's soft float).
  constexpr std::size_t kExaminedPerStep = 64;
  if (return_index_ == 0) return;
  if (shortcut_cursor_ >= return_index_) shortcut_cursor_ = 0;
  const float reach = static_cast<float>(scan.max_range_mm) * 1e-3f - params_.shortcut_clearance_m;
  if (!(reach > 0.0f)) return;
  const Pose2 laser = laser_at_scan(nav, scan);
  const std::size_t end = std::min(return_index_, shortcut_cursor_ + kExaminedPerStep);
  for (std::size_t i = shortcut_cursor_; i < end; ++i) {
    const Eigen::Vector3f p = breadcrumb(i);
    if ((p - nav.position_m).head<2>().squaredNorm() > reach * reach) continue;
    shortcut_cursor_ = i + 1;
    bool kept_out = false;
    for (std::size_t k = 0; k < params_.keep_out_count && !kept_out; ++k)
      kept_out = params_.keep_out[k].crossed_by({nav.position_m.x(), nav.position_m.y()}, {p.x(), p.y()},
                                                params_.shortcut_clearance_m);
    if (!kept_out && straight_path_clear(scan, laser, {p.x(), p.y()}, params_.shortcut_clearance_m)) {
      return_index_ = i;
      shortcut_cursor_ = 0;
      ++shortcuts_;
    }
    return;
  }
  shortcut_cursor_ = end;
}

Eigen::Vector2f MissionController::homing_velocity(const Eigen::Vector2f& offset) const {
  const float dist = offset.norm();
  if (!(dist > 1e-3f)) return Eigen::Vector2f::Zero();
  const float speed = std::min(params_.return_speed_mps, dist * kReturnGainPerS);
  return offset * (speed / dist);
}

}  // namespace kestrel::mission
