#pragma once
// Parameters of the compact SLAM (paper 004's modified CoreSLAM). All floats, described once
// as a ParamField table (param_file.hpp) that both checks them and reads them from a file.
#include <array>

#include "kestrel/core/status.hpp"
#include "kestrel/params/param_file.hpp"

namespace kestrel::slam {

struct SlamParams {
  // --- map (slam_map.hpp)
  float cell_m = 0.06f;           // cell side; the 1024-cell map spans 1024 times this
  float hole_width_m = 0.4f;      // width of the V drawn across each return (CoreSLAM's "hole")
  float clear_reach_m = 4.0f;     // how far before each return its ray clears the map
  float weight = 30.0f;           // how far a cell moves towards a return's profile, of 256
  // A scan is drawn only when the sensor has moved this far or turned this much since the last
  // scan drawn: a hovering vehicle would otherwise redraw its own error into the map ten
  // times a second, and the map would follow the filter instead of holding it.
  float draw_every_m = 0.3f;
  float draw_every_rad = 0.2f;
  // A scan due to be drawn is drawn only where the fit's curvature, over the returns on cells
  // the map knows, is at least this in both directions (levels/m^2): where what the map holds
  // pins the pose, so that a pose drifted along a direction the map cannot tell (a wall with no
  // corner in reach) draws nothing. 0 draws wherever due (CoreSLAM).
  float draw_min_curvature = 0.0f;
  // --- search (scan_fit.hpp)
  float iterations = 200.0f;      // Monte Carlo candidates per scan
  float sigma_xy_m = 0.08f;       // first spread of the candidates around the best so far
  float sigma_theta_rad = 0.03f;
  float anchor_per_m2 = 200.0f;   // levels a candidate pays per m^2 from the filter's pose
  float anchor_per_rad2 = 500.0f; // ...and per rad^2
  float min_curvature = 2000.0f;  // levels/m^2: flatter directions keep the filter's position
  float max_points = 300.0f;      // the scan's returns are thinned to at most this many
  float min_points = 30.0f;       // fewer: the scan is neither matched nor drawn
  // --- corrections
  float warmup_scans = 10.0f;     // the first scans only draw the map, at the filter's pose
  float max_fit_level = 90.0f;    // the best pose's mean map value (0 wall .. 255 free) must be below
  float min_gain_level = 6.0f;    // ...and this much below the filter pose's
  float max_correction_m = 0.5f;  // a larger correction is refused (the match jumped)
  float max_correction_rad = 0.1f;
};

inline constexpr std::size_t kSlamParamCount = 20;
std::array<params::ParamField, kSlamParamCount> slam_param_fields(SlamParams& p);
Status validate(const SlamParams& p);
// Reads a parameter file over `out` (keys absent keep their values); on any error, `out` is
// unchanged and `error` names the line, or the inconsistency (min_points above max_points).
Status load_slam_params(const char* path, SlamParams& out, params::ParamError& error);

}  // namespace kestrel::slam
