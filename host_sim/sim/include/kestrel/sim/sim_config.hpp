#pragma once
// Everything that parameterises a simulated run besides the world and the seed, readable
// from one `key = value` file (keys vehicle.*, laser.*, imu.*, sim.*).
#include <cstdint>
#include <string>

#include "kestrel/sim/config_file.hpp"
#include "kestrel/sim/imu_params.hpp"
#include "kestrel/sim/laser_params.hpp"
#include "kestrel/sim/ray_caster.hpp"
#include "kestrel/sim/vehicle_params.hpp"
#include "kestrel/sim/world.hpp"

namespace kestrel::sim {

struct SimConfig {
  VehicleParams vehicle;
  LaserParams laser = LaserParams::utm30lx();
  ImuParams imu;
  uint64_t seed = 1;
  double command_delay_s = 0.02;   // sim.command_delay_s: companion computer to rotors
  double status_rate_hz = 50;      // sim.status_rate_hz: autopilot status messages
  double truth_history_s = 4.0;    // sim.truth_history_s: how far back truth_at() reaches
  double ray_grid_cell_m = 1.0;    // sim.ray_grid_cell_m
  // sim.laser_sees_wall_thickness: 1 = the laser meets a wall's faces and end caps (the box the
  // collision checker uses, World::wall_thickness_m thick), 0 = its zero-thick centre line.
  // 0 is the default every figure in the README was measured with; at 0 a doorway looks
  // wall_thickness_m wider to the laser than it is to the vehicle, and a jamb seen edge-on is
  // invisible (README, Exploration, "Not done"; measured in modules/exploration/EXPERIMENTS.md).
  double laser_sees_wall_thickness = 0;
  WallSurfaces laser_walls() const {
    return laser_sees_wall_thickness != 0 ? WallSurfaces::kBoxOutlines : WallSurfaces::kCentreLines;
  }
  // sim.laser_sees_tops_from_above: 1 = a beam starting over an obstacle's footprint meets its
  // top (the altimeter of a vehicle over a desk reads the height above the desk; a tilted scan
  // beam over it ends on it), as it is; 0 = it misses it and reads the floor, the model the
  // README's exploration figures were flown with before session 58, which hid the height
  // filter's lock-out over furniture (modules/exploration/EXPERIMENTS.md, "Obstacle tops seen
  // from above"; host_sim/sim/configs/tops_missed.cfg).
  double laser_sees_tops_from_above = 1;
  FacesOverStart laser_faces_over_start() const {
    return laser_sees_tops_from_above != 0 ? FacesOverStart::kMet : FacesOverStart::kMissed;
  }

  // Applies a parsed file on top of the current values; "" or "SOURCE:LINE: reason".
  std::string apply(ConfigFile& file);
  // "" or the first reason the configuration is unusable.
  std::string validate() const;
};

}  // namespace kestrel::sim
