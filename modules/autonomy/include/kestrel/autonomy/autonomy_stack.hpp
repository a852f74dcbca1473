#pragma once
// The composition module: the one place that sees the HAL. It wires
//   Imu -> NavFilter.predict, Altimeter -> NavFilter.update_altitude,
//   LaserScanner -> ScanMatcher -> NavFilter.update_pose,
//   (Explorer ->) MissionController (-> ClearanceGuard) -> Controller -> FlightController
// and runs them as the real-time loop (level 2 of paper 000 Figure 4) on the core Scheduler,
// with the task table of task_table.hpp. The scan matcher's local-map rebuild is level 3:
// background_step() runs it, from a background thread on a board or in lockstep after each
// poll in the simulator (deterministic), and the loop never waits for it. So does the compact
// SLAM when it is enabled: the scan task hands it a matched scan through a one-slot mailbox and
// applies the correction it hands back at the next scan; neither side ever waits.
//
// Memory: everything is inside this object (about 14.9 MiB: the scan matcher's two maps, the
// SLAM's, the frontier explorer's grid and the home re-localisation's map), which the firmware
// allocates once at start-up (static storage or one allocation before arming). After start()
// nothing allocates.
#include <atomic>
#include <cstdint>

#include "kestrel/autonomy/clearance_guard.hpp"
#include "kestrel/autonomy/home_fix.hpp"
#include "kestrel/autonomy/return_velocity_bound.hpp"
#include "kestrel/autonomy/scan_prior.hpp"
#include "kestrel/autonomy/stack_config.hpp"
#include "kestrel/autonomy/sensor_watchdog.hpp"
#include "kestrel/autonomy/slam_frame.hpp"
#include "kestrel/autonomy/task_table.hpp"
#include "kestrel/control/controller.hpp"
#include "kestrel/core/mailbox.hpp"
#include "kestrel/core/scheduler.hpp"
#include "kestrel/estimation/nav_filter.hpp"
#include "kestrel/exploration/blend_explorer.hpp"
#include "kestrel/exploration/frontier_explorer.hpp"
#include "kestrel/exploration/srt_explorer.hpp"
#include "kestrel/exploration/wall_follow_explorer.hpp"
#include "kestrel/hal/altimeter.hpp"
#include "kestrel/hal/clock.hpp"
#include "kestrel/hal/flight_controller.hpp"
#include "kestrel/hal/imu.hpp"
#include "kestrel/hal/laser_scanner.hpp"
#include "kestrel/mission/mission_controller.hpp"
#include "kestrel/scan_matching/scan_matcher.hpp"
#include "kestrel/slam/compact_slam.hpp"

namespace kestrel::autonomy {

// The devices the stack flies with. The altimeter is optional (nullptr): the EKF then holds
// altitude on the IMU alone, which is only good for short hops.
struct Devices {
  hal::Clock& clock;
  hal::LaserScanner& laser;
  hal::Imu& imu;
  hal::Altimeter* altimeter;
  hal::FlightController& autopilot;
};

// What the loop did, for metrics.json and telemetry. Level 3's counts are kept apart
// (map_rebuilds(), slam().counters()): another thread writes them on a board.
struct StackCounters {
  uint32_t scans = 0;
  uint32_t scans_matched = 0;
  uint32_t scans_rejected = 0;       // by the scan matcher (flags say why)
  uint32_t poses_gated = 0;          // matched, but the EKF's gate refused the pose
  uint32_t imu_samples = 0;
  uint32_t imu_errors = 0;
  uint32_t altitude_samples = 0;
  uint32_t guidance_steps = 0;
  uint32_t guidance_rejected = 0;    // flight-home set-points the approach limiter could not bound (zeroed)
  uint32_t setpoints_sent = 0;
  uint32_t autopilot_errors = 0;
  uint32_t scans_lost = 0;           // matched nothing: the pose is the filter's prediction
  uint32_t map_restarts = 0;         // lost too long: the local map started again
  uint32_t device_errors = 0;        // polls that returned an error (not kNoData)
  uint32_t home_fixes = 0;           // home re-localisations the filter applied
  uint32_t home_fixes_refused = 0;   // ...and refused
  // Altitude set-point raised over furniture the altimeter found (ClearanceGuard::rises), by any
  // height: a desk's floor placed a few millimetres high counts too.
  uint32_t clearance_rises = 0;
  uint32_t clearance_rises_weighed = 0;  // ...whose first raised cycle was over a floor the filter still weighed
};

// The newest scan the compact SLAM processed, in the filter's frame (through the SlamFrame it
// was offered under), for diagnostics: kestrel-sim's SLAM trace compares it with the truth.
struct SlamStep {
  TimeUs stamp;             // the scan's
  slam::SlamResult result;  // poses in the SLAM's frame
  Pose2 prior;              // the filter's pose at the stamp
  Pose2 fit;                // the SLAM's best fit (the prior when it searched nothing)
  SlamFrame frame;          // the SLAM's map in the filter's frame, as the scan was offered
};

class AutonomyStack {
 public:
  // exec_clock measures task execution time (a real clock even in simulation).
  AutonomyStack(const Devices& devices, const TimeSource& exec_clock);

  // Validates and applies the whole configuration; kInvalidArgument names nothing, so each
  // sub-configuration is checked by its module with its own Status (see configure_error()).
  Status configure(const StackConfig& config);
  const char* configure_error() const { return configure_error_; }

  // Registers the tasks with the scheduler, releasing now. Nothing allocates after this.
  Status start();
  // Runs the tasks that are due; returns how many ran.
  std::size_t poll();
  TimeUs next_release() const { return scheduler_.next_release(); }
  // Level 3: rebuilds the scan matcher's local map if a key scan is waiting, runs the SLAM on
  // the scan waiting for it, if any, and the explorer's background work (the frontier
  // explorer's grid and planner).
  void background_step();

  const NavState& nav() const { return nav_; }
  const GuidanceSetpoint& setpoint() const { return setpoint_; }
  const AttitudeSetpoint& command() const { return command_; }
  uint32_t control_flags() const { return control_flags_; }
  const scan_matching::ScanMatch& last_match() const { return last_match_; }
  bool new_match() const { return new_match_; }  // true during the poll that produced it
  const mission::MissionController& mission() const { return mission_; }
  const exploration::Explorer* explorer() const { return explorer_; }
  const estimation::NavFilter& filter() const { return filter_; }
  const scan_matching::ScanMatcher& matcher() const { return matcher_; }
  const slam::CompactSlam& slam() const { return slam_; }
  // Written by background_step(): read them on the thread that calls it (the simulator runs
  // both on one), or once it is idle. slam_steps() counts the scans processed.
  const SlamStep& last_slam_step() const { return last_slam_step_; }
  uint32_t slam_steps() const { return slam_steps_; }
  // Level 3's counts of the home re-localisation; the loop's are in counters().
  const HomeFix& home_fix() const { return home_fix_; }
  const Scheduler& scheduler() const { return scheduler_; }
  const StackCounters& counters() const { return counters_; }
  // Local-map rebuilds done by background_step(): level 3's count, readable from the loop's thread.
  uint32_t map_rebuilds() const { return map_rebuilds_.load(std::memory_order_relaxed); }
  // How often the IMU and the laser fell silent for longer than their timeouts.
  const SilenceCounters& silences() const { return watchdog_.counters(); }
  bool finished() const { return mission_.finished(); }

 private:
  static void run_imu(void* self, TimeUs release);
  static void run_scan_match(void* self, TimeUs release);
  static void run_guidance(void* self, TimeUs release);
  static void run_control(void* self, TimeUs release);
  void imu_task(TimeUs now);
  void scan_task(TimeUs now);
  void guidance_task(TimeUs now);
  void control_task(TimeUs now);
  void take_slam_correction();
  // A correction the filter took moved the estimate's path from `since` on; what was drawn
  // along it (the mission's breadcrumbs) moves too.
  void estimate_moved(TimeUs since, const Pose2& frame_before);
  void offer_scan_to_slam();
  void offer_scan_to_home_fix();
  void take_home_fix();

  Devices dev_;
  StackConfig config_;
  Scheduler scheduler_;
  const char* configure_error_ = "";
  bool configured_ = false;
  bool started_ = false;

  scan_matching::OnboardMapStorage maps_;
  scan_matching::ScanMatcher matcher_;
  estimation::NavFilter filter_;
  control::Controller controller_;
  mission::MissionController mission_;
  exploration::BlendExplorer blend_;
  exploration::WallFollowExplorer wallfollow_;
  exploration::SrtExplorer srt_;
  exploration::FrontierExplorer frontier_;
  exploration::Explorer* explorer_ = nullptr;
  slam::SlamMap slam_map_;
  slam::CompactSlam slam_{slam_map_};

  // The SLAM's mailboxes, one slot each way (core/mailbox.hpp): a matched scan to level 3, a
  // correction back to the loop.
  struct SlamInput {
    scan_matching::ScanPoints points;
    Pose2 prior;   // in the SLAM's frame
    TimeUs stamp;
    SlamFrame frame;  // slam_frame_ when offered: the correction goes back through it
  };
  Mailbox<SlamInput> slam_in_;
  Mailbox<PoseMeasurement2> slam_out_;
  SlamStep last_slam_step_;  // level 3 only
  uint32_t slam_steps_ = 0;  // level 3 only
  TimeUs last_slam_offer_;
  bool slam_offered_ = false;
  SlamFrame slam_frame_;  // the SLAM's map in the filter's frame (home fixes part them); loop only
  HomeFix home_fix_;

  LaserScan scan_;             // the scan being matched
  LaserScan guidance_scan_;    // the newest matched scan, for the explorer
  exploration::MatchConstraint guidance_match_{};  // and what its match could measure
  bool guidance_scan_fresh_ = false;
  LaserScan newest_scan_;      // the newest scan, matched or not: the flight home's limiter
  bool newest_scan_fresh_ = false;
  AltimeterSample newest_altitude_;  // the altimeter's newest reading: touchdown
  bool have_altitude_ = false;
  ReturnVelocityBound return_bound_;  // the flight home's velocity, bounded on the newest scan
  ClearanceGuard clearance_;          // the altitude set-point kept clear of what is under it
  SensorWatchdog watchdog_;           // whether the IMU and the laser still talk
  mission::ExplorerOutput explorer_out_;  // the explorer's newest set-point
  scan_matching::ScanMatch last_match_;
  bool new_match_ = false;
  NavState nav_;
  GuidanceSetpoint setpoint_;
  AttitudeSetpoint command_;
  uint32_t control_flags_ = 0;
  bool armed_ = false;
  bool blind_descending_ = false;  // the failsafe's blind descent, since blind_descent_since_
  TimeUs blind_descent_since_;
  StackCounters counters_;        // written by the loop (levels 1-2) only
  std::atomic<uint32_t> map_rebuilds_{0};  // written by background_step() only
};

}  // namespace kestrel::autonomy
