#pragma once
// The time-stamped messages that flow between the HAL and the algorithms. Time first, units in
// the comments, fixed size: a message can be copied into a queue slot without allocating.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>

#include "kestrel/core/se2.hpp"
#include "kestrel/core/time.hpp"

namespace kestrel {

// Largest scan of the supported lasers: the UTM-30LX gives 1081 beams over 270 degrees.
inline constexpr std::size_t kMaxBeams = 1081;

// Range codes below kMinValidRangeMm are not distances: like the Hokuyo SCIP protocol, the
// scanner reports why a beam has no return.
namespace range_code {
inline constexpr uint16_t kNoReturn = 0;     // nothing within range (open space, glass)
inline constexpr uint16_t kTooNear = 1;      // closer than the minimum range
inline constexpr uint16_t kDropout = 2;      // lost return (dust, grazing incidence, mixed pixel)
inline constexpr uint16_t kDeflected = 3;    // beam sent elsewhere (e.g. down by a mirror)
}  // namespace range_code
inline constexpr uint16_t kMinValidRangeMm = 20;
// The finest angle between beams a fan may have: far below any scanner's (the UTM-30LX's is
// 0.0044 rad), and coarse enough that a beam index computed from an angle stays within int.
inline constexpr float kMinAngleStepRad = 1e-4f;

// Whether a fan of beams can be used at all, whatever module takes it: 1..kMaxBeams beams,
// finite angles, a step no finer than kMinAngleStepRad (either sign), no more than one full
// turn, and (fan_well_formed) a maximum range that can hold a return.
inline bool fan_angles_well_formed(double beam_count, double first_angle_rad, double angle_step_rad) {
  return beam_count >= 1 && beam_count <= static_cast<double>(kMaxBeams) && std::isfinite(first_angle_rad) &&
         std::isfinite(angle_step_rad) && std::fabs(angle_step_rad) >= kMinAngleStepRad &&
         std::fabs(angle_step_rad) * beam_count <= 6.2832;
}
inline bool fan_well_formed(uint16_t beam_count, float first_angle_rad, float angle_step_rad, uint16_t max_range_mm) {
  return fan_angles_well_formed(beam_count, first_angle_rad, angle_step_rad) && max_range_mm >= kMinValidRangeMm;
}

struct LaserScan {
  TimeUs stamp;                 // time the first beam was taken
  Duration scan_period;         // time of one full mirror revolution
  Duration beam_interval;       // time between consecutive beams
  float first_angle_rad = 0;    // angle of beam 0 in the sensor frame, counter-clockwise
  float angle_step_rad = 0;     // angle between consecutive beams, counter-clockwise
  uint16_t max_range_mm = 0;    // the sensor's maximum range
  uint16_t beam_count = 0;      // valid entries of range_mm
  std::array<uint16_t, kMaxBeams> range_mm{};  // mm, or a range_code below kMinValidRangeMm

  static bool is_return(uint16_t r) { return r >= kMinValidRangeMm; }
  bool fan_well_formed() const {
    return kestrel::fan_well_formed(beam_count, first_angle_rad, angle_step_rad, max_range_mm);
  }
  float angle_of(std::size_t i) const { return first_angle_rad + angle_step_rad * static_cast<float>(i); }
  TimeUs time_of(std::size_t i) const { return stamp + beam_interval * static_cast<int64_t>(i); }
};

struct ImuSample {
  TimeUs stamp;
  Eigen::Vector3f accel_mps2 = Eigen::Vector3f::Zero();  // specific force, body frame (x fwd, y left, z up)
  Eigen::Vector3f gyro_radps = Eigen::Vector3f::Zero();  // angular rate, body frame
};

struct AltimeterSample {
  TimeUs stamp;
  float height_m = 0;      // above the floor
  float variance_m2 = 0;   // of height_m
};

// Set-point for the attitude-stabilised vehicle, the inputs u of paper 000 equation 1.
struct AttitudeSetpoint {
  TimeUs stamp;
  float pitch_rad = 0;      // u_phi: positive pitches the nose down, accelerating along +x body
  float roll_rad = 0;       // u_psi: positive accelerates along +y body
  float thrust = 0;         // u_t: normalised collective thrust, 0..1
  float yaw_rate_radps = 0; // u_theta: counter-clockwise positive
};

// The autopilot's report. Attitude angles are right-handed Euler angles, body to world =
// Rz(yaw) Ry(pitch) Rx(roll), as autopilots report them: pitch > 0 is nose down (thrust towards
// +x body, like AttitudeSetpoint), roll > 0 lifts the left side (thrust towards -y body: the
// opposite sign of AttitudeSetpoint's roll, which follows paper 000 equation 1).
struct FlightStatus {
  TimeUs stamp;
  bool armed = false;
  float battery_v = 0;
  float roll_rad = 0;   // right-handed about body x: > 0 lifts the left side
  float pitch_rad = 0;  // right-handed about body y (left): > 0 is nose down
  float yaw_rad = 0;    // counter-clockwise from the world x axis
};

// A 2D pose measurement with its covariance (x, y, theta), e.g. from the scan matcher.
struct PoseMeasurement2 {
  TimeUs stamp;                // time of the scan the pose was computed from
  Pose2 pose;                  // m, m, rad
  Eigen::Matrix3f covariance = Eigen::Matrix3f::Identity();  // m², m², rad²
  uint32_t flags = 0;          // producer-specific quality flags
};

}  // namespace kestrel

namespace kestrel {

// The farthest a position of the navigation frame may lie from its origin on any axis: far
// beyond any indoor flight, near enough that a float keeps millimetres and grid cells fit an
// int. The filter refuses measurements beyond it, guidance estimates beyond it.
inline constexpr float kMaxNavCoordinateM = 1.0e4f;

// The filter's estimate of the vehicle's motion: what guidance and control act on.
// World frame: x, y horizontal, z up, heading counter-clockwise from the world x axis.
struct NavState {
  TimeUs stamp;
  Eigen::Vector3f position_m = Eigen::Vector3f::Zero();
  Eigen::Vector3f velocity_mps = Eigen::Vector3f::Zero();
  Eigen::Vector3f accel_mps2 = Eigen::Vector3f::Zero();
  float heading_rad = 0;
  float yaw_rate_radps = 0;
  Eigen::Vector3f position_std_m = Eigen::Vector3f::Zero();  // 1-sigma, per axis
  float heading_std_rad = 0;
  bool valid = false;  // false until the filter has been initialised by a pose measurement
};

// What guidance asks of the controller. In kPosition mode the controller drives to
// position_m with velocity_mps as feed-forward; in kVelocity mode it tracks velocity_mps in
// x and y and holds position_m.z(). The heading is always tracked.
struct GuidanceSetpoint {
  enum class Mode : uint8_t { kPosition, kVelocity };
  TimeUs stamp;
  Mode mode = Mode::kPosition;
  Eigen::Vector3f position_m = Eigen::Vector3f::Zero();
  Eigen::Vector3f velocity_mps = Eigen::Vector3f::Zero();
  float heading_rad = 0;
};

}  // namespace kestrel
