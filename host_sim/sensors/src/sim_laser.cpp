#include "kestrel/sim/sim_laser.hpp"

#include <algorithm>
#include <cmath>

#include "kestrel/core/angle.hpp"

namespace kestrel::sim {

SimLaser::SimLaser(const LaserParams& params, RayCaster& caster, Rng rng, SimAltimeter* altimeter)
    : p_(params),
      geometry_(params.geometry()),
      caster_(caster),
      rng_(rng.fork(1)),
      railing_rng_(rng.fork(2)),
      altimeter_(altimeter) {
  beams_ = static_cast<int>(p_.beam_count);
  deflected_ = static_cast<int>(p_.deflected_beams);
  interval_ = Duration::from_us(static_cast<int64_t>(p_.beam_interval_us));
  period_ = Duration::from_s(p_.scan_period_s);
  mount_ = Eigen::Vector3d(p_.mount_x_m, p_.mount_y_m, p_.mount_z_m);
  if (altimeter_) altimeter_->set_has_source(deflected_ > 0);
  building_.beam_count = static_cast<uint16_t>(beams_);
  building_.first_angle_rad = geometry_.first_angle_rad;
  building_.angle_step_rad = geometry_.angle_step_rad;
  building_.max_range_mm = geometry_.max_range_mm;
  building_.scan_period = period_;
  building_.beam_interval = interval_;
  next_scan_start_ = TimeUs{};  // the first sweep starts at t = 0
  building_.stamp = next_scan_start_;
}

Status SimLaser::poll(LaserScan& out) {
  if (!fresh_) return Status::kNoData;
  out = ready_;
  fresh_ = false;
  return Status::kOk;
}

uint16_t SimLaser::measure(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  const RayHit hit = caster_.cast(origin, dir, p_.max_range_m, &railing_rng_);
  if (hit.kind == RayHit::Kind::kNone) return range_code::kNoReturn;
  if (hit.range_m < p_.min_range_m) return range_code::kTooNear;
  if (rng_.bernoulli(p_.dropout_probability)) return range_code::kDropout;
  const double r = hit.range_m + p_.sigma_at(hit.range_m) * rng_.gaussian();
  const long mm = std::lround(r * 1000.0);
  if (r > p_.max_range_m) return range_code::kNoReturn;
  return static_cast<uint16_t>(std::clamp<long>(mm, kMinValidRangeMm, 65535));
}

bool SimLaser::on_step(const VehicleState& before, const VehicleState& after) {
  bool completed_now = false;
  const double step_us = static_cast<double>((after.stamp - before.stamp).us);
  if (step_us <= 0) return false;
  // The tilt barely changes within one step: take it at the step's end and turn only the
  // heading and position per beam.
  const double dyaw = wrap_angle(after.yaw_rad - before.yaw_rad);
  const Eigen::Matrix3d tilt =
      (Eigen::AngleAxisd(after.pitch_rad, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(after.roll_rad, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  while (true) {
    const TimeUs t = building_.stamp + interval_ * next_beam_;
    if (t > after.stamp) break;
    if (t > before.stamp || (t == before.stamp && before.stamp.us == 0)) {
      const double f = static_cast<double>((t - before.stamp).us) / step_us;
      const double yaw = before.yaw_rad + dyaw * f;
      const Eigen::Matrix3d rot = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * tilt;
      const Eigen::Vector3d pos = before.position_m + (after.position_m - before.position_m) * f;
      const Eigen::Vector3d origin = pos + rot * mount_;
      if (next_beam_ < deflected_) {
        const uint16_t r = measure(origin, -rot.col(2));
        if (LaserScan::is_return(r)) {
          deflected_sum_ += r * 1e-3;
          ++deflected_hits_;
        }
        building_.range_mm[static_cast<std::size_t>(next_beam_)] = range_code::kDeflected;
      } else {
        const double a = p_.first_angle_rad + p_.angle_step_rad * next_beam_;
        const Eigen::Vector3d dir_s(std::cos(a), std::sin(a), 0.0);
        building_.range_mm[static_cast<std::size_t>(next_beam_)] = measure(origin, rot * dir_s);
      }
    }
    ++next_beam_;
    if (next_beam_ == deflected_ && deflected_ > 0 && altimeter_) {
      if (deflected_hits_ > 0) {
        AltimeterSample s;
        s.stamp = building_.stamp + interval_ * (deflected_ / 2);
        s.height_m = static_cast<float>(deflected_sum_ / deflected_hits_ - p_.mount_z_m);
        const double sg = p_.sigma_at(s.height_m);
        s.variance_m2 = static_cast<float>(sg * sg / deflected_hits_);
        (void)altimeter_->push(s);
      }
      deflected_sum_ = 0;
      deflected_hits_ = 0;
    }
    if (next_beam_ == beams_) {
      ready_ = building_;
      fresh_ = true;
      completed_now = true;
      ++completed_;
      next_beam_ = 0;
      building_.stamp = building_.stamp + period_;
    }
  }
  return completed_now;
}

}  // namespace kestrel::sim
