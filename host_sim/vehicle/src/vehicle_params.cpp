#include "kestrel/sim/vehicle_params.hpp"

#include <cmath>

namespace kestrel::sim {

void VehicleParams::bindings(ConfigBinding (&out)[kBindingCount]) {
  ConfigBinding b[kBindingCount] = {
      {"vehicle.k_pitch", &k_pitch},           {"vehicle.b_pitch", &b_pitch},
      {"vehicle.k_roll", &k_roll},             {"vehicle.b_roll", &b_roll},
      {"vehicle.k_thrust", &k_thrust},         {"vehicle.b_thrust", &b_thrust},
      {"vehicle.k_yaw", &k_yaw},               {"vehicle.b_yaw", &b_yaw},
      {"vehicle.attitude_tau_s", &attitude_tau_s}, {"vehicle.max_tilt_rad", &max_tilt_rad},
      {"vehicle.max_yaw_rate_radps", &max_yaw_rate_radps},
      {"vehicle.gust_std_mps2", &gust_std_mps2}, {"vehicle.gust_tau_s", &gust_tau_s},
      {"vehicle.body_radius_m", &body_radius_m}, {"vehicle.body_height_m", &body_height_m},
      {"vehicle.step_s", &step_s}};
  for (std::size_t i = 0; i < kBindingCount; ++i) out[i] = b[i];
}

const char* VehicleParams::validate() const {
  if (!(attitude_tau_s >= 0)) return "vehicle.attitude_tau_s must be >= 0";
  if (!(max_tilt_rad > 0 && max_tilt_rad < 1.5)) return "vehicle.max_tilt_rad must be in (0, 1.5)";
  if (!(gust_std_mps2 >= 0)) return "vehicle.gust_std_mps2 must be >= 0";
  if (!(gust_tau_s > 0)) return "vehicle.gust_tau_s must be > 0";
  if (!(body_radius_m > 0 && body_height_m > 0)) return "vehicle body sizes must be > 0";
  if (!(step_s >= 1e-5 && step_s <= 0.01)) return "vehicle.step_s must be in [1e-5, 0.01]";
  if (std::fabs(step_s * 1e6 - std::round(step_s * 1e6)) > 1e-6)
    return "vehicle.step_s must be a whole number of microseconds";
  return "";
}

}  // namespace kestrel::sim
