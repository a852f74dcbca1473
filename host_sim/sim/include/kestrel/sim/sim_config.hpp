#pragma once
// Everything that parameterises a simulated run besides the world and the seed, readable
// from one `key = value` file (keys vehicle.*, laser.*, imu.*, sim.*).
#include <cstdint>
#include <string>

#include "kestrel/sim/config_file.hpp"
#include "kestrel/sim/imu_params.hpp"
#include "kestrel/sim/laser_params.hpp"
#include "kestrel/sim/vehicle_params.hpp"

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

  // Applies a parsed file on top of the current values; "" or "SOURCE:LINE: reason".
  std::string apply(ConfigFile& file);
  // "" or the first reason the configuration is unusable.
  std::string validate() const;
};

}  // namespace kestrel::sim
