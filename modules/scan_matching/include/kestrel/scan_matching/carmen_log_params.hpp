#pragma once
// The scan matcher's profile for the sub-sampled Radish/CARMEN logs (kestrel-replay and the
// real-data tests share it): one profile for every such log, never tuned per log. Laser only:
// nothing here reads a log's reference poses or odometry.
#include <cmath>

#include "kestrel/scan_matching/params.hpp"

namespace kestrel::scan_matching {

// The logs' robots move far between recorded scans (seconds apart), so the profile uses a
// coarser map than the vehicle and a wide window.
inline Params carmen_log_params() {
  Params p;
  p.resolution_m = 0.02f;
  p.sigma_m = 0.03f;
  p.angle_step_rad = 0.25f * 3.14159265f / 180.0f;
  p.max_range_m = 40.0f;
  p.max_accel_mps2 = 1.0f;
  p.max_ang_accel_radps2 = 1.0f;
  // The stamps of a sub-sampled log do not bound the motion between its scans (intel turns
  // 30 degrees between scans stamped 0.01 s apart), so the window never shrinks below what
  // such logs move between scans (about 1.2 m and 35 degrees, data/README.md), and its cap
  // leaves room for that around both the constant-velocity and the stopped hypothesis.
  // For the same reason the constant-velocity hypothesis repeats the last displacement per
  // scan instead of scaling it by the stamps' ratio (up to 2x, or 0.003x, on intel).
  p.velocity_per_scan = true;
  p.min_window_m = 1.2f;
  p.max_window_m = 2.4f;
  p.min_window_rad = 0.65f;
  p.max_window_rad = 1.3f;
  // A wall seen at a grazing angle has its returns much farther apart than the beam spacing
  // at their range (spacing / cos(incidence)): joining up to 8 spacings and 1 m keeps such
  // walls as contours instead of isolated dots (the likely cause, not proven, of the score
  // preferring poses that slide the scan back towards the key scans, where the map is dense).
  p.join_gap_factor = 8.0f;
  p.join_max_m = 1.0f;
  // Weak motion prior (Params::cv_box_m): along a corridor whose end is out of range, a
  // pose within 0.3 m / 0.15 rad of the constant-velocity prediction wins unless one
  // outside scores more than 10 % better.
  p.cv_box_m = 0.3f;
  p.cv_box_rad = 0.15f;
  p.cv_tie_fraction = 0.1f;
  p.min_score = 0.05f;
  p.cov_half_window = 12;
  return p;
}

}  // namespace kestrel::scan_matching
