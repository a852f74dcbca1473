#include "kestrel/sim/simulation.hpp"

#include <cmath>

namespace kestrel::sim {
namespace {

// Independent random streams of the sub-systems (fixed ids: never renumber them).
constexpr double kPi = 3.14159265358979323846;

enum StreamId : uint64_t { kGustStream = 1, kLaserStream = 2, kImuStream = 3 };

VehicleState initial_state(const World& w) {
  VehicleState s;
  s.position_m = Eigen::Vector3d(w.start.x, w.start.y, w.start.z);
  s.yaw_rad = w.start.yaw_rad;
  s.on_ground = w.start.z <= 0;
  return s;
}

}  // namespace

Simulation::Simulation(World world, const SimConfig& config)
    : world_(std::move(world)),
      cfg_(config),
      root_rng_(config.seed),
      caster_(world_, config.ray_grid_cell_m, config.laser_walls(), config.laser_faces_over_start()),
      vehicle_(cfg_.vehicle, initial_state(world_), root_rng_.fork(kGustStream)),
      laser_(cfg_.laser, caster_, root_rng_.fork(kLaserStream), &altimeter_),
      imu_(cfg_.imu, root_rng_.fork(kImuStream)),
      clock_(*this),
      autopilot_(clock_, Duration::from_s(cfg_.command_delay_s), Duration::from_s(1.0 / cfg_.status_rate_hz)),
      collision_(world_, caster_.grid(), cfg_.vehicle.body_radius_m, cfg_.vehicle.body_height_m) {
  const auto steps = static_cast<std::size_t>(std::ceil(cfg_.truth_history_s / vehicle_.step_duration().seconds())) + 2;
  history_.assign(steps, VehicleState{});
  history_[0] = vehicle_.state();
  history_size_ = 1;
  contacts_.reserve(4);
}

const FreeSpaceMap& Simulation::free_space() {
  if (!free_space_) free_space_ = std::make_unique<FreeSpaceMap>(world_);
  return *free_space_;
}

Status Simulation::step_until(TimeUs t) {
  while (now() < t) one_step();
  return Status::kOk;
}

void Simulation::one_step() {
  const VehicleState before = vehicle_.state();
  const AttitudeSetpoint& sp = autopilot_.active(before.stamp);
  if (flight_ended()) {
    vehicle_.idle_step();
  } else {
    vehicle_.step(sp, autopilot_.armed());
    Contact c;
    if (collision_.check(vehicle_.state(), c)) {
      vehicle_.freeze();
      contacts_.push_back(c);
      if (observer_) observer_->on_contact(c);
    }
  }
  const VehicleState& after = vehicle_.state();
  history_head_ = (history_head_ + 1) % history_.size();
  history_[history_head_] = after;
  if (history_size_ < history_.size()) ++history_size_;
  if (observer_) observer_->on_step(after);

  if (laser_.on_step(before, after) && observer_) {
    VehicleState truth;
    if (truth_at(laser_.last_scan().stamp, truth) != Status::kOk) truth = after;
    observer_->on_scan(laser_.last_scan(), truth);
  }
  if (imu_.on_step(after) && observer_) observer_->on_imu(imu_.last_sample());
  autopilot_.update_status(after);
}

Status Simulation::truth_at(TimeUs t, VehicleState& out) const {
  const VehicleState& newest = history_[history_head_];
  if (t > newest.stamp) return Status::kOutOfRange;
  const int64_t step = vehicle_.step_duration().us;
  const int64_t back = (newest.stamp - t).us;
  const std::size_t k = static_cast<std::size_t>(back / step);  // steps back to the state at/after t
  if (k + 1 > history_size_) return Status::kOutOfRange;
  const std::size_t n = history_.size();
  const VehicleState& hi = history_[(history_head_ + n - k) % n];
  if (hi.stamp == t) {
    out = hi;
    return Status::kOk;
  }
  if (k + 2 > history_size_) return Status::kOutOfRange;
  const VehicleState& lo = history_[(history_head_ + n - k - 1) % n];
  const double f = static_cast<double>((t - lo.stamp).us) / static_cast<double>((hi.stamp - lo.stamp).us);
  out = hi;
  out.stamp = t;
  out.position_m = lo.position_m + (hi.position_m - lo.position_m) * f;
  out.velocity_mps = lo.velocity_mps + (hi.velocity_mps - lo.velocity_mps) * f;
  out.accel_mps2 = lo.accel_mps2 + (hi.accel_mps2 - lo.accel_mps2) * f;
  out.roll_rad = lo.roll_rad + (hi.roll_rad - lo.roll_rad) * f;
  out.pitch_rad = lo.pitch_rad + (hi.pitch_rad - lo.pitch_rad) * f;
  double dyaw = hi.yaw_rad - lo.yaw_rad;
  if (dyaw > kPi) dyaw -= 2 * kPi;
  if (dyaw < -kPi) dyaw += 2 * kPi;
  out.yaw_rad = lo.yaw_rad + dyaw * f;
  if (out.yaw_rad > kPi) out.yaw_rad -= 2 * kPi;
  if (out.yaw_rad <= -kPi) out.yaw_rad += 2 * kPi;
  return Status::kOk;
}

}  // namespace kestrel::sim
