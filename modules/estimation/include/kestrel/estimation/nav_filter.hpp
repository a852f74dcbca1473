#pragma once
// The data-fusion filter of paper 000 section 5.2, with the state history that absorbs late
// measurements and the seconds-old SLAM corrections of section 5.3.
//
// Structure. Four decoupled filters instead of one 15-state EKF: three world axes, each
// [position, velocity, accelerometer bias] (AxisFilter), and the heading [psi, gyro bias]
// (HeadingFilter). The IMU is the input of the prediction: its specific force is rotated into
// the world frame with the autopilot's roll and pitch (FlightStatus, small and known) and the
// filter's own heading, gravity is removed, and each axis integrates its component; the
// acceleration the filter reports is that input minus the estimated bias. The axes couple only
// through the heading, which enters their input (its uncertainty is added to their input
// noise) and rotates the horizontal bias pair when the vehicle yaws. Why: one prediction
// costs about 200 float operations instead of about 7000 for F P F^T of a coupled 15-state
// filter; on the Verdex (soft float, tens of cycles per operation) the coupled filter at
// 100 Hz alone would take most of the 20 M-cycle budget of a 10 Hz scan cycle, and re-running
// one second of history for a late SLAM correction would take several cycles' budgets.
// Dropped: cross-covariances between axes (the scan matcher's x-y covariance term is used in
// the gate only) and between heading and position.
//
// Timing. predict() runs once per IMU sample: it is the fixed clock. Each step stores the
// input and the predicted (prior) state and covariance in a ring of kHistory slots
// (1024: 5.1 s at 200 Hz, 10.2 s at 100 Hz; 256 KiB). Every measurement is logged
// (kMeasurementLog entries, sorted by stamp) and applied at the time it was taken: the filter
// restarts from the prior of the slot at or before its stamp, applies the logged
// measurements of that slot in stamp order (each with H extrapolated over the few
// milliseconds between the slot and its stamp), and re-propagates with the stored inputs,
// re-applying every later logged measurement, to the newest sample. The result equals the
// in-order result. A measurement older than the oldest slot is rejected with kOutOfRange; one
// stamped more than max_future_s after the newest IMU sample with kTimeJump.
//
// SLAM corrections (apply_correction) are a pose of the vehicle at an earlier time in the
// SLAM frame. The difference D between that pose and the filter's pose at that time is a
// rigid SE(2) shift of the trajectory from then on: the state at that time is shifted, the
// scan matcher poses logged after it are shifted, and later scan matcher poses are mapped
// through frame_correction() (the accumulated D), so the present state moves by D while the
// local, scan-matcher-driven estimate stays smooth. Covariances are left as they are.
//
// At rest. On the ground, motors idle, the velocity is known to be zero on every axis; fed
// as a measurement (update_at_rest) it makes the accelerometer biases observable on all three
// axes before take-off, including one the laser cannot see (along a corridor, where the scan
// matcher says nothing and an unestimated 0.1 m/s^2 bias would carry the vehicle away).
//
// Start: IMU samples before the first pose are stored (kNoData); the first pose initialises
// the state at its own stamp and propagates through the stored samples after it; the first
// altimeter sample sets the height outright. A sample in order but stamped not after the
// state's start, which arrived after the first pose (queued behind it), is dropped with kNoData
// too and counted as imu_before_start: the IMU's stream is fine, the state starts later.
//
// Bad inputs: non-finite samples (kNotFinite), IMU time going backwards (kTimeJump, sample
// dropped), an IMU gap above max_imu_gap_s (kTimeJump: coasts at constant velocity over the
// gap and restarts the history), gated measurements (kRejected; a lasting run of gated heights
// is decided as a floor step or a height re-lock, see EkfParams). Each is counted. Finite but
// physically impossible values are refused with kOutOfRange and counted too: an IMU component
// beyond kMaxAccelMps2 or kMaxGyroRadps (a float that size would overflow P), a pose x or y
// or an altimeter height beyond kMaxNavCoordinateM (messages.hpp); set_attitude ignores a
// roll or pitch outside [-pi, pi] (not a wrapped angle) as it ignores a non-finite one.
//
// API
//   NavFilter(params)                  construct once (large: keep it static or at start-up)
//   Status set_params(p)               validate and use; does not reset the state
//   void   set_attitude(FlightStatus)  roll/pitch for the following IMU samples (default level)
//   Status predict(ImuSample)          one fixed-clock step; kNoData before the first pose
//                                      or the state's start
//   Status update_pose(PoseMeasurement2)     scan matcher pose (world frame, 3x3 covariance)
//   Status update_altitude(AltimeterSample)
//   Status update_at_rest(stamp, variance)   zero velocity: the vehicle rests on the ground
//   Status apply_correction(PoseMeasurement2) SLAM pose of the vehicle at meas.stamp
//   NavState state() const             the newest estimate; valid once initialised
//   counters(), frame_correction(), axis(i), floor_m(), weighed_floor_m(), heading(),
//   history_span()
//   Conventions: FlightStatus roll and pitch are right-handed rotations about body x
//   (forward) and body y (left), body to world = Rz(yaw) Ry(pitch) Rx(roll), as the
//   simulator's autopilot reports them: pitch > 0 is nose down (like AttitudeSetpoint), roll
//   > 0 lifts the left side (accelerates along -y body: the opposite sign of
//   AttitudeSetpoint's roll, which follows paper 000 equation 1).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/estimation/axis_filter.hpp"
#include "kestrel/estimation/ekf_params.hpp"
#include "kestrel/estimation/heading_filter.hpp"

namespace kestrel::estimation {

struct NavFilterCounters {
  uint32_t imu_samples = 0;          // accepted predictions
  uint32_t imu_not_finite = 0;
  uint32_t imu_out_of_range = 0;     // a component beyond kMaxAccelMps2 / kMaxGyroRadps
  uint32_t imu_time_backwards = 0;   // stamp not after the previous sample
  uint32_t imu_before_start = 0;     // in order, but not after the state's start (the first pose)
  uint32_t imu_gaps = 0;             // gaps above max_imu_gap_s (history restarted)
  uint32_t pose_updates = 0;
  uint32_t pose_rejected = 0;        // gated out (outliers)
  uint32_t altitude_updates = 0;
  uint32_t altitude_rejected = 0;
  uint32_t altitude_relocks = 0;     // heights set from the altimeter after a run of rejections
  uint32_t floor_steps = 0;          // runs of rejections taken as a step of the floor
  uint32_t at_rest_updates = 0;
  uint32_t corrections = 0;
  uint32_t corrections_rejected = 0;
  uint32_t meas_not_finite = 0;
  uint32_t meas_out_of_range = 0;    // pose x, y or height beyond kMaxNavCoordinateM
  uint32_t meas_too_old = 0;         // older than the history
  uint32_t meas_future = 0;          // beyond max_future_s ahead of the newest sample
  uint32_t log_overflow = 0;         // log entries dropped while still inside the history
  uint32_t replays = 0;              // measurements that needed re-propagation
  uint32_t replayed_steps = 0;       // prediction steps re-run for them
};

// Every counter by name, for the tools that report them (kestrel-sim's metrics.json as
// nav.NAME, kestrel-fw's exit report): one list, so a counter added above and not here fails
// the size check below instead of going unreported.
struct NavFilterCounterField {
  const char* name;
  uint32_t NavFilterCounters::*member;
};
inline constexpr std::array<NavFilterCounterField, 22> kNavFilterCounterFields{{
    {"imu_samples", &NavFilterCounters::imu_samples},
    {"imu_not_finite", &NavFilterCounters::imu_not_finite},
    {"imu_out_of_range", &NavFilterCounters::imu_out_of_range},
    {"imu_time_backwards", &NavFilterCounters::imu_time_backwards},
    {"imu_before_start", &NavFilterCounters::imu_before_start},
    {"imu_gaps", &NavFilterCounters::imu_gaps},
    {"pose_updates", &NavFilterCounters::pose_updates},
    {"pose_rejected", &NavFilterCounters::pose_rejected},
    {"altitude_updates", &NavFilterCounters::altitude_updates},
    {"altitude_rejected", &NavFilterCounters::altitude_rejected},
    {"altitude_relocks", &NavFilterCounters::altitude_relocks},
    {"floor_steps", &NavFilterCounters::floor_steps},
    {"at_rest_updates", &NavFilterCounters::at_rest_updates},
    {"corrections", &NavFilterCounters::corrections},
    {"corrections_rejected", &NavFilterCounters::corrections_rejected},
    {"meas_not_finite", &NavFilterCounters::meas_not_finite},
    {"meas_out_of_range", &NavFilterCounters::meas_out_of_range},
    {"meas_too_old", &NavFilterCounters::meas_too_old},
    {"meas_future", &NavFilterCounters::meas_future},
    {"log_overflow", &NavFilterCounters::log_overflow},
    {"replays", &NavFilterCounters::replays},
    {"replayed_steps", &NavFilterCounters::replayed_steps},
}};
static_assert(sizeof(NavFilterCounters) == kNavFilterCounterFields.size() * sizeof(uint32_t),
              "every NavFilterCounters member must be listed in kNavFilterCounterFields");

class NavFilter {
 public:
  static constexpr std::size_t kHistory = 1024;
  static constexpr std::size_t kMeasurementLog = 512;
  // Fewest gated heights in a run before altitude_relock_s decides it: one stray reading
  // across a long gap between altimeter samples is not a run.
  static constexpr uint8_t kRelockMinRejected = 5;
  // A run has stayed when its readings last moved (over altitude_step_tol_m from where they
  // had settled) no later than this share of altitude_relock_s before it is decided: a box's
  // side face ramps the first few readings, and a climb the filter does not see (0.5 m/s moves
  // them 0.1 m in 0.2 s) keeps moving them.
  static constexpr float kSettledShare = 0.6f;
  // A run jumped when its readings lay over altitude_step_tol_m from the last height taken
  // within this long of its start: 0.1 m in 0.15 s is faster than the estimate creeps out of its
  // gate (a climb it does not see at 0.5 m/s takes 0.2 s), and the altimeter's spot crossing a
  // desk's edge slowly ramps the first readings by steps under the tolerance.
  static constexpr float kJumpWithinS = 0.15f;
  // Plausibility bounds of the inputs (far beyond any sensor's range or indoor flight).
  static constexpr float kMaxAccelMps2 = 1000.0f;  // about 100 g
  static constexpr float kMaxGyroRadps = 100.0f;

  explicit NavFilter(const EkfParams& params = {});

  Status set_params(const EkfParams& params);
  const EkfParams& params() const { return params_; }
  // Forgets everything: the next pose initialises the filter again.
  void reset();

  void set_attitude(const FlightStatus& status);
  Status predict(const ImuSample& imu);
  Status update_pose(const PoseMeasurement2& meas);
  Status update_altitude(const AltimeterSample& meas);
  // The vehicle is at rest at `stamp` (velocity zero, variance (m/s)^2 > 0 per axis).
  Status update_at_rest(TimeUs stamp, float variance_mps2);
  Status apply_correction(const PoseMeasurement2& slam_pose);

  NavState state() const;
  bool initialised() const { return initialised_; }
  const NavFilterCounters& counters() const { return counters_; }
  Pose2 frame_correction() const { return frame_correction_; }
  const AxisState& axis(int i) const { return cur_.ax[static_cast<std::size_t>(i)]; }
  // Where the altimeter's floor is now, above the take-off floor (0 until a floor step).
  float floor_m() const { return cur_.floor_m; }
  // The floor a run of gated heights shows while it is being weighed, before it is decided:
  // for what must not wait altitude_relock_s to know what is under the vehicle (the clearance
  // guard over an obstacle's top). Only a run that jumped (kJumpWithinS) and has at least
  // kWeighedMinRejected readings, each within altitude_step_tol_m of the one before (a single
  // stray reading is not a floor), its newest no more than kWeighedStaleS old (an altimeter
  // fallen silent shows nothing): the floor its newest reading would place, the height less
  // that reading. nullopt otherwise, and with runs off (altitude_relock_s = 0).
  std::optional<float> weighed_floor_m() const;
  static constexpr uint8_t kWeighedMinRejected = 2;
  // At 10 Hz a reading is due every 0.1 s; one delivered late may drop the weighed floor for a
  // cycle, which ClearanceGuard's hold (hold_s) spans.
  static constexpr float kWeighedStaleS = 0.25f;
  const HeadingState& heading() const { return cur_.hd; }
  Duration history_span() const;

 private:
  struct Filters {
    std::array<AxisState, 3> ax;
    HeadingState hd;
    Eigen::Vector3f accel_world = Eigen::Vector3f::Zero();  // last input minus bias, m/s^2
    float yaw_rate = 0;                                     // last gyro minus bias, rad/s
    // Where the altimeter's floor is, above the take-off floor: a height reading is
    // height_m + floor_m in the world. Kept in the replayed state, as is the run of gated
    // heights that moves it, so a replay through a late measurement decides the run the same
    // way. The run's length is the IMU time propagated since its first height (a float per
    // slot instead of a stamp).
    float floor_m = 0;
    float rejected_run_s = 0;
    float run_jumped_s = -1;       // the run's time its readings first lay over the tolerance from the last taken; < 0 not yet
    float run_last_nu = 0;         // the run's latest rejected height's innovation, m
    float run_settled_nu = 0;      // where its readings settled: moved by a departure over the tolerance the next reading confirmed
    float run_settled_s = 0;       // the run's time when they settled there
    // A reading over the tolerance from the settled one, not yet followed by another: a lone
    // jitter (or the deciding reading) does not move the settled point, a move does, from it.
    float run_departed_nu = 0;
    float run_departed_s = 0;
    bool run_departing = false;
    float run_newest_s = 0;        // the run's time at its newest reading
    float last_taken_nu = 0;       // the innovation of the last height taken, m
    uint8_t heights_rejected = 0;  // in a row, saturating
    bool height_known = false;     // false until the first altimeter sample
  };
  struct Input {
    Eigen::Vector3f accel = Eigen::Vector3f::Zero();  // body specific force of the sample
    float gyro_z = 0;
    float roll = 0;
    float pitch = 0;
  };
  struct Slot {
    TimeUs t;
    Input in;       // the sample that ended the step into this slot
    Filters prior;  // state after that step, before this slot's measurements
  };
  enum class Kind : uint8_t { kPose, kAltitude, kCorrection, kAtRest };
  struct Entry {
    TimeUs t;
    Kind kind = Kind::kPose;
    bool fresh = false;  // being applied for the first time: count and (correction) compute D
    Eigen::Vector3f z = Eigen::Vector3f::Zero();  // pose x, y, psi | height | D dx, dy, dpsi | 0
    Eigen::Matrix3f R = Eigen::Matrix3f::Zero();
  };

  Slot& slot(std::size_t i) { return slots_[(first_ + i) % kHistory]; }
  const Slot& slot(std::size_t i) const { return slots_[(first_ + i) % kHistory]; }
  Entry& entry(std::size_t i) { return log_[(log_first_ + i) % kMeasurementLog]; }

  void initialise(TimeUs t, const Pose2& pose);
  void propagate(const Filters& from, Filters& to, const Input& in, float dt) const;
  Status submit(Entry e);
  Status apply(Filters& f, Entry& e, const Slot& s, std::size_t log_index);
  Status apply_pose(Filters& f, const Entry& e, float delta, bool count);
  // A run jumped: its readings lay over altitude_step_tol_m from the last height taken within
  // kJumpWithinS of its start.
  static bool run_jumped(const Filters& f) {
    return f.run_jumped_s >= 0.0f && f.run_jumped_s <= kJumpWithinS;
  }
  Status apply_altitude(Filters& f, const Entry& e, float delta, bool count);
  Status apply_at_rest(Filters& f, const Entry& e, bool count);
  void shift(Filters& f, const Eigen::Vector3f& d) const;
  static void unshift(Entry& e, const Eigen::Vector3f& d);
  std::size_t slot_at(TimeUs t) const;
  std::size_t log_insert(const Entry& e);
  void log_trim();

  EkfParams params_;
  std::array<Slot, kHistory> slots_{};
  std::size_t first_ = 0;
  std::size_t count_ = 0;
  std::array<Entry, kMeasurementLog> log_{};
  std::size_t log_first_ = 0;
  std::size_t log_count_ = 0;
  Filters cur_;  // posterior at the newest slot
  Input attitude_;
  Pose2 frame_correction_;
  bool initialised_ = false;
  bool have_imu_ = false;
  TimeUs last_imu_t_;
  bool have_height_ = false;
  float last_height_ = 0;
  NavFilterCounters counters_;
};

}  // namespace kestrel::estimation
