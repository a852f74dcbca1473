#include "kestrel/sim/laser_params.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kestrel/core/messages.hpp"

namespace kestrel::sim {

LaserParams LaserParams::utm30lx() {
  LaserParams p;
  p.deflected_beams = 20;  // the MIT vehicle deflects a few beams down (paper 000, Fig. 1)
  return p;
}

LaserParams LaserParams::urg04lx() {
  LaserParams p;
  p.model = "urg04lx";
  p.beam_count = 682;
  p.angle_step_rad = 2 * 3.14159265358979323846 / 1024;
  p.first_angle_rad = -p.angle_step_rad * (682 - 1) / 2;
  p.min_range_m = 0.02;
  p.max_range_m = 4.0;
  p.scan_period_s = 0.1;
  p.beam_interval_us = 98;
  p.sigma_near_m = 0.010;
  p.sigma_far_m = 0.010;
  p.far_from_m = 1.0;
  p.sigma_rel = 0.01;
  p.dropout_probability = 0.005;
  p.deflected_beams = 8;  // the same mirror as on the UTM-30LX (paper 000 Figure 1): there is no other altimeter
  p.mount_z_m = 0.05;
  return p;
}

double LaserParams::sigma_at(double r) const {
  const double abs_sigma = r < far_from_m ? sigma_near_m : sigma_far_m;
  return std::max(abs_sigma, sigma_rel * r);
}

hal::LaserGeometry LaserParams::geometry() const {
  hal::LaserGeometry g;
  g.beam_count = static_cast<uint16_t>(beam_count);
  g.first_angle_rad = static_cast<float>(first_angle_rad);
  g.angle_step_rad = static_cast<float>(angle_step_rad);
  g.min_range_mm = static_cast<uint16_t>(std::lround(min_range_m * 1000));
  g.max_range_mm = static_cast<uint16_t>(std::min(65535L, std::lround(max_range_m * 1000)));
  g.scan_period = Duration::from_s(scan_period_s);
  return g;
}

void LaserParams::bindings(ConfigBinding (&out)[kBindingCount]) {
  ConfigBinding b[kBindingCount] = {
      {"laser.beam_count", &beam_count},         {"laser.first_angle_rad", &first_angle_rad},
      {"laser.angle_step_rad", &angle_step_rad}, {"laser.min_range_m", &min_range_m},
      {"laser.max_range_m", &max_range_m},       {"laser.scan_period_s", &scan_period_s},
      {"laser.beam_interval_us", &beam_interval_us}, {"laser.sigma_near_m", &sigma_near_m},
      {"laser.sigma_far_m", &sigma_far_m},       {"laser.far_from_m", &far_from_m},
      {"laser.sigma_rel", &sigma_rel},           {"laser.dropout_probability", &dropout_probability},
      {"laser.deflected_beams", &deflected_beams}, {"laser.mount_x_m", &mount_x_m},
      {"laser.mount_y_m", &mount_y_m},           {"laser.mount_z_m", &mount_z_m}};
  for (std::size_t i = 0; i < kBindingCount; ++i) out[i] = b[i];
}

const char* LaserParams::validate() const {
  if (!(beam_count >= 1 && beam_count <= static_cast<double>(kMaxBeams)) || beam_count != std::floor(beam_count))
    return "laser.beam_count must be a whole number in [1, 1081]";
  if (!(min_range_m >= 0.02 && max_range_m > min_range_m && max_range_m <= 65.0))
    return "laser ranges must satisfy 0.02 <= min_range_m < max_range_m <= 65";
  if (!(beam_interval_us >= 1) || beam_interval_us != std::floor(beam_interval_us))
    return "laser.beam_interval_us must be a whole number >= 1";
  // Upper bounds keep the values inside what the simulator converts them to (int64 us, float).
  if (!(scan_period_s <= 10)) return "laser.scan_period_s must be at most 10";
  constexpr double kTwoPi = 2 * std::numbers::pi;
  if (!(std::fabs(first_angle_rad) <= kTwoPi && std::fabs(angle_step_rad) <= kTwoPi))
    return "laser angles must lie within [-2 pi, 2 pi]";
  if (!fan_angles_well_formed(beam_count, first_angle_rad, angle_step_rad))
    return "laser.angle_step_rad must be at least 1e-4 rad either way, and beam_count steps at most one turn";
  if (!(scan_period_s * 1e6 >= beam_interval_us * beam_count))
    return "laser.scan_period_s is shorter than the sweep (beam_count * beam_interval_us)";
  if (!(sigma_near_m >= 0 && sigma_far_m >= 0 && sigma_rel >= 0)) return "laser noise must be >= 0";
  if (!(dropout_probability >= 0 && dropout_probability <= 1))
    return "laser.dropout_probability must be in [0, 1]";
  if (!(deflected_beams >= 0 && deflected_beams < beam_count) || deflected_beams != std::floor(deflected_beams))
    return "laser.deflected_beams must be a whole number below beam_count";
  if (!(std::fabs(mount_x_m) <= 2 && std::fabs(mount_y_m) <= 2 && std::fabs(mount_z_m) <= 2))
    return "laser.mount_x_m, mount_y_m and mount_z_m must each be in [-2, 2] m";
  return "";
}

}  // namespace kestrel::sim
