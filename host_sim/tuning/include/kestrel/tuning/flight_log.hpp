#pragma once
// One simulated flight recorded for the tuning tools, with ground truth: what the vehicle's
// loop saw (IMU samples, autopilot attitude reports, the scan matcher's poses as the autonomy
// stack produced them, altimeter samples), what the autopilot applied (the attitude set-point
// in force at every physics step) and the true motion. kestrel-tune-ekf learns the EKF's noise
// parameters from the sensor streams against the true velocity (paper 000 section 5.2);
// kestrel-sysid fits equation 1 to the commands and the true accelerations (section 4).
//
// Flights: `hover` and `waypoints` are the closed-loop AutonomyMission (the stack's scan
// matcher provides the poses); `manual` replays a CommandScript open loop (no poses: it is
// for the model fit only). Everything is recorded without changing what the stack receives:
// the IMU and the true state come from the SimObserver taps, the altimeter queue is read and
// refilled between physics steps, the poses are read from AutonomyStack::last_match().
//
// API
//   FlightSpec; FlightLog; Result-like: std::string fly_and_record(spec, log)
#include <cstdint>
#include <string>
#include <vector>

#include "kestrel/autonomy/stack_config.hpp"
#include "kestrel/core/messages.hpp"
#include "kestrel/sim/sim_config.hpp"

namespace kestrel::tuning {

enum class FlightKind { kHover, kWaypoints, kManual };

struct FlightSpec {
  FlightKind kind = FlightKind::kHover;
  std::string world = "iarc-arena";
  sim::SimConfig sim;                 // seed, vehicle, laser, IMU
  double duration_s = 30;             // simulated time limit
  double hover_s = 10;                // hover mission: time at the set-point
  std::vector<Eigen::Vector4f> waypoints;  // waypoints mission: x y z (m) heading (rad), world frame
  // Manual mission: CommandScript text, and the name its errors carry. Empty text is an error
  // ("the script has no commands"), as in kestrel-sim: it once meant the default tour, so an
  // empty --script file flew that tour silently.
  std::string script_text;
  std::string script_name = "<script>";
  // The stack's filter parameters, as given (EkfParams' defaults, not the laser's:
  // autonomy::vehicle_ekf_params).
  estimation::EkfParams ekf;
  bool use_default_controller = true;
  control::ControllerParams controller;  // used when use_default_controller is false
};

struct TruthRecord {
  TimeUs stamp;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();
  double yaw_rad = 0;
  double yaw_rate_radps = 0;
  bool on_ground = true;
  AttitudeSetpoint command;  // the set-point the autopilot applied during the step ending here
};

struct FlightLog {
  std::vector<ImuSample> imu;
  std::vector<FlightStatus> attitude;
  std::vector<PoseMeasurement2> poses;      // accepted scan-matcher poses
  std::vector<int64_t> pose_delivery_us;    // when each pose became available, minus its stamp
  std::vector<AltimeterSample> altitude;
  std::vector<TruthRecord> truth;           // every physics step
  // Estimate against truth at every pose, as the stack flew it (hover score).
  double hover_rms_m = 0;
  uint32_t poses_gated = 0;  // matched poses the stack's EKF gate refused
  bool collided = false;
  std::string end_message;
};

// Flies `spec` and fills `log`; "" or why the flight could not be flown.
std::string fly_and_record(const FlightSpec& spec, FlightLog& log);

// A few waypoints in the iarc-arena hallway around its start (2, 7.5): forward 3 m, sideways,
// up, back; they excite all three axes.
std::vector<Eigen::Vector4f> arena_waypoints();

}  // namespace kestrel::tuning
