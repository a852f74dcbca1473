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
  // The ranges documented beside each field; every test written !(within) to refuse NaN.
  if (!(k_pitch > 0 && k_pitch <= 100)) return "vehicle.k_pitch must be in (0, 100] m/s^2 per rad";
  if (!(std::fabs(b_pitch) <= 10)) return "vehicle.b_pitch must be in [-10, 10] m/s^2";
  if (!(k_roll > 0 && k_roll <= 100)) return "vehicle.k_roll must be in (0, 100] m/s^2 per rad";
  if (!(std::fabs(b_roll) <= 10)) return "vehicle.b_roll must be in [-10, 10] m/s^2";
  if (!(k_thrust > 0 && k_thrust <= 200)) return "vehicle.k_thrust must be in (0, 200] m/s^2";
  if (!(std::fabs(b_thrust) <= 50)) return "vehicle.b_thrust must be in [-50, 50] m/s^2";
  if (!(k_yaw > 0 && k_yaw <= 10)) return "vehicle.k_yaw must be in (0, 10]";
  if (!(std::fabs(b_yaw) <= 10)) return "vehicle.b_yaw must be in [-10, 10] rad/s";
  if (!(attitude_tau_s >= 0 && attitude_tau_s <= 10)) return "vehicle.attitude_tau_s must be in [0, 10] s";
  if (!(max_tilt_rad > 0 && max_tilt_rad < 1.5)) return "vehicle.max_tilt_rad must be in (0, 1.5)";
  if (!(max_yaw_rate_radps > 0 && max_yaw_rate_radps <= 20))
    return "vehicle.max_yaw_rate_radps must be in (0, 20] rad/s";
  if (!(gust_std_mps2 >= 0 && gust_std_mps2 <= 20)) return "vehicle.gust_std_mps2 must be in [0, 20] m/s^2";
  if (!(gust_tau_s > 0 && gust_tau_s <= 3600)) return "vehicle.gust_tau_s must be in (0, 3600] s";
  if (!(body_radius_m > 0 && body_radius_m <= 5)) return "vehicle.body_radius_m must be in (0, 5] m";
  if (!(body_height_m > 0 && body_height_m <= 5)) return "vehicle.body_height_m must be in (0, 5] m";
  if (!(step_s >= 1e-5 && step_s <= 0.01)) return "vehicle.step_s must be in [1e-5, 0.01]";
  if (std::fabs(step_s * 1e6 - std::round(step_s * 1e6)) > 1e-6)
    return "vehicle.step_s must be a whole number of microseconds";
  return "";
}

}  // namespace kestrel::sim
