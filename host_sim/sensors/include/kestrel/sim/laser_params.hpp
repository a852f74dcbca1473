#pragma once
// Datasheet models of the two Hokuyo scanners of the papers.
//
// UTM-30LX (paper 000): 1081 beams over 270° (0.25° steps), 40 Hz, 0.1-30 m; a revolution is
// 1440 steps, so a beam is taken every 25 ms / 1440 = 17.4 µs (we use 17 µs: LaserScan holds
// whole microseconds, and every beam is cast at exactly the time LaserScan::time_of reports).
// Repeatability σ 10 mm up to 10 m, 30 mm beyond (datasheet "σ < 10 mm / < 30 mm").
//
// URG-04LX (papers 002, 004): 240° at 360°/1024 steps, 10 Hz, 0.02-4 m. The datasheet says
// 683 steps, but steps 44..725 give 682 ranges, which is what the real recording in
// ../shared/data/mines/exp2.dat holds: we use 682 beams so simulated and real scans have the
// same geometry. One beam every 100 ms / 1024 = 97.7 µs (98 µs). Accuracy ±10 mm up to 1 m and
// ±1 % beyond, used as 1σ.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>

#include "kestrel/hal/laser_scanner.hpp"
#include "kestrel/sim/config_file.hpp"

namespace kestrel::sim {

struct LaserParams {
  const char* model = "utm30lx";
  double beam_count = 1081;
  double first_angle_rad = -2.356194490192345;  // -135°
  double angle_step_rad = 0.004363323129985824;  // 0.25°
  double min_range_m = 0.1;
  double max_range_m = 30.0;
  double scan_period_s = 0.025;
  double beam_interval_us = 17;
  // Noise: σ(r) = max(sigma_near_m if r < far_from_m else sigma_far_m, sigma_rel * r).
  double sigma_near_m = 0.010;
  double sigma_far_m = 0.030;
  double far_from_m = 10.0;
  double sigma_rel = 0.0;
  double dropout_probability = 0.002;  // per beam: lost returns (dust, mixed pixels)
  // Beams at the start (right end) of the sweep deflected straight down by a mirror, for
  // height (paper 000, Figure 1); they read range_code::kDeflected in the scan. 0 = no mirror.
  double deflected_beams = 0;
  // The scanner's optical centre in the body frame (x fwd, y left, z up).
  double mount_x_m = 0.0;  // each within +-2 m of the body's centre (-1e300 flew NaN)
  double mount_y_m = 0.0;
  double mount_z_m = 0.08;

  static LaserParams utm30lx();
  static LaserParams urg04lx();
  double sigma_at(double r) const;
  hal::LaserGeometry geometry() const;
  static constexpr std::size_t kBindingCount = 16;
  void bindings(ConfigBinding (&out)[kBindingCount]);
  const char* validate() const;
};

}  // namespace kestrel::sim
