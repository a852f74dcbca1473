#pragma once
// Parameters of the scan matcher (paper 000, section 5.1). Defaults are the paper's vehicle
// configuration: a UTM-30LX at 40 Hz, 7.5 mm map cells and 0.15 degree rotation steps.
#include <cstdint>

namespace kestrel::scan_matching {

// Cells of the likelihood map hold a scaled log-likelihood in [0, kCellMax]. The cap keeps a
// whole scan's sum (kMaxBeams * kCellMax = 64,860) inside the uint16 accumulators of the
// exhaustive search.
inline constexpr uint8_t kCellMax = 60;

struct Params {
  // --- likelihood map (5.1.1)
  float resolution_m = 0.0075f;     // map cell and translation search step
  float sigma_m = 0.015f;           // laser noise: P(d) ~ exp(-d / sigma)
  float kernel_sigmas = 3.0f;       // log-likelihood is clipped to 0 beyond this many sigma
  // --- contours (5.1.1)
  float join_base_m = 0.05f;        // always join endpoints closer than this
  float join_gap_factor = 3.0f;     // ...or closer than this many beam spacings at their range
  float join_max_m = 0.6f;          // never join farther than this (railing posts stay joined)
  uint8_t join_beam_window = 4;     // join candidates up to this many points apart in scan order
  // --- points
  float min_range_m = 0.1f;
  float max_range_m = 29.0f;        // returns at or beyond this are treated as no return
  uint16_t min_points = 20;         // fewer valid points: the scan is rejected
  // --- local map (5.1.1)
  uint8_t keyframes = 5;            // k: scans drawn in the local map (<= kMaxKeyframes)
  float min_overlap = 0.85f;        // a scan joins the map when fewer of its points fit it
  // ...or when it is farther than this fraction of the laser's reach from every key scan. Only
  // points within the laser's reach of a key scan are scored (CorrelativeSearch::rotate), so
  // a 4 m URG-04LX needs key scans every 1.2 m. 0: every point in the map scored, no such
  // key scans.
  float key_spacing_of_reach = 0.3f;
  // --- search (5.1.2)
  float angle_step_rad = 0.0026180f;  // 0.15 degree
  float max_accel_mps2 = 4.0f;        // window half-width 0.5 a dt^2, clamped below
  float max_ang_accel_radps2 = 20.0f;
  float min_window_m = 0.05f;
  float max_window_m = 0.30f;
  float min_window_rad = 0.02f;
  float max_window_rad = 0.35f;
  float prior_sigmas = 4.0f;          // window half-width in prior standard deviations
  bool multi_resolution = true;     // branch and bound; false: exhaustive image addition
  // Constant-velocity prediction: false scales the last displacement by the ratio of the scans'
  // time steps (true stamps: the vehicle); true repeats the last displacement once per scan,
  // for logs sub-sampled by distance travelled, whose stamps say little about the motion
  // between scans (intel turns 30 degrees between scans stamped 0.01 s apart).
  bool velocity_per_scan = false;
  float min_score = 0.15f;          // mean cell value / kCellMax below this: match is lost
  // A lost match never comes back by itself once the vehicle has left the map's reach: the
  // window stays within max_window_m of a prediction whose error keeps growing, against key
  // scans of a place the laser no longer sees (a 4 m URG-04LX crossing a room). After this
  // long without a fit, a scan that still has min_points restarts the local map at the
  // prediction: the absolute error so far stays, but the next scans measure the motion again
  // instead of leaving the filter on the IMU alone. 0: never restart.
  float restart_after_lost_s = 0.5f;
  // Weak motion prior, used only without a caller's prior (PosePrior): a box around the
  // constant-velocity prediction, within which a pose wins unless one outside scores more than
  // `cv_tie_fraction` better. Along a corridor whose end is out of range the score is flat
  // within about 10 % over a metre, and the plain optimum lands anywhere along it; this breaks
  // such near-ties towards the motion, and leaves clear optima (a turn, a new room) alone.
  // 0: off (the vehicle: its EKF's prior already carries the motion).
  float cv_box_m = 0.0f;            // half-width of the box, metres
  float cv_box_rad = 0.0f;          // half-width of the box, radians
  float cv_tie_fraction = 0.1f;     // outside the box, a pose must score (1 / (1 - f)) x more
  // --- covariance (5.1.3)
  uint8_t cov_half_window = 12;     // translation slice half-width, cells
  uint8_t cov_theta_steps = 8;      // rotation curve half-width, steps
  float degenerate_ratio = 25.0f;   // eigenvalue ratio that flags a degenerate geometry
  // A degenerate match whose likely region runs off the slice (a corridor) adds a key scan when
  // the newest is at least this old and was not itself taken at such a match: the local map
  // may hold only a slice of the corridor, seen through a door, which every scan along it fits
  // as well as anywhere, so the overlap rarely asks for one. One is enough until a key scan is
  // taken elsewhere; more would each take in the estimate's error along the corridor (a vehicle
  // hovering there, once a second). 0: never (the default, also the vehicle's).
  float degenerate_key_interval_s = 0.0f;
  bool subcell_refine = true;       // parabolic peak interpolation on the slice and curve
};

}  // namespace kestrel::scan_matching
