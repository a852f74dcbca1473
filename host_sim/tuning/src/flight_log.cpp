#include "kestrel/tuning/flight_log.hpp"

#include <memory>

#include "kestrel/flight/autonomy_mission.hpp"
#include "kestrel/sim/builtin_worlds.hpp"
#include "kestrel/sim/command_script.hpp"
#include "kestrel/sim/manual_mission.hpp"
#include "kestrel/sim/sim_altimeter.hpp"
#include "kestrel/sim/simulation.hpp"

namespace kestrel::tuning {
namespace {

// The observer taps: every IMU sample, and every physics step's truth with the set-point the
// autopilot applied during it (the autopilot releases delayed commands at the step's start,
// so asking again for that instant returns the same command and changes nothing).
class Recorder final : public sim::SimObserver {
 public:
  Recorder(sim::Simulation& s, FlightLog& log, Duration status_period)
      : sim_(s), log_(log), status_period_(status_period) {}
  void on_imu(const ImuSample& sample) override { log_.imu.push_back(sample); }
  void on_step(const sim::VehicleState& t) override {
    TruthRecord r;
    r.stamp = t.stamp;
    r.position_m = t.position_m;
    r.velocity_mps = t.velocity_mps;
    r.accel_mps2 = t.accel_mps2;
    r.yaw_rad = t.yaw_rad;
    r.yaw_rate_radps = t.yaw_rate_radps;
    r.on_ground = t.on_ground;
    r.command = sim_.autopilot().active(t.stamp - sim_.step_duration());
    log_.truth.push_back(r);
    // The autopilot's attitude report, at its status rate, as FakeAutopilot makes it.
    if (log_.attitude.empty() || t.stamp >= log_.attitude.back().stamp + status_period_) {
      FlightStatus st;
      st.stamp = t.stamp;
      st.armed = sim_.autopilot().armed();
      st.roll_rad = static_cast<float>(t.roll_rad);
      st.pitch_rad = static_cast<float>(t.pitch_rad);
      st.yaw_rad = static_cast<float>(t.yaw_rad);
      log_.attitude.push_back(st);
    }
  }

 private:
  sim::Simulation& sim_;
  FlightLog& log_;
  Duration status_period_;
};

// Reads the altimeter queue and puts the samples back in order: the stack polls the same
// queue afterwards and sees exactly what it would have seen.
void tap_altimeter(sim::Simulation& s, FlightLog& log) {
  auto& alt = static_cast<sim::SimAltimeter&>(s.altimeter());
  AltimeterSample buf[64];
  std::size_t n = 0;
  while (n < 64 && alt.poll(buf[n]) == Status::kOk) ++n;
  for (std::size_t i = 0; i < n; ++i) {
    // The stack may leave samples queued across ticks: record each one once.
    if (log.altitude.empty() || buf[i].stamp > log.altitude.back().stamp) log.altitude.push_back(buf[i]);
    (void)alt.push(buf[i]);
  }
}

}  // namespace

std::vector<Eigen::Vector4f> arena_waypoints() {
  return {{5.0f, 7.5f, 1.0f, 0.0f},  {5.0f, 7.0f, 1.3f, 0.0f}, {3.0f, 8.2f, 1.0f, 0.5f},
          {6.0f, 7.5f, 0.8f, 0.0f}, {2.5f, 7.5f, 1.0f, 0.0f}};
}

std::string fly_and_record(const FlightSpec& spec, FlightLog& log) {
  log = FlightLog{};
  const sim::WorldParseResult world = sim::load_world(spec.world);
  if (!world.ok) return world.error;
  if (std::string e = spec.sim.validate(); !e.empty()) return e;
  sim::Simulation s(world.world, spec.sim);
  const Duration status_period = Duration::from_s(1.0 / spec.sim.status_rate_hz);
  Recorder rec(s, log, status_period);
  s.set_observer(&rec);

  std::unique_ptr<sim::Mission> mission;
  flight::AutonomyMission* autonomy = nullptr;
  if (spec.kind == FlightKind::kManual) {
    sim::CommandScript script;
    const std::string e = script.parse(spec.script_text, spec.script_name);
    if (!e.empty()) return e;
    mission = std::make_unique<sim::ManualMission>(std::move(script));
  } else {
    flight::FlightOptions fo;
    fo.kind = spec.kind == FlightKind::kHover ? mission::MissionKind::kHover : mission::MissionKind::kWaypoints;
    fo.stack.mission_kind = fo.kind;
    fo.stack.mission.hover_duration_s = static_cast<float>(spec.hover_s);
    fo.stack.ekf = spec.ekf;
    fo.ekf_for_laser = false;  // the parameters under test, whatever the laser
    fo.slam_on = false;        // the filter under test on the scan matcher alone
    if (!spec.use_default_controller) fo.stack.controller = spec.controller;
    if (spec.kind == FlightKind::kWaypoints) {
      for (const Eigen::Vector4f& w : spec.waypoints) {
        mission::Waypoint wp;
        wp.position_m = w.head<3>();
        wp.heading_rad = w[3];
        if (!fo.stack.waypoints.push_back(wp)) return "too many waypoints";
      }
      if (fo.stack.waypoints.empty()) return "the waypoints flight needs waypoints";
    }
    auto m = std::make_unique<flight::AutonomyMission>(std::move(fo));
    autonomy = m.get();
    mission = std::move(m);
  }

  // The loop of sim::run_mission, with the taps between the steps and the ticks.
  if (const Status st = mission->start(s); st != Status::kOk)
    return std::string("mission did not start: ") + to_string(st);
  const TimeUs stop = s.now() + Duration::from_s(spec.duration_s);
  const Duration tick = mission->tick_period().us > 0 ? mission->tick_period() : Duration::from_ms(10);
  TimeUs last_pose;
  bool have_pose = false;
  auto take_pose = [&] {
    if (autonomy == nullptr) return;
    const auto& m = autonomy->stack().last_match();
    if (!m.ok() || (have_pose && m.measurement.stamp <= last_pose)) return;
    if (m.points == 0) return;  // nothing matched yet
    last_pose = m.measurement.stamp;
    have_pose = true;
    log.poses.push_back(m.measurement);
    log.pose_delivery_us.push_back((s.now() - m.measurement.stamp).us);
  };
  tap_altimeter(s, log);
  sim::MissionState state = mission->tick(s);
  take_pose();
  while (state == sim::MissionState::kRunning && s.now() < stop) {
    TimeUs next = s.now() + tick;
    if (next > stop) next = stop;
    (void)s.step_until(next);
    if (s.flight_ended()) {
      log.collided = true;
      break;
    }
    tap_altimeter(s, log);
    state = mission->tick(s);
    take_pose();
  }
  s.set_observer(nullptr);
  if (autonomy != nullptr) {
    log.hover_rms_m = autonomy->hover_rms_m();
    log.poses_gated = autonomy->stack().counters().poses_gated;
  }
  log.end_message = log.collided ? "collision" : state == sim::MissionState::kDone ? "done"
                                               : state == sim::MissionState::kFailed ? "failed: " + mission->failure()
                                                                                      : "time limit";
  return "";
}

}  // namespace kestrel::tuning
