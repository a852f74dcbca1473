#pragma once
// Everything the autonomy stack is configured with, one struct per module (each with its
// defaults and units inline in its own header), plus what ties them together.
#include "kestrel/autonomy/clearance_guard.hpp"
#include "kestrel/autonomy/home_fix.hpp"
#include "kestrel/autonomy/sensor_watchdog.hpp"
#include "kestrel/control/controller_params.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/static_vector.hpp"
#include "kestrel/estimation/ekf_params.hpp"
#include "kestrel/exploration/explorer.hpp"
#include "kestrel/exploration/params.hpp"
#include "kestrel/mission/mission_controller.hpp"
#include "kestrel/scan_matching/params.hpp"
#include "kestrel/slam/slam_params.hpp"

namespace kestrel::autonomy {

// The scan matcher as the vehicle runs it: 1 cm cells over the 2000-cell on-board map give a
// 20 m window, wide enough that a 15 m room's far side and a corridor's end walls constrain
// the match (scan_matcher.hpp, kOnboardMapDim).
// The controller as the vehicle flies it: position errors clipped at 0.7 m keep the approach
// speed near 0.6 m/s, so scans taken during a 25 ms sweep stay sharp for the matcher (paper
// 002 flies at 0.5 m/s for the same reason).
inline control::ControllerParams vehicle_controller_params() {
  control::ControllerParams p = control::default_controller_params();
  p.max_position_error_m = 0.7f;
  return p;
}

inline scan_matching::Params vehicle_matcher_params() {
  scan_matching::Params p;
  p.resolution_m = 0.01f;
  p.sigma_m = 0.02f;
  // The prior is the EKF's gyro-propagated heading, good to a tenth of a degree, and its
  // standard deviation sizes the rotation window; the default floor (1.15 degrees, meant for
  // a prediction from the last two matches) would only cost time: half the loop's budget.
  p.min_window_rad = 0.01f;
  // Join grazing-angle wall returns into contours as the CARMEN profile does (up to 8 beam
  // spacings and 1 m): kept as isolated dots, the far part of a corridor wall is fainter in
  // the map than the near part, and along a corridor whose ends are out of reach every match
  // slid back towards the key scans by its whole window (URG-04LX, synthetic corridor: 10 cm
  // behind on average; joined, 2 cm ahead).
  p.join_gap_factor = 8.0f;
  p.join_max_m = 1.0f;
  // degenerate_key_interval_s stays 0 (off): flown on the 10 m map at 1 s it mended
  // gt-building's corridor, where the local map could hold only the slice seen through a door
  // (UTM-30LX, 30 minutes, seeds 1-60: 40 flights landed at home, 27 without; 52 entered every
  // room, 53 without), but its key scans take in the error along a corridor: the 1 m/s hallway
  // flight ended further off, and iarc-arena's waypoint tour touched room B's door frame on 6 of
  // 20 seeds with it, none without (README, Exploration; modules/exploration/EXPERIMENTS.md).
  // The 20 m map mends that corridor without it (59 of 60 at home); the rule was not re-flown
  // on it with the UTM-30LX (with the URG-04LX: within the spread, fewer flights at home).
  // kestrel-sim: --mission-arg corridor_keys_s=1.
  return p;
}

// The filter as the vehicle runs it with its laser. A laser of short reach (the URG-04LX's
// 4 m) often leaves the scan matcher one wall direction: along a corridor, or in a room wider
// than twice its reach. There the matches slide along the wall while their covariance still
// claims centimetres, and with the default accelerometer noise the filter followed them into
// a wrong velocity and flew the vehicle into a door jamb or the corridor's end. A quieter
// accelerometer model lets the IMU hold the velocity through such stretches. Over 150
// 30-minute gt-building flights, runaways (1 m of error in 10 s) fell from 6.2 to 2.8 per
// flight hour, and flights through every room without a contact rose from 76 to 101. The
// 30 m UTM-30LX keeps the default: the quieter model made its iarc-arena hovers 1.6 times
// worse. Both in modules/exploration/EXPERIMENTS.md, *A quieter accelerometer model*.
inline constexpr uint16_t kShortReachLaserMm = 10000;
inline constexpr float kShortReachAccelNoiseXy = 3e-4f;  // (m/s^2)^2/Hz, against the default 4e-3
inline estimation::EkfParams vehicle_ekf_params(uint16_t laser_max_range_mm) {
  estimation::EkfParams p;
  if (laser_max_range_mm > 0 && laser_max_range_mm <= kShortReachLaserMm) p.accel_noise_xy = kShortReachAccelNoiseXy;
  return p;
}

// The compact SLAM as the vehicle runs it with its laser (modules/slam). With the URG-04LX it
// holds the estimate on walls the scan matcher's five key scans have forgotten: over 150
// 30-minute gt-building flights, runaways (1 m of error in 10 s) fell from 2.8 to 1.1 per
// flight hour, flights through every room without a contact rose from 101 to 115, and flights
// that landed at home from 53 to 107 (modules/exploration/EXPERIMENTS.md, *The compact SLAM*).
inline bool vehicle_slam_enabled(uint16_t laser_max_range_mm) {
  return laser_max_range_mm > 0 && laser_max_range_mm <= kShortReachLaserMm;
}

struct StackConfig {
  scan_matching::Params matcher = vehicle_matcher_params();
  // EkfParams' defaults, the UTM-30LX's: a caller that knows its laser sets
  // vehicle_ekf_params(max_range_mm) (kestrel-sim and kestrel-fw do).
  estimation::EkfParams ekf;
  control::ControllerParams controller = vehicle_controller_params();
  exploration::Params explorer;
  exploration::ExplorerKind explorer_kind = exploration::ExplorerKind::kBlend;
  mission::MissionParams mission;
  mission::MissionKind mission_kind = mission::MissionKind::kHover;
  StaticVector<mission::Waypoint, mission::MissionController::kMaxWaypoints> waypoints;
  // Where the vehicle stands at power-up, in the world frame the mission is expressed in: the
  // scan matcher's first scan starts the map at this pose.
  Pose2 home;
  // Apply each scan-matcher pose at the time its scan was taken (the EKF's state history), or,
  // false, as if taken on arrival: the comparison of paper 000 Figure 3b.
  bool use_measurement_time = true;
  // The compact SLAM (level 3, modules/slam): off, the filter runs on the scan matcher alone.
  // On, a matched scan is handed to it when it is idle and slam_period_s (less half a laser
  // period) has passed since the last one, and its corrections reach the filter through
  // NavFilter::apply_correction. Off here; a caller that knows its laser sets
  // vehicle_slam_enabled(max_range_mm) (kestrel-sim and kestrel-fw do).
  bool slam_enabled = false;
  slam::SlamParams slam;
  float slam_period_s = 0.1f;
  // How long the IMU or the laser may stay silent before the mission is told the estimate is
  // stale (and its failsafe lands the vehicle): sensor_watchdog.hpp.
  SensorTimeouts sensor_timeouts;
  // Home re-localisation against the scans of the first minute, on the way home (home_fix.hpp).
  HomeFixConfig home_fix;
  // The altitude set-point raised over furniture the altimeter finds (clearance_guard.hpp).
  ClearanceParams clearance;
};

}  // namespace kestrel::autonomy
