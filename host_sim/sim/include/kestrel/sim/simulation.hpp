#pragma once
// One simulated flight: owns the world, the vehicle, the fake laser, IMU, altimeter and
// autopilot and the lockstep clock, and hands them out as HAL interfaces, so the same
// autonomy code runs here and on the board. Ground truth (pose, velocity, acceleration) is
// available now and at past times for metrics.
//
// Each fixed physics step (1 ms by default): release due set-points from the autopilot's
// delay line; integrate the vehicle; test for contacts (a contact ends the flight: the vehicle
// stops where it hit); cast the laser beams falling inside the step from interpolated poses;
// take an IMU sample when due; publish autopilot status. Random numbers come from one seed,
// split into independent streams per sub-system, so equal world + config + seed give equal
// outputs.
#include <memory>
#include <vector>

#include "kestrel/hal/altimeter.hpp"
#include "kestrel/hal/clock.hpp"
#include "kestrel/hal/flight_controller.hpp"
#include "kestrel/hal/imu.hpp"
#include "kestrel/hal/laser_scanner.hpp"
#include "kestrel/sim/collision_checker.hpp"
#include "kestrel/sim/fake_autopilot.hpp"
#include "kestrel/sim/free_space_map.hpp"
#include "kestrel/sim/ray_caster.hpp"
#include "kestrel/sim/sim_altimeter.hpp"
#include "kestrel/sim/sim_clock.hpp"
#include "kestrel/sim/sim_config.hpp"
#include "kestrel/sim/sim_imu.hpp"
#include "kestrel/sim/sim_laser.hpp"
#include "kestrel/sim/vehicle.hpp"
#include "kestrel/sim/world.hpp"

namespace kestrel::sim {

// Optional tap on everything the simulation produces (recording, rendering, metrics). Called
// from inside step_until(), in time order.
class SimObserver {
 public:
  virtual ~SimObserver() = default;
  // A completed scan and the true state at the scan's stamp (its first beam).
  virtual void on_scan(const LaserScan& /*scan*/, const VehicleState& /*truth*/) {}
  virtual void on_imu(const ImuSample& /*sample*/) {}
  virtual void on_contact(const Contact& /*contact*/) {}
  // Every physics step's true state.
  virtual void on_step(const VehicleState& /*truth*/) {}
};

class Simulation {
 public:
  Simulation(World world, const SimConfig& config);
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // The HAL face.
  hal::Clock& clock() { return clock_; }
  hal::LaserScanner& laser() { return laser_; }
  hal::Imu& imu() { return imu_; }
  hal::Altimeter& altimeter() { return altimeter_; }
  hal::FlightController& flight_controller() { return autopilot_; }

  // Advances in fixed steps until now() >= t (returns at once if t has passed).
  Status step_until(TimeUs t);
  TimeUs now() const { return vehicle_.state().stamp; }
  Duration step_duration() const { return vehicle_.step_duration(); }

  // Ground truth.
  const VehicleState& truth() const { return vehicle_.state(); }
  // The true state at a past time within config().truth_history_s, interpolated linearly
  // between physics steps: kOk, or kOutOfRange.
  Status truth_at(TimeUs t, VehicleState& out) const;

  // Contacts end the flight; the vehicle stays where it hit.
  bool flight_ended() const { return !contacts_.empty(); }
  const std::vector<Contact>& contacts() const { return contacts_; }

  void set_observer(SimObserver* observer) { observer_ = observer; }

  const World& world() const { return world_; }
  const SimConfig& config() const { return cfg_; }
  RayCaster& ray_caster() { return caster_; }
  // Reachable free area of the world (built on first use, before flight).
  const FreeSpaceMap& free_space();
  SimLaser& sim_laser() { return laser_; }
  SimImu& sim_imu() { return imu_; }
  FakeAutopilot& autopilot() { return autopilot_; }

 private:
  void one_step();

  World world_;
  SimConfig cfg_;
  Rng root_rng_;
  RayCaster caster_;
  Vehicle vehicle_;
  SimAltimeter altimeter_;
  SimLaser laser_;
  SimImu imu_;
  SimClock clock_;
  FakeAutopilot autopilot_;
  CollisionChecker collision_;
  std::vector<VehicleState> history_;  // ring of the last steps, allocated once
  std::size_t history_head_ = 0;       // index of the newest
  std::size_t history_size_ = 0;
  std::vector<Contact> contacts_;
  SimObserver* observer_ = nullptr;
  std::unique_ptr<FreeSpaceMap> free_space_;
};

}  // namespace kestrel::sim
