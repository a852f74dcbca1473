#include "kestrel/sim/sim_config.hpp"

namespace kestrel::sim {

std::string SimConfig::apply(ConfigFile& file) {
  ConfigBinding vb[VehicleParams::kBindingCount];
  vehicle.bindings(vb);
  file.apply(vb, VehicleParams::kBindingCount);
  ConfigBinding lb[LaserParams::kBindingCount];
  laser.bindings(lb);
  file.apply(lb, LaserParams::kBindingCount);
  ConfigBinding ib[ImuParams::kBindingCount];
  imu.bindings(ib);
  file.apply(ib, ImuParams::kBindingCount);
  ConfigBinding sb[] = {{"sim.command_delay_s", &command_delay_s},
                        {"sim.status_rate_hz", &status_rate_hz},
                        {"sim.truth_history_s", &truth_history_s},
                        {"sim.ray_grid_cell_m", &ray_grid_cell_m},
                        {"sim.laser_sees_wall_thickness", &laser_sees_wall_thickness},
                        {"sim.laser_sees_tops_from_above", &laser_sees_tops_from_above}};
  file.apply(sb, sizeof(sb) / sizeof(sb[0]));
  const std::string unknown = file.unknown_keys();
  if (!unknown.empty()) return unknown;
  return validate();
}

std::string SimConfig::validate() const {
  if (const char* e = vehicle.validate(); *e) return e;
  if (const char* e = laser.validate(); *e) return e;
  if (const char* e = imu.validate(); *e) return e;
  if (!(command_delay_s >= 0 && command_delay_s <= 1.0)) return "sim.command_delay_s must be in [0, 1]";
  if (!(status_rate_hz >= 1 && status_rate_hz <= 1000)) return "sim.status_rate_hz must be in [1, 1000]";
  if (!(truth_history_s >= 0.1 && truth_history_s <= 60)) return "sim.truth_history_s must be in [0.1, 60]";
  if (!(ray_grid_cell_m >= 0.1 && ray_grid_cell_m <= 10)) return "sim.ray_grid_cell_m must be in [0.1, 10]";
  if (laser_sees_wall_thickness != 0 && laser_sees_wall_thickness != 1)
    return "sim.laser_sees_wall_thickness must be 0 or 1";
  if (laser_sees_tops_from_above != 0 && laser_sees_tops_from_above != 1)
    return "sim.laser_sees_tops_from_above must be 0 or 1";
  return "";
}

}  // namespace kestrel::sim
