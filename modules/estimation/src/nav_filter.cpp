#include "kestrel/estimation/nav_filter.hpp"

#include <Eigen/LU>  // 3x3 inverse with check: its definition lives in the LU module
#include <algorithm>
#include <cmath>
#include <limits>

#include "kestrel/core/angle.hpp"

namespace kestrel::estimation {
namespace {

bool finite3(const Eigen::Vector3f& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }
bool within(const Eigen::Vector3f& v, float limit) { return v.cwiseAbs().maxCoeff() <= limit; }

// Sets the height to a reading outright: its variance is the reading's, uncorrelated with the
// velocity and bias, which keep their estimates. `delta` is the reading's offset from the slot.
void set_height(AxisState& a, float height, float variance, float delta) {
  a.x(0) = height - delta * a.x(1);
  a.P.row(0).setZero();
  a.P.col(0).setZero();
  a.P(0, 0) = variance;
}

}  // namespace

NavFilter::NavFilter(const EkfParams& params) : params_(params) {}

Status NavFilter::set_params(const EkfParams& params) {
  const Status s = validate(params);
  if (ok(s)) params_ = params;
  return s;
}

void NavFilter::reset() {
  first_ = count_ = 0;
  log_first_ = log_count_ = 0;
  initialised_ = false;
  cur_ = Filters{};
  attitude_ = Input{};
  frame_correction_ = Pose2{};
  have_imu_ = have_height_ = false;
  counters_ = NavFilterCounters{};
}

std::optional<float> NavFilter::weighed_floor_m() const {
  const Filters& f = cur_;
  const bool jumped = run_jumped(f);
  if (params_.altitude_relock_s <= 0.0f || f.heights_rejected < kWeighedMinRejected || !jumped ||
      !(f.rejected_run_s - f.run_newest_s <= kWeighedStaleS) || !std::isfinite(f.run_last_nu))
    return std::nullopt;
  return f.floor_m - f.run_last_nu;
}

Duration NavFilter::history_span() const { return count_ == 0 ? Duration{} : slot(count_ - 1).t - slot(0).t; }

void NavFilter::set_attitude(const FlightStatus& status) {
  // Also rejects NaN: the comparisons are false.
  if (!(std::fabs(status.roll_rad) <= kPi<float>) || !(std::fabs(status.pitch_rad) <= kPi<float>)) return;
  attitude_.roll = status.roll_rad;
  attitude_.pitch = status.pitch_rad;
}

void NavFilter::initialise(TimeUs t, const Pose2& pose) {
  Filters f;
  const float pos[3] = {pose.x, pose.y, have_height_ ? last_height_ : 0.0f};
  for (std::size_t i = 0; i < 3; ++i) {
    f.ax[i].x << pos[i], 0.0f, 0.0f;
    f.ax[i].P = Eigen::Vector3f(params_.init_pos_var, params_.init_vel_var, params_.init_accel_bias_var).asDiagonal();
  }
  f.height_known = have_height_;
  f.hd.x << pose.theta, 0.0f;
  f.hd.P = Eigen::Vector2f(params_.init_heading_var, params_.init_gyro_bias_var).asDiagonal();
  log_first_ = log_count_ = 0;
  initialised_ = true;
  if (count_ > 0 && t < slot(0).t) {
    // The pose is older than every IMU sample taken in before it (the laser's first beam came
    // before the IMU's first sample, as on a board where both start together).
    if ((slot(0).t - t).seconds() > params_.max_imu_gap_s) {
      // By more than a gap: nothing carries the state from the pose to the first sample. Start
      // at the first sample, as if the pose had been taken then.
      ++counters_.imu_gaps;
      t = slot(0).t;
    } else if ((slot(count_ - 1).t - t).seconds() >= params_.max_imu_gap_s) {
      // The samples reach a gap or more past the pose: dropped, they would leave the next
      // sample a gap's step from the pose. Keep them and put the pose in front.
      if (count_ == kHistory) {
        first_ = (first_ + 1) % kHistory;
        --count_;
      }
      first_ = (first_ + kHistory - 1) % kHistory;
      ++count_;
      slot(0).t = t;
      slot(0).in = slot(1).in;
    }
    // Otherwise one step of less than a gap covers them: the history starts at the pose.
  }
  if (count_ == 0 || t < slot(0).t) {
    // No stored input covers the pose's time: start the history at it.
    first_ = 0;
    count_ = 1;
    Slot& s = slots_[0];
    s.t = t;
    s.in = attitude_;
    s.in.accel = Eigen::Vector3f(0.0f, 0.0f, params_.gravity_mps2);
    s.prior = f;
    cur_ = f;
    return;
  }
  // IMU samples stored before the first pose: start at the slot of the pose's time and
  // propagate through the later ones, so the first pose is handled like a late measurement.
  const std::size_t k = slot_at(t);
  first_ = (first_ + k) % kHistory;
  count_ -= k;
  slot(0).prior = f;
  for (std::size_t i = 1; i < count_; ++i) {
    propagate(slot(i - 1).prior, slot(i).prior, slot(i).in, static_cast<float>((slot(i).t - slot(i - 1).t).seconds()));
  }
  cur_ = slot(count_ - 1).prior;
}

void NavFilter::propagate(const Filters& from, Filters& to, const Input& in, float dt) const {
  to = from;
  const float w = in.gyro_z - from.hd.x(1);
  const float psi_mid = from.hd.x(0) + 0.5f * w * dt;
  heading_predict(to.hd, in.gyro_z, dt, params_.gyro_noise, params_.gyro_bias_walk);

  // Body to world: Rz(psi) Ry(pitch) Rx(roll), right-handed rotations of FlightStatus.
  Eigen::Vector3f f = in.accel;
  if (in.roll != 0.0f) {
    const float cr = std::cos(in.roll), sr = std::sin(in.roll);
    f = Eigen::Vector3f(f.x(), cr * f.y() - sr * f.z(), sr * f.y() + cr * f.z());
  }
  if (in.pitch != 0.0f) {
    const float cp = std::cos(in.pitch), sp = std::sin(in.pitch);
    f = Eigen::Vector3f(cp * f.x() + sp * f.z(), f.y(), -sp * f.x() + cp * f.z());
  }
  const float c = std::cos(psi_mid), s = std::sin(psi_mid);
  const Eigen::Vector3f u(c * f.x() - s * f.y(), s * f.x() + c * f.y(), f.z() - params_.gravity_mps2);

  // The bias lives in the body frame; its world-frame pair turns with the vehicle.
  const float dpsi = w * dt;
  const float bx = to.ax[0].x(2), by = to.ax[1].x(2);
  to.ax[0].x(2) = bx - dpsi * by;
  to.ax[1].x(2) = by + dpsi * bx;

  const float heading_var_accel = (u.x() * u.x() + u.y() * u.y()) * from.hd.P(0, 0);
  const AxisNoise qh{params_.accel_noise_xy, params_.accel_bias_walk, params_.position_walk};
  const AxisNoise qz{params_.accel_noise_z, params_.accel_bias_walk, params_.position_walk};
  axis_predict(to.ax[0], u.x(), dt, qh, heading_var_accel);
  axis_predict(to.ax[1], u.y(), dt, qh, heading_var_accel);
  axis_predict(to.ax[2], u.z(), dt, qz, 0.0f);
  to.accel_world = u - Eigen::Vector3f(to.ax[0].x(2), to.ax[1].x(2), to.ax[2].x(2));
  to.yaw_rate = in.gyro_z - to.hd.x(1);
  if (to.heights_rejected > 0) to.rejected_run_s += dt;
}

Status NavFilter::predict(const ImuSample& imu) {
  if (!finite3(imu.accel_mps2) || !finite3(imu.gyro_radps)) {
    ++counters_.imu_not_finite;
    return Status::kNotFinite;
  }
  if (!within(imu.accel_mps2, kMaxAccelMps2) || !within(imu.gyro_radps, kMaxGyroRadps)) {
    ++counters_.imu_out_of_range;
    return Status::kOutOfRange;
  }
  if (have_imu_ && imu.stamp <= last_imu_t_) {
    ++counters_.imu_time_backwards;
    return Status::kTimeJump;
  }
  if (count_ > 0 && imu.stamp <= slot(count_ - 1).t) {
    // In order, but before the time the first pose set (the pose was taken in ahead of the
    // samples queued behind it): the state starts later, so there is nothing to step.
    have_imu_ = true;
    last_imu_t_ = imu.stamp;
    ++counters_.imu_before_start;
    return Status::kNoData;
  }
  // A gap is time between IMU samples. The newest slot is normally the previous sample; right
  // after a first pose older than the few samples taken in before it, it is the pose, and the
  // next sample's step from there covers the dropped ones (less than a gap plus one sample
  // period: initialise()). Measured from the pose, that step looked like a gap at the boundary.
  const bool had_sample = have_imu_;
  const Duration since_previous_sample = imu.stamp - last_imu_t_;
  have_imu_ = true;
  last_imu_t_ = imu.stamp;
  Input in = attitude_;
  in.accel = imu.accel_mps2;
  in.gyro_z = imu.gyro_radps.z();
  if (!initialised_) {
    // Keep the inputs: the first pose may be stamped before this sample.
    if (count_ > 0 && (imu.stamp - slot(count_ - 1).t).seconds() > params_.max_imu_gap_s) count_ = 0;
    if (count_ == kHistory) {
      first_ = (first_ + 1) % kHistory;
      --count_;
    }
    slot(count_).t = imu.stamp;
    slot(count_).in = in;
    ++count_;
    return Status::kNoData;
  }
  const float dt = static_cast<float>((imu.stamp - slot(count_ - 1).t).seconds());
  // The shorter of the two: a sample dropped as before the start (imu_before_start) is a sample
  // of the stream, but the step runs from the start, whose time may lie well after it.
  const float gap = had_sample ? std::min(dt, static_cast<float>(since_previous_sample.seconds())) : dt;
  if (gap > params_.max_imu_gap_s) {
    // Coast over the gap at constant velocity (no trustworthy input), then restart the
    // history here: nothing before the gap can be replayed across it.
    ++counters_.imu_gaps;
    for (AxisState& a : cur_.ax) {
      axis_predict(a, a.x(2), dt, AxisNoise{params_.accel_noise_xy, params_.accel_bias_walk, params_.position_walk},
                   0.0f);
    }
    heading_predict(cur_.hd, cur_.hd.x(1), dt, params_.gyro_noise, params_.gyro_bias_walk);
    cur_.accel_world.setZero();
    cur_.yaw_rate = 0.0f;
    // A run of rejected heights lasts in time, not in IMU samples: it spans the gap when its
    // readings on either side of it agree.
    if (cur_.heights_rejected > 0) cur_.rejected_run_s += dt;
    first_ = 0;
    count_ = 1;
    log_first_ = log_count_ = 0;
    slots_[0].t = imu.stamp;
    slots_[0].in = in;
    slots_[0].prior = cur_;
    return Status::kTimeJump;
  }

  if (count_ == kHistory) {
    first_ = (first_ + 1) % kHistory;
    --count_;
  }
  Slot& s = slot(count_);
  s.t = imu.stamp;
  s.in = in;
  propagate(cur_, s.prior, in, dt);
  ++count_;
  cur_ = s.prior;
  ++counters_.imu_samples;
  return Status::kOk;
}

Status NavFilter::update_pose(const PoseMeasurement2& meas) {
  if (!meas.pose.finite() || !meas.covariance.allFinite()) {
    ++counters_.meas_not_finite;
    return Status::kNotFinite;
  }
  if (!(meas.covariance(0, 0) > 0.0f && meas.covariance(1, 1) > 0.0f && meas.covariance(2, 2) > 0.0f)) {
    ++counters_.meas_not_finite;
    return Status::kInvalidArgument;
  }
  if (!(std::fabs(meas.pose.x) <= kMaxNavCoordinateM && std::fabs(meas.pose.y) <= kMaxNavCoordinateM)) {
    ++counters_.meas_out_of_range;
    return Status::kOutOfRange;
  }
  const Pose2 w = frame_correction_.compose(meas.pose);
  if (!initialised_) {
    initialise(meas.stamp, w);
    ++counters_.pose_updates;
    return Status::kOk;
  }
  Entry e;
  e.t = meas.stamp;
  e.kind = Kind::kPose;
  e.z << w.x, w.y, w.theta;
  // Rotate the x-y block into the corrected frame; scale by the learnt factors.
  const float c = std::cos(frame_correction_.theta), s = std::sin(frame_correction_.theta);
  Eigen::Matrix3f rot = Eigen::Matrix3f::Identity();
  rot.topLeftCorner<2, 2>() << c, -s, s, c;
  e.R = rot * meas.covariance * rot.transpose();
  e.R.topLeftCorner<2, 2>() *= params_.pose_cov_scale;
  e.R.block<2, 1>(0, 2) *= std::sqrt(params_.pose_cov_scale * params_.heading_cov_scale);
  e.R.block<1, 2>(2, 0) *= std::sqrt(params_.pose_cov_scale * params_.heading_cov_scale);
  e.R(2, 2) *= params_.heading_cov_scale;
  // A pose older than a correction already applied was taken in the frame before it.
  for (std::size_t i = log_count_; i > 0 && entry(i - 1).t > e.t; --i) {
    if (entry(i - 1).kind == Kind::kCorrection) unshift(e, entry(i - 1).z);
  }
  return submit(e);
}

Status NavFilter::update_altitude(const AltimeterSample& meas) {
  if (!std::isfinite(meas.height_m) || !std::isfinite(meas.variance_m2)) {
    ++counters_.meas_not_finite;
    return Status::kNotFinite;
  }
  if (meas.variance_m2 < 0.0f) {
    ++counters_.meas_not_finite;
    return Status::kInvalidArgument;
  }
  if (!(std::fabs(meas.height_m) <= kMaxNavCoordinateM)) {
    ++counters_.meas_out_of_range;
    return Status::kOutOfRange;
  }
  if (!initialised_) {
    have_height_ = true;
    last_height_ = meas.height_m;
    return Status::kNoData;
  }
  Entry e;
  e.t = meas.stamp;
  e.kind = Kind::kAltitude;
  e.z(0) = meas.height_m;
  e.R(0, 0) = meas.variance_m2 > 0.0f ? meas.variance_m2 * params_.altimeter_var_scale : params_.altimeter_var;
  return submit(e);
}

Status NavFilter::update_at_rest(TimeUs stamp, float variance_mps2) {
  if (!std::isfinite(variance_mps2)) {
    ++counters_.meas_not_finite;
    return Status::kNotFinite;
  }
  if (!(variance_mps2 > 0.0f)) {
    ++counters_.meas_not_finite;  // as update_pose counts a non-positive variance
    return Status::kInvalidArgument;
  }
  if (!initialised_) return Status::kNoData;
  Entry e;
  e.t = stamp;
  e.kind = Kind::kAtRest;
  e.R(0, 0) = variance_mps2;
  return submit(e);
}

Status NavFilter::apply_correction(const PoseMeasurement2& slam_pose) {
  if (!slam_pose.pose.finite()) {
    ++counters_.meas_not_finite;
    return Status::kNotFinite;
  }
  if (!initialised_) return Status::kNoData;
  Entry e;
  e.t = slam_pose.stamp;
  e.kind = Kind::kCorrection;
  e.z << slam_pose.pose.x, slam_pose.pose.y, slam_pose.pose.theta;
  return submit(e);
}

std::size_t NavFilter::slot_at(TimeUs t) const {
  std::size_t lo = 0, hi = count_ - 1;  // invariant: slot(lo).t <= t
  while (lo < hi) {
    const std::size_t mid = (lo + hi + 1) / 2;
    if (slot(mid).t <= t) {
      lo = mid;
    } else {
      hi = mid - 1;
    }
  }
  return lo;
}

void NavFilter::log_trim() {
  while (log_count_ > 0 && entry(0).t < slot(0).t) {
    log_first_ = (log_first_ + 1) % kMeasurementLog;
    --log_count_;
  }
}

std::size_t NavFilter::log_insert(const Entry& e) {
  if (log_count_ == kMeasurementLog) {
    ++counters_.log_overflow;  // log_trim() ran first: the oldest is still inside the history
    log_first_ = (log_first_ + 1) % kMeasurementLog;
    --log_count_;
  }
  std::size_t i = log_count_;
  while (i > 0 && entry(i - 1).t > e.t) {
    entry(i) = entry(i - 1);
    --i;
  }
  entry(i) = e;
  ++log_count_;
  return i;
}

Status NavFilter::submit(Entry e) {
  const TimeUs newest = slot(count_ - 1).t;
  if (e.t > newest + Duration::from_s(params_.max_future_s)) {
    ++counters_.meas_future;
    return Status::kTimeJump;
  }
  if (e.t < slot(0).t) {
    ++counters_.meas_too_old;
    return Status::kOutOfRange;
  }
  log_trim();
  e.fresh = true;
  const std::size_t li = log_insert(e);
  const std::size_t k = slot_at(e.t);
  if (k == count_ - 1 && li == log_count_ - 1) return apply(cur_, entry(li), slot(k), li);

  // Late: restart from the prior at slot k and replay every logged measurement from there.
  ++counters_.replays;
  std::size_t j = li;
  while (j > 0 && entry(j - 1).t >= slot(k).t) --j;
  Filters f = slot(k).prior;
  Status result = Status::kOk;
  for (std::size_t i = k; i < count_; ++i) {
    if (i > k) {
      Slot& s = slot(i);
      propagate(f, s.prior, s.in, static_cast<float>((s.t - slot(i - 1).t).seconds()));
      f = s.prior;
      ++counters_.replayed_steps;
    }
    const TimeUs end = i + 1 < count_ ? slot(i + 1).t : TimeUs{std::numeric_limits<int64_t>::max()};
    while (j < log_count_ && entry(j).t < end) {
      const bool fresh = entry(j).fresh;
      const Status s = apply(f, entry(j), slot(i), j);
      if (fresh) result = s;
      ++j;
    }
  }
  cur_ = f;
  return result;
}

Status NavFilter::apply(Filters& f, Entry& e, const Slot& s, std::size_t log_index) {
  const float delta = static_cast<float>((e.t - s.t).seconds());
  const bool fresh = e.fresh;
  e.fresh = false;
  switch (e.kind) {
    case Kind::kPose: return apply_pose(f, e, delta, fresh);
    case Kind::kAltitude: return apply_altitude(f, e, delta, fresh);
    case Kind::kAtRest: return apply_at_rest(f, e, fresh);
    case Kind::kCorrection: break;
  }
  if (fresh) {
    // D maps the filter's pose at the correction's time onto the SLAM pose.
    const Pose2 est{f.ax[0].x(0) + delta * f.ax[0].x(1), f.ax[1].x(0) + delta * f.ax[1].x(1),
                    wrap_angle(f.hd.x(0) + delta * f.yaw_rate)};
    const Pose2 slam{e.z(0), e.z(1), wrap_angle(e.z(2))};
    const Pose2 d = slam.compose(est.inverse());
    if (!d.finite() || std::hypot(d.x, d.y) > params_.max_correction_m) {
      ++counters_.corrections_rejected;
      e.z.setZero();  // stays in the log as a no-op
      return Status::kRejected;
    }
    e.z << d.x, d.y, d.theta;
    const float c = std::cos(d.theta), sn = std::sin(d.theta);
    Eigen::Matrix2f rot;
    rot << c, -sn, sn, c;
    for (std::size_t i = log_index + 1; i < log_count_; ++i) {
      Entry& later = entry(i);
      if (later.kind != Kind::kPose) continue;
      const Pose2 p = d.compose(Pose2{later.z(0), later.z(1), later.z(2)});
      later.z << p.x, p.y, p.theta;
      const Eigen::Matrix2f rxy = rot * later.R.topLeftCorner<2, 2>() * rot.transpose();
      const Eigen::Vector2f rxt = rot * later.R.block<2, 1>(0, 2);
      later.R.topLeftCorner<2, 2>() = rxy;
      later.R.block<2, 1>(0, 2) = rxt;
      later.R.block<1, 2>(2, 0) = rxt.transpose();
    }
    frame_correction_ = d.compose(frame_correction_);
    ++counters_.corrections;
  }
  shift(f, e.z);
  return Status::kOk;
}

void NavFilter::unshift(Entry& e, const Eigen::Vector3f& d) {
  if (d.isZero(0.0f)) return;
  const Pose2 p = Pose2{d(0), d(1), d(2)}.inverse().compose(Pose2{e.z(0), e.z(1), e.z(2)});
  e.z << p.x, p.y, p.theta;
  const float c = std::cos(d(2)), s = std::sin(d(2));
  Eigen::Matrix3f rot = Eigen::Matrix3f::Identity();
  rot.topLeftCorner<2, 2>() << c, s, -s, c;
  e.R = rot * e.R * rot.transpose();
}

void NavFilter::shift(Filters& f, const Eigen::Vector3f& d) const {
  if (d.isZero(0.0f)) return;
  const float c = std::cos(d(2)), s = std::sin(d(2));
  auto rotate = [&](int row, float tx, float ty) {
    const float x = f.ax[0].x(row), y = f.ax[1].x(row);
    f.ax[0].x(row) = c * x - s * y + tx;
    f.ax[1].x(row) = s * x + c * y + ty;
  };
  rotate(0, d(0), d(1));
  rotate(1, 0.0f, 0.0f);
  rotate(2, 0.0f, 0.0f);
  const float ax = f.accel_world.x(), ay = f.accel_world.y();
  f.accel_world.x() = c * ax - s * ay;
  f.accel_world.y() = s * ax + c * ay;
  f.hd.x(0) = wrap_angle(f.hd.x(0) + d(2));
}

Status NavFilter::apply_pose(Filters& f, const Entry& e, float delta, bool count) {
  const ScalarInnovation ix = axis_position_innovation(f.ax[0], e.z(0), e.R(0, 0), delta);
  const ScalarInnovation iy = axis_position_innovation(f.ax[1], e.z(1), e.R(1, 1), delta);
  const ScalarInnovation ih = heading_innovation(f.hd, e.z(2), e.R(2, 2), delta, f.yaw_rate);
  Eigen::Matrix3f S = e.R;
  S(0, 0) = ix.s;
  S(1, 1) = iy.s;
  S(2, 2) = ih.s;
  const Eigen::Vector3f nu(ix.nu, iy.nu, ih.nu);
  float det = 0;
  Eigen::Matrix3f S_inv;
  bool invertible = false;
  S.computeInverseAndDetWithCheck(S_inv, det, invertible, 0.0f);
  const float d2 = invertible ? nu.dot(S_inv * nu) : std::numeric_limits<float>::infinity();
  if (!(det > 0.0f) || !(d2 <= params_.pose_gate_chi2)) {
    if (count) ++counters_.pose_rejected;
    return Status::kRejected;
  }
  axis_position_update(f.ax[0], ix, delta);
  axis_position_update(f.ax[1], iy, delta);
  heading_update(f.hd, ih, delta);
  if (count) ++counters_.pose_updates;
  return Status::kOk;
}

Status NavFilter::apply_altitude(Filters& f, const Entry& e, float delta, bool count) {
  if (!f.height_known) {
    // The first height sets the vertical position outright (no gate: nothing to compare with).
    set_height(f.ax[2], e.z(0) + f.floor_m, e.R(0, 0), delta);
    f.height_known = true;
    if (count) ++counters_.altitude_updates;
    return Status::kOk;
  }
  ScalarInnovation iz = axis_position_innovation(f.ax[2], e.z(0) + f.floor_m, e.R(0, 0), delta);
  if (!(iz.s > 0.0f) || !(iz.nu * iz.nu <= params_.altitude_gate_chi2 * iz.s)) {
    // A run is a sequence of readings that moves smoothly against the estimate; a jump
    // within it (a beam at a box's edge, an outlier) starts a new one from that reading.
    if (f.heights_rejected == 0 || !(std::fabs(iz.nu - f.run_last_nu) <= params_.altitude_step_tol_m)) {
      f.heights_rejected = 0;
      f.rejected_run_s = 0;
      f.run_jumped_s = -1;
      f.run_settled_nu = iz.nu;
      f.run_settled_s = 0;
      f.run_departing = false;
    }
    f.run_last_nu = iz.nu;
    f.run_newest_s = f.rejected_run_s;
    if (f.run_jumped_s < 0 && std::fabs(iz.nu - f.last_taken_nu) > params_.altitude_step_tol_m)
      f.run_jumped_s = f.rejected_run_s;
    bool departs = !(std::fabs(iz.nu - f.run_settled_nu) <= params_.altitude_step_tol_m);
    if (departs && f.run_departing) {
      f.run_settled_nu = f.run_departed_nu;
      f.run_settled_s = f.run_departed_s;
      departs = !(std::fabs(iz.nu - f.run_settled_nu) <= params_.altitude_step_tol_m);
    }
    f.run_departing = departs;
    if (departs) {
      f.run_departed_nu = iz.nu;
      f.run_departed_s = f.rejected_run_s;
    }
    if (f.heights_rejected < UINT8_MAX) ++f.heights_rejected;
    const bool decided = params_.altitude_relock_s > 0.0f && f.heights_rejected >= kRelockMinRejected &&
                         f.rejected_run_s >= params_.altitude_relock_s && std::isfinite(iz.nu);
    // A floor step jumped: its readings lay beyond the tolerance from the last one taken soon
    // after it began (kJumpWithinS: an estimate creeping out of its gate does not), and it
    // stayed (its readings settled at least kSettledShare of altitude_relock_s before now, and
    // have not moved on since; entering a box, a tilted beam meets its side face first and ramps
    // the run's first readings down to the top). A run that jumped and has not stayed yet is
    // given the time to: until kSettledShare of altitude_relock_s more, then it is decided as it
    // stands (a climb the filter does not see keeps moving). Anything else is the estimate's
    // error; so is a run met with no usable variance, which no update could weigh.
    const bool jumped = run_jumped(f);
    const bool stayed = f.rejected_run_s - f.run_settled_s >= kSettledShare * params_.altitude_relock_s;
    // Over a raised floor, a run that ends where the take-off floor would put it is that floor
    // again, however it got there: leaving a box, a tilted beam meets its side face and reads
    // heights in between, a ramp that may settle late; taken for the estimate's error, the run
    // re-locked the height on the box's floor (a simulated flight then dropped 0.9 m onto it).
    // It must have moved over the tolerance: an estimate creeping out of its gate over a floor
    // just over the tolerance high ends near where the take-off floor would put it too.
    const bool back_over_take_off_floor = f.floor_m != 0.0f && std::fabs(iz.nu) > params_.altitude_step_tol_m &&
                                          std::fabs(iz.nu - f.floor_m) <= params_.altitude_step_tol_m;
    const bool may_yet_stay = jumped && !stayed && !back_over_take_off_floor && iz.s > 0.0f &&
                              f.rejected_run_s < (1.0f + kSettledShare) * params_.altitude_relock_s;
    if (!decided || may_yet_stay) {
      if (count) ++counters_.altitude_rejected;
      return Status::kRejected;
    }
    f.heights_rejected = 0;
    if (!((jumped && stayed) || back_over_take_off_floor) || !(iz.s > 0.0f)) {
      // The estimate, not the floor, moved. The vertical velocity that carried it away is
      // suspect too, so it is loosened as well. Counted as a re-lock only, not an update.
      set_height(f.ax[2], e.z(0) + f.floor_m, e.R(0, 0), delta);
      f.ax[2].P(1, 1) += params_.altitude_relock_vel_var;
      f.last_taken_nu = 0;
      if (count) ++counters_.altitude_relocks;
      return Status::kOk;
    }
    // The floor moved under a vehicle that did not. Back within the tolerance of the take-off
    // floor it snaps to it, so that the steps' small errors do not add up over a flight of
    // boxes crossed and left (the reading then moves the height by at most the tolerance).
    f.floor_m -= iz.nu;
    if (std::fabs(f.floor_m) <= params_.altitude_step_tol_m) f.floor_m = 0;
    iz = axis_position_innovation(f.ax[2], e.z(0) + f.floor_m, e.R(0, 0), delta);
    if (count) ++counters_.floor_steps;
  }
  f.heights_rejected = 0;
  f.last_taken_nu = iz.nu;
  axis_position_update(f.ax[2], iz, delta);
  if (count) ++counters_.altitude_updates;
  return Status::kOk;
}

Status NavFilter::apply_at_rest(Filters& f, const Entry& e, bool count) {
  for (AxisState& a : f.ax) axis_velocity_update(a, axis_velocity_innovation(a, 0.0f, e.R(0, 0)));
  if (count) ++counters_.at_rest_updates;
  return Status::kOk;
}

NavState NavFilter::state() const {
  NavState n;
  if (!initialised_) return n;
  n.stamp = slot(count_ - 1).t;
  for (int i = 0; i < 3; ++i) {
    const AxisState& a = cur_.ax[static_cast<std::size_t>(i)];
    n.position_m(i) = a.x(0);
    n.velocity_mps(i) = a.x(1);
    n.position_std_m(i) = std::sqrt(std::max(a.P(0, 0), 0.0f));
  }
  n.accel_mps2 = cur_.accel_world;
  n.heading_rad = cur_.hd.x(0);
  n.yaw_rate_radps = cur_.yaw_rate;
  n.heading_std_rad = std::sqrt(std::max(cur_.hd.P(0, 0), 0.0f));
  n.valid = true;
  return n;
}

}  // namespace kestrel::estimation
