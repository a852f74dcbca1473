#pragma once
// A fake Hokuyo behind hal::LaserScanner. The rotating mirror takes beam i at
// stamp + i * beam_interval; each beam is cast from the vehicle's true pose at that instant
// (interpolated within the 1 ms physics step), so a scan taken while the vehicle turns or
// accelerates is skewed exactly as a real one. Each range gets the datasheet noise, is
// rounded to millimetres, and is replaced by a range_code when there is no return (nothing in
// range, glass), the target is nearer than the minimum range, or the return drops out.
// Optional mirror-deflected beams feed a SimAltimeter.
#include "kestrel/core/messages.hpp"
#include "kestrel/hal/laser_scanner.hpp"
#include "kestrel/sim/laser_params.hpp"
#include "kestrel/sim/random.hpp"
#include "kestrel/sim/ray_caster.hpp"
#include "kestrel/sim/sim_altimeter.hpp"
#include "kestrel/sim/vehicle.hpp"

namespace kestrel::sim {

class SimLaser final : public hal::LaserScanner {
 public:
  SimLaser(const LaserParams& params, RayCaster& caster, Rng rng, SimAltimeter* altimeter);

  hal::LaserGeometry geometry() const override { return geometry_; }
  // Newest complete scan not yet read: kOk, or kNoData.
  Status poll(LaserScan& out) override;

  // Casts every beam whose time lies in (before.stamp, after.stamp], interpolating the pose.
  // Returns true when a scan was completed in this step (then last_scan() holds it).
  bool on_step(const VehicleState& before, const VehicleState& after);
  const LaserScan& last_scan() const { return ready_; }
  const LaserParams& params() const { return p_; }
  uint64_t scans_completed() const { return completed_; }

 private:
  uint16_t measure(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir);

  LaserParams p_;
  hal::LaserGeometry geometry_;
  RayCaster& caster_;
  Rng rng_;
  Rng railing_rng_;
  SimAltimeter* altimeter_;
  int beams_ = 0;
  int deflected_ = 0;
  Duration interval_;
  Duration period_;
  Eigen::Vector3d mount_ = Eigen::Vector3d::Zero();
  LaserScan building_;
  LaserScan ready_;
  int next_beam_ = 0;
  TimeUs next_scan_start_;
  bool fresh_ = false;
  uint64_t completed_ = 0;
  double deflected_sum_ = 0;
  int deflected_hits_ = 0;
};

}  // namespace kestrel::sim
