#include "run_outputs.hpp"

#include <cmath>
#include <limits>
#include <optional>

#include "kestrel/output/json_writer.hpp"
#include "kestrel/output/tum_writer.hpp"

namespace kestrel::sim::tools {

Status write_metrics(const std::string& path, const SimOptions& opt, Simulation& sim, const FlightRecorder& rec,
                     const RunResult& run, const Mission& mission, uint64_t heap_allocs_after_arm) {
  output::JsonWriter j;
  j.begin_object();
  j.string("world", sim.world().name);
  j.string("mission", mission.name());
  j.string("laser", opt.laser);
  j.integer("seed", static_cast<int64_t>(opt.seed));
  j.number("duration_s", opt.duration_s);
  j.number("sim_time_s", run.end.seconds());
  j.string("end_reason", run.message);
  j.integer("collisions", static_cast<int64_t>(sim.contacts().size()));
  j.integer("heap_allocs_after_arm", static_cast<int64_t>(heap_allocs_after_arm));
  j.begin_array("contacts");
  for (const Contact& c : sim.contacts()) {
    j.begin_object();
    j.number("t_s", c.stamp.seconds());
    j.number("x_m", c.position_m.x());
    j.number("y_m", c.position_m.y());
    j.number("z_m", c.position_m.z());
    j.number("depth_m", c.depth_m);
    j.integer("world_line", c.line);
    // Whose contact it was: the estimator's when the estimate was metres off; else not the
    // estimator's (the guidance's, or a surface the simulated laser does not show).
    if (const std::optional<EstimateError> e = mission.estimate_error_at(c.stamp)) {
      j.number("estimate_err_x_m", e->x_m);
      j.number("estimate_err_y_m", e->y_m);
      j.number("estimate_err_m", std::hypot(e->x_m, e->y_m));
    }
    j.end_object();
  }
  j.end_array();
  j.number("coverage", rec.coverage());
  if (rec.coverage_t90_s() >= 0) j.number("coverage_t90_s", rec.coverage_t90_s());
  else j.number("coverage_t90_s", std::numeric_limits<double>::quiet_NaN());
  j.integer("rooms_entered", rec.rooms_entered());
  j.integer("rooms_total", static_cast<int64_t>(sim.world().rooms.size()));
  // Which rooms a flight missed, not only how many: each room's first entry, null if never.
  j.begin_object("room_entry_s");
  const std::vector<double>& entry = rec.room_entry_s();
  for (std::size_t i = 0; i < entry.size() && i < sim.world().rooms.size(); ++i)
    j.number(sim.world().rooms[i].name.c_str(), entry[i] >= 0 ? entry[i] : std::numeric_limits<double>::quiet_NaN());
  j.end_object();
  if (rec.t_all_rooms_s() >= 0) j.number("t_all_rooms_s", rec.t_all_rooms_s());
  else j.number("t_all_rooms_s", std::numeric_limits<double>::quiet_NaN());
  j.number("reachable_area_m2", rec.free_space().reachable_area_m2());
  j.number("distance_m", rec.distance_m());
  j.number("max_speed_mps", rec.max_speed_mps());
  j.number("max_altitude_m", rec.max_altitude_m());
  j.integer("scans", static_cast<int64_t>(rec.scans()));
  j.integer("imu_samples", static_cast<int64_t>(rec.imu_samples()));
  const VehicleState& t = sim.truth();
  j.begin_object("final_truth");
  j.number("x_m", t.position_m.x());
  j.number("y_m", t.position_m.y());
  j.number("z_m", t.position_m.z());
  j.number("yaw_rad", t.yaw_rad);
  j.end_object();
  // Where the flight ended against where it took off, by the truth: the mission's
  // returned_home is by the estimate, which may have drifted.
  j.number("final_from_start_m",
           std::hypot(t.position_m.x() - sim.world().start.x, t.position_m.y() - sim.world().start.y));
  MissionMetrics extra;
  mission.metrics(extra);
  for (const auto& [k, v] : extra) j.number(k.c_str(), v);
  j.end_object();
  return j.write_file(path);
}

Status write_truth_tum(const std::string& path, const FlightRecorder& rec) {
  output::TumWriter w;
  if (Status s = w.open(path); s != Status::kOk) return s;
  for (const VehicleState& s : rec.scan_truth()) {
    const Status st = w.write(s.stamp.seconds(), s.position_m.x(), s.position_m.y(), s.position_m.z(), s.yaw_rad,
                              s.roll_rad, s.pitch_rad);
    if (st != Status::kOk) return st;
  }
  return w.close();
}

}  // namespace kestrel::sim::tools
