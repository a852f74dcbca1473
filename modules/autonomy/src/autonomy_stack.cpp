#include "kestrel/autonomy/autonomy_stack.hpp"
#include "kestrel/autonomy/match_constraint.hpp"

namespace kestrel::autonomy {

// DESIGN.md: the Verdex's firmware within 16 MiB in all. The stack is allocated at start-up, so
// the budget tool (static RAM) does not see it: 14.6 MiB with the 20 m local map, the compact
// SLAM's 1 MiB map, the frontier explorer's 1.4 MiB grid and the home re-localisation's 0.8 MiB,
// and 1 MiB kept for the rest of the firmware, which is tens of KiB.
static_assert(sizeof(AutonomyStack) < 15u * 1024u * 1024u, "AutonomyStack outgrows the Verdex's 16 MiB");

AutonomyStack::AutonomyStack(const Devices& devices, const TimeSource& exec_clock)
    : dev_(devices),
      scheduler_(devices.clock, exec_clock),
      matcher_(scan_matching::Params{}, maps_.map_a, maps_.map_b, /*synchronous=*/false) {}

Status AutonomyStack::configure(const StackConfig& c) {
  configured_ = false;
  if (started_) {
    configure_error_ = "the stack is running";
    return Status::kUnsupported;
  }
  config_ = c;
  if (matcher_.configure(c.matcher, c.home) != Status::kOk) {
    configure_error_ = "scan matcher parameters";
    return Status::kInvalidArgument;
  }
  if (c.slam_enabled &&
      (slam_.configure(c.slam) != Status::kOk || !(c.slam_period_s >= 0.0f && c.slam_period_s <= 10.0f))) {
    configure_error_ = "SLAM parameters";
    return Status::kInvalidArgument;
  }
  if (filter_.set_params(c.ekf) != Status::kOk) {
    configure_error_ = "EKF parameters";
    return Status::kInvalidArgument;
  }
  if (controller_.set_params(c.controller) != Status::kOk) {
    configure_error_ = "controller parameters";
    return Status::kInvalidArgument;
  }
  if (!c.sensor_timeouts.valid()) {
    configure_error_ = "sensor timeouts";
    return Status::kInvalidArgument;
  }
  if (home_fix_.configure(c.home_fix, c.matcher) != Status::kOk) {
    configure_error_ = "home re-localisation parameters";
    return Status::kInvalidArgument;
  }
  if (validate(c.clearance) != Status::kOk) {
    configure_error_ = "clearance parameters";
    return Status::kInvalidArgument;
  }
  clearance_ = ClearanceGuard(c.clearance);
  slam_frame_ = {};
  watchdog_.configure(c.sensor_timeouts);
  // The operator's keep-out boxes are the explorer's; the flight home keeps out of them too.
  mission::MissionParams mp = c.mission;
  mp.keep_out = c.explorer.srt.keep_out;
  mp.keep_out_count = c.explorer.srt.keep_out_count;
  // The home re-localisation's reference scans look all round home, but for the frontier
  // explorer's (home_fix.hpp).
  if (c.home_fix.enabled) {
    mp.takeoff_survey_rad = c.explorer_kind == exploration::ExplorerKind::kFrontier ? c.home_fix.frontier_survey_rad
                                                                                    : c.home_fix.survey_rad;
    mp.home_survey_rad = c.home_fix.home_survey_rad;
    mp.stall_survey_radius_m = c.home_fix.radius_m;  // where it searches
  }
  if (mission_.configure(c.mission_kind, mp, &c.waypoints) != Status::kOk) {
    configure_error_ = "mission parameters or waypoints";
    return Status::kInvalidArgument;
  }
  explorer_ = nullptr;
  if (c.mission_kind == mission::MissionKind::kExplore) {
    const hal::LaserGeometry g = dev_.laser.geometry();
    const exploration::BeamGeometry beams{g.beam_count, g.first_angle_rad, g.angle_step_rad, g.max_range_mm};
    switch (c.explorer_kind) {
      case exploration::ExplorerKind::kBlend: explorer_ = &blend_; break;
      case exploration::ExplorerKind::kWallFollow: explorer_ = &wallfollow_; break;
      case exploration::ExplorerKind::kSrt: explorer_ = &srt_; break;
      case exploration::ExplorerKind::kFrontier: explorer_ = &frontier_; break;
    }
    exploration::Params ep = c.explorer;
    ep.guidance.altitude_m = c.mission.takeoff_altitude_m;
    if (explorer_ == nullptr || explorer_->configure(ep, beams) != Status::kOk) {
      configure_error_ = "explorer parameters or laser geometry";
      explorer_ = nullptr;
      return Status::kInvalidArgument;
    }
  }
  configure_error_ = "";
  configured_ = true;
  return Status::kOk;
}

Status AutonomyStack::start() {
  if (!configured_) return Status::kNotFound;
  if (started_) return Status::kOk;
  const TimeUs now = dev_.clock.now();
  const hal::LaserGeometry g = dev_.laser.geometry();
  void (*const runners[])(void*, TimeUs) = {&run_imu, &run_scan_match, &run_guidance, &run_control};
  for (const TaskRow& row : task_table(g.scan_period)) {
    const TaskSpec spec{row.name, row.period, row.budget, runners[static_cast<int>(row.id)], this};
    const Status s = scheduler_.add(spec, now);
    if (s != Status::kOk) return s;
  }
  started_ = true;
  return Status::kOk;
}

std::size_t AutonomyStack::poll() {
  new_match_ = false;
  return started_ ? scheduler_.poll() : 0;
}

void AutonomyStack::background_step() {
  if (matcher_.local_map().rebuild() == Status::kOk) map_rebuilds_.fetch_add(1, std::memory_order_relaxed);
  // explorer_ is set by configure(), before the loop and this thread start.
  if (explorer_ != nullptr) explorer_->background_step();
  home_fix_.background_step();
  // A correction not yet taken holds the next scan back: the filter applies them in order.
  if (slam_out_.full()) return;
  const SlamInput* in = slam_in_.readable();
  if (in == nullptr) return;
  const slam::SlamResult r = slam_.process(in->points, in->prior);
  last_slam_step_ = {in->stamp, r, in->frame.to_filter(in->prior), in->frame.to_filter(r.fit), in->frame};
  ++slam_steps_;
  if (r.corrected()) {  // counted by the SLAM (slam().counters()); the filter counts its refusals
    PoseMeasurement2* out = slam_out_.writable();
    *out = {};
    out->stamp = in->stamp;
    out->pose = in->frame.to_filter(r.pose);
    slam_out_.post();
  }
  slam_in_.done();
}

void AutonomyStack::take_slam_correction() {
  const PoseMeasurement2* correction = slam_out_.readable();
  if (correction == nullptr) return;
  const Pose2 before = filter_.frame_correction();
  // Refusals are counted by the filter.
  if (filter_.apply_correction(*correction) == Status::kOk) estimate_moved(correction->stamp, before);
  slam_out_.done();
  nav_ = filter_.state();
}

void AutonomyStack::estimate_moved(TimeUs since, const Pose2& frame_before) {
  mission_.estimate_moved(since, filter_.frame_correction().compose(frame_before.inverse()));
}

void AutonomyStack::offer_scan_to_slam() {
  // A correction that arrived since this scan's update would leave the prior stale: the next
  // scan is offered instead (on a board, background_step runs on its own thread). The output
  // is read after the input slot is found free: level 3 posts a correction before it frees
  // the slot, so a free slot shows every correction made from the last scan.
  SlamInput* in = slam_in_.writable();
  if (in == nullptr || slam_out_.full()) return;
  // Half a laser period of slack: a Hokuyo's stamps are whole milliseconds that jitter, and a
  // 10 Hz laser's 99 ms gap must not halve the SLAM's rate.
  const Duration period = Duration::from_s(config_.slam_period_s) - Duration{dev_.laser.geometry().scan_period.us / 2};
  if (slam_offered_ && scan_.stamp - last_slam_offer_ < period) return;
  scan_matching::PosePrior at_scan;
  if (!scan_prior_from_nav(nav_, scan_.stamp, at_scan)) return;
  in->points = matcher_.scan_points();
  in->prior = slam_frame_.to_slam(at_scan.pose);
  in->stamp = scan_.stamp;
  in->frame = slam_frame_;
  last_slam_offer_ = scan_.stamp;
  slam_offered_ = true;
  slam_in_.post();
}

void AutonomyStack::offer_scan_to_home_fix() {
  // Only scans the matcher fitted: a lost one's pose is the filter's prediction.
  if ((last_match_.measurement.flags & scan_matching::match_flag::kLost) != 0) return;
  scan_matching::PosePrior at_scan;
  if (!scan_prior_from_nav(nav_, scan_.stamp, at_scan)) return;
  const mission::Phase phase = mission_.phase();
  const bool homing = mission_.homing();
  const bool at_altitude = (phase == mission::Phase::kTakeoff || phase == mission::Phase::kExplore) &&
                           nav_.position_m.z() >= 0.8f * mission_.params().takeoff_altitude_m;
  home_fix_.offer(matcher_.scan_points(), scan_, at_scan.pose, homing, at_altitude);
}

void AutonomyStack::take_home_fix() {
  PoseMeasurement2 fix;
  if (!home_fix_.take(fix)) return;
  const Pose2 before = filter_.frame_correction();
  if (filter_.apply_correction(fix) != Status::kOk) {
    ++counters_.home_fixes_refused;
    return;
  }
  ++counters_.home_fixes;
  slam_frame_.filter_moved(before, filter_.frame_correction());
  // Fixes come on the way home, after every breadcrumb: today this moves none, but the trail
  // stays in the filter's frame whatever a fix's stamp.
  estimate_moved(fix.stamp, before);
  nav_ = filter_.state();
}

void AutonomyStack::run_imu(void* self, TimeUs release) { static_cast<AutonomyStack*>(self)->imu_task(release); }
void AutonomyStack::run_scan_match(void* self, TimeUs release) {
  static_cast<AutonomyStack*>(self)->scan_task(release);
}
void AutonomyStack::run_guidance(void* self, TimeUs release) {
  static_cast<AutonomyStack*>(self)->guidance_task(release);
}
void AutonomyStack::run_control(void* self, TimeUs release) {
  static_cast<AutonomyStack*>(self)->control_task(release);
}

void AutonomyStack::imu_task(TimeUs now) {
  watchdog_.imu_polled(now);
  // Attitude first: the filter rotates the samples that follow with it.
  FlightStatus status;
  if (dev_.autopilot.poll_status(status) == Status::kOk) filter_.set_attitude(status);

  ImuSample s;
  for (;;) {
    const Status st = dev_.imu.poll(s);
    if (st == Status::kNoData) break;
    if (st != Status::kOk) {
      ++counters_.device_errors;
      break;
    }
    ++counters_.imu_samples;
    const Status p = filter_.predict(s);
    // Stored before the first pose, a sample is taken; after it, kNoData is one dropped as
    // before the state's start, and a stream that stays there is not alive.
    if (p == Status::kOk || (p == Status::kNoData && !filter_.initialised())) {
      watchdog_.imu_alive(now);
    } else {
      ++counters_.imu_errors;
    }
  }
  if (dev_.altimeter != nullptr) {
    AltimeterSample a;
    while (dev_.altimeter->poll(a) == Status::kOk) {
      ++counters_.altitude_samples;
      (void)filter_.update_altitude(a);  // rejections are counted by the filter
      newest_altitude_ = a;
      have_altitude_ = true;
    }
  }
  nav_ = filter_.state();
}

void AutonomyStack::scan_task(TimeUs now) {
  watchdog_.scan_polled(now);
  const Status st = dev_.laser.poll(scan_);
  if (st == Status::kNoData) return;
  if (st != Status::kOk) {
    ++counters_.device_errors;
    return;
  }
  ++counters_.scans;
  newest_scan_ = scan_;
  newest_scan_fresh_ = true;
  // Centre the search on the filter's pose at the scan's time: the IMU carries it through a
  // turn or a lost match, where the matcher's own constant-velocity guess would not. Its
  // uncertainty sizes the window: what the filter has not already accounted for.
  if (config_.slam_enabled) take_slam_correction();
  take_home_fix();
  scan_matching::PosePrior prior;
  const scan_matching::PosePrior* prior_ptr = scan_prior_from_nav(nav_, scan_.stamp, prior) ? &prior : nullptr;
  // The filter's frame has moved by the SLAM's corrections; the matcher's map has not.
  if (prior_ptr != nullptr && filter_.counters().corrections > 0)
    prior = prior_in_matcher_frame(prior, filter_.frame_correction());
  last_match_ = matcher_.process(scan_, prior_ptr);
  new_match_ = true;
  // The laser is alive while it delivers scans the matcher could use: a scan with too few
  // returns (nothing within reach) is the world's silence, not the device's.
  namespace mf = scan_matching::match_flag;
  if ((last_match_.measurement.flags & (mf::kBadGeometry | mf::kTimeBackwards)) == 0) watchdog_.scan_alive(now);
  if (!last_match_.ok()) {
    ++counters_.scans_rejected;
    return;
  }
  ++counters_.scans_matched;
  if ((last_match_.measurement.flags & scan_matching::match_flag::kLost) != 0) ++counters_.scans_lost;
  if ((last_match_.measurement.flags & scan_matching::match_flag::kMapRestarted) != 0) ++counters_.map_restarts;
  PoseMeasurement2 m = last_match_.measurement;
  if (!config_.use_measurement_time) m.stamp = dev_.clock.now();
  if (filter_.update_pose(m) == Status::kRejected) ++counters_.poses_gated;
  // Resting on the ground with the motors off, the vehicle does not move: a zero-velocity
  // update per scan lets the filter learn its accelerometer biases on every axis.
  if (mission_.at_rest() && !armed_) (void)filter_.update_at_rest(scan_.stamp, config_.ekf.at_rest_var);
  nav_ = filter_.state();
  if (config_.slam_enabled) offer_scan_to_slam();
  offer_scan_to_home_fix();
  guidance_scan_ = scan_;
  guidance_match_ = match_constraint_in_nav_frame(last_match_, scan_.stamp, filter_.frame_correction());
  guidance_scan_fresh_ = true;
}

void AutonomyStack::guidance_task(TimeUs now) {
  // The explorer plans once per scan, on the newest one; between scans its set-point stands.
  if (explorer_ != nullptr && guidance_scan_fresh_ && mission_.phase() == mission::Phase::kExplore) {
    explorer_->note_match(guidance_match_);
    (void)explorer_->step(nav_, guidance_scan_, explorer_out_.setpoint);
    explorer_out_.finished = explorer_->finished();
    guidance_scan_fresh_ = false;
    ++counters_.guidance_steps;
  }
  // The mission sees the estimate as stale while a device it stands on is silent: its failsafe.
  // On the way home it may leave its trail where the newest scan, if recent, shows the way clear.
  const bool scan_recent = ReturnVelocityBound::recent(now, dev_.laser.geometry().scan_period, newest_scan_);
  setpoint_ = mission_.step(now, watchdog_.for_mission(nav_), explorer_ != nullptr ? &explorer_out_ : nullptr,
                            scan_recent ? &newest_scan_ : nullptr, have_altitude_ ? &newest_altitude_ : nullptr);
  // Flying home and landing there, the explorer's approach limiter bounds the mission's
  // velocity set-point against the newest scan, matched or not (return_velocity_bound.hpp).
  const bool homing = mission_.phase() == mission::Phase::kReturn || mission_.phase() == mission::Phase::kLand;
  if (explorer_ != nullptr && homing &&
      setpoint_.mode == GuidanceSetpoint::Mode::kVelocity &&
      return_bound_.apply(now, dev_.laser.geometry().scan_period, newest_scan_, newest_scan_fresh_, nav_, *explorer_,
                          setpoint_) != Status::kOk)
    ++counters_.guidance_rejected;
  // Exploring and flying home the mission's height is the flight altitude, nobody's target;
  // a waypoint's height is the operator's, and the mission must still arrive at it.
  const bool exploring = mission_.phase() == mission::Phase::kExplore || mission_.phase() == mission::Phase::kReturn;
  const float floor = ClearanceGuard::floor_under(filter_.floor_m(), filter_.weighed_floor_m());
  const uint32_t rises_before = clearance_.rises();
  clearance_.apply(now, floor, exploring, setpoint_);
  const uint32_t rises = clearance_.rises() - rises_before;
  counters_.clearance_rises += rises;
  if (floor != filter_.floor_m()) counters_.clearance_rises_weighed += rises;
}

void AutonomyStack::control_task(TimeUs now) {
  const bool want = mission_.wants_armed();
  if (want != armed_) {
    if (dev_.autopilot.arm(want) == Status::kOk) {
      armed_ = want;
    } else {
      ++counters_.autopilot_errors;
    }
  }
  if (!armed_) return;
  control::ControlOutput out = controller_.step(nav_, setpoint_);
  if (!nav_.valid || !watchdog_.imu_fresh()) {
    // Blind: no estimate to steer on (none yet, or frozen with the IMU silent), so level the
    // vehicle at once. Until the mission's failsafe begins, hold hover thrust; in its descent,
    // sink at kBlindSinkAccel for kBlindSinkS to build a slow descent (about 0.3 m/s), then
    // nearly at hover thrust, so that it reaches the floor at about that speed (0.4 m/s from
    // 1 m) instead of gathering speed all the way down (0.8 m/s).
    constexpr float kBlindSinkAccel = -0.3f;  // m/s^2
    constexpr float kBlindSettleAccel = -0.05f;  // m/s^2
    constexpr Duration kBlindSinkS = Duration::from_ms(1000);
    const bool descending = mission_.phase() == mission::Phase::kFailsafeLand;
    if (descending && !blind_descending_) blind_descent_since_ = now;
    blind_descending_ = descending;
    float accel = 0.0f;
    if (descending) accel = now - blind_descent_since_ < kBlindSinkS ? kBlindSinkAccel : kBlindSettleAccel;
    out = controller_.safe_output(now, control::control_flag::kInvalidNav);
    out.command.thrust = controller_.params().model.thrust.command_for(accel);
  } else {
    blind_descending_ = false;
  }
  out.command.stamp = now;
  command_ = out.command;
  control_flags_ = out.flags;
  if (dev_.autopilot.send(command_) == Status::kOk) {
    ++counters_.setpoints_sent;
  } else {
    ++counters_.autopilot_errors;
  }
}

}  // namespace kestrel::autonomy
