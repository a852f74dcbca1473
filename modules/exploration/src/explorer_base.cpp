#include "kestrel/exploration/explorer_base.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "kestrel/core/mode_names.hpp"

namespace kestrel::exploration {
namespace {

bool usable_position(const NavState& nav) {
  return std::fabs(nav.position_m.x()) <= kMaxNavCoordinateM && std::fabs(nav.position_m.y()) <= kMaxNavCoordinateM;
}

}  // namespace

const char* to_string(ExplorerKind k) {
  switch (k) {
    case ExplorerKind::kBlend:
      return "blend";
    case ExplorerKind::kWallFollow:
      return "wallfollow";
    case ExplorerKind::kSrt:
      return "srt";
    case ExplorerKind::kFrontier:
      return "frontier";
  }
  return "unknown";
}

Result<ExplorerKind> parse_explorer_kind(const char* name) {
  return parse_by_name(name, kExplorerKinds);
}

Status ExplorerBase::configure(const Params& params, const BeamGeometry& geometry) {
  configured_ = false;
  if (params.validate() != Status::kOk) return Status::kInvalidArgument;
  if (field_.configure(geometry, params.wall) != Status::kOk) return Status::kInvalidArgument;
  if (approach_.configure(params.approach, geometry) != Status::kOk) return Status::kInvalidArgument;
  params_ = params;
  look_.configure(params.look_across);
  if (configure_strategy() != Status::kOk) return Status::kInvalidArgument;
  configured_ = true;
  reset();
  return Status::kOk;
}

void ExplorerBase::reset() {
  yaw_ = YawRateLimiter{};
  look_.reset();
  have_position_ = false;
  have_time_ = false;
  status_ = ExplorerStatus{};
  reset_strategy();
}

void ExplorerBase::hold(const NavState& nav, TimeUs now, GuidanceSetpoint& out) const {
  out = GuidanceSetpoint{};
  out.stamp = now;
  out.mode = GuidanceSetpoint::Mode::kVelocity;
  Point2 p = last_position_;
  if (!have_position_ && usable_position(nav))
    p = {nav.position_m.x(), nav.position_m.y()};
  out.position_m = {p.x, p.y, params_.guidance.altitude_m};
  out.velocity_mps.setZero();
  if (yaw_.initialised())
    out.heading_rad = yaw_.command();
  else
    out.heading_rad = std::isfinite(nav.heading_rad) ? nav.heading_rad : 0.0f;
}

Status ExplorerBase::step(const NavState& nav, const LaserScan& scan, GuidanceSetpoint& out) {
  const TimeUs now = scan.stamp;
  Status st = Status::kOk;
  if (!configured_) {
    st = Status::kNotFound;
  } else if (!nav.valid || !std::isfinite(nav.position_m.x()) || !std::isfinite(nav.position_m.y()) ||
             !std::isfinite(nav.heading_rad)) {
    st = Status::kNotFinite;
  } else if (!usable_position(nav)) {
    st = Status::kOutOfRange;
  } else if (scan.beam_count == 0) {
    st = Status::kNoData;
  } else if (!field_.geometry().matches(scan)) {
    st = Status::kInvalidArgument;
  } else if (have_time_ && now < last_time_) {
    st = Status::kTimeJump;
  }
  if (st != Status::kOk) {
    hold(nav, now, out);
    status_.last = st;
    ++status_.rejected;
    return st;
  }

  const Pose2 pose{nav.position_m.x(), nav.position_m.y(), nav.heading_rad};
  if (!yaw_.initialised()) yaw_.reset(nav.heading_rad, now);
  last_time_ = now;
  have_time_ = true;
  last_position_ = {pose.x, pose.y};
  have_position_ = true;

  out = GuidanceSetpoint{};
  out.stamp = now;
  out.position_m = {pose.x, pose.y, params_.guidance.altitude_m};
  float heading_target = yaw_.command();
  st = plan(pose, scan, now, out, heading_target);
  if (st != Status::kOk) {
    hold(nav, now, out);
    status_.last = st;
    ++status_.rejected;
    return st;
  }
  out.position_m.z() = params_.guidance.altitude_m;
  if (out.mode == GuidanceSetpoint::Mode::kVelocity) {
    Eigen::Vector2f v = limit_speed(out.velocity_mps.head<2>(), params_.guidance.speed_limit_mps);
    // Backing off a return inside the stop distance can add speed: the limit is applied again.
    if (approach_.enabled())
      v = limit_speed(limit_approach(scan, pose, v), params_.guidance.speed_limit_mps);
    out.velocity_mps = {v.x(), v.y(), 0.0f};
  }
  heading_target = look_.heading(heading_target);
  status_.heading_target_rad = heading_target;
  status_.looking_across = look_.active();
  status_.look_across_turns = look_.looks();
  out.heading_rad = yaw_.step(heading_target, now, params_.guidance.yaw_rate_limit_radps);
  status_.last = Status::kOk;
  ++status_.steps;
  return Status::kOk;
}

Status ExplorerBase::bound_velocity(const NavState& nav, const LaserScan& scan, GuidanceSetpoint& setpoint) {
  if (setpoint.mode != GuidanceSetpoint::Mode::kVelocity) return Status::kOk;
  if (!configured_ || !field_.geometry().matches(scan) || !std::isfinite(nav.heading_rad)) {
    setpoint.velocity_mps.x() = 0.0f;
    setpoint.velocity_mps.y() = 0.0f;
    return Status::kInvalidArgument;
  }
  if (!approach_.enabled()) return Status::kOk;
  const Pose2 pose{nav.position_m.x(), nav.position_m.y(), nav.heading_rad};
  const Eigen::Vector2f v = limit_approach(scan, pose, setpoint.velocity_mps.head<2>());
  setpoint.velocity_mps.x() = v.x();
  setpoint.velocity_mps.y() = v.y();
  return Status::kOk;
}

Eigen::Vector2f ExplorerBase::limit_approach(const LaserScan& scan, const Pose2& pose, const Eigen::Vector2f& v) {
  // The returns are in the body frame: the command goes there and back (equation 4 and its
  // inverse), so the limit holds whatever the estimate's position error.
  const float heading_rad = pose.theta;
  const float c = std::cos(heading_rad), s = std::sin(heading_rad);
  Eigen::Vector2f body{c * v.x() + s * v.y(), -s * v.x() + c * v.y()};
  // The operator's keep-out boxes are in the navigation frame: their nearest points, as
  // returns the laser cannot give (a glass window passes the beams; the field and the limiter
  // would otherwise let the vehicle slide into one).
  std::array<VirtualReturn, kMaxKeepOuts> boxes{};
  std::size_t n = 0;
  if (std::isfinite(pose.x) && std::isfinite(pose.y)) {
    for (std::size_t i = 0; i < params_.srt.keep_out_count && i < kMaxKeepOuts; ++i) {
      const KeepOut& k = params_.srt.keep_out[i];
      const float nx = std::clamp(pose.x, k.x_min, k.x_max), ny = std::clamp(pose.y, k.y_min, k.y_max);
      float wx = nx - pose.x, wy = ny - pose.y, range = std::hypot(wx, wy);
      if (range < 1e-3f) {
        // Inside: the "return" lies opposite the nearest way out, so backing off leaves by it.
        const float to_face[4] = {pose.x - k.x_min, k.x_max - pose.x, pose.y - k.y_min, k.y_max - pose.y};
        const float dir[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
        std::size_t best = 0;
        for (std::size_t f = 1; f < 4; ++f)
          if (to_face[f] < to_face[best]) best = f;
        wx = dir[best][0];
        wy = dir[best][1];
        range = 0.0f;
      } else {
        wx /= range;
        wy /= range;
      }
      boxes[n++] = {c * wx + s * wy, -s * wx + c * wy, range};
    }
  }
  status_.approach = approach_.limit(scan, field_.directions(), body, std::span<const VirtualReturn>(boxes.data(), n));
  if (status_.approach.scaled) ++status_.approach_scaled;
  if (status_.approach.stopped) ++status_.approach_stops;
  return WallFollowField::to_inertial(body, heading_rad);
}

Eigen::Vector2f ExplorerBase::wall_following_velocity(const LaserScan& scan, float heading_rad) {
  // The geometry was checked by step(), so the field cannot refuse the scan.
  (void)field_.body_velocity(scan, status_.field);
  status_.v_wf = WallFollowField::to_inertial(status_.field.body_mps, heading_rad);
  return status_.v_wf;
}

}  // namespace kestrel::exploration
