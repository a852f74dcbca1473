#include "kestrel/flight/autonomy_mission.hpp"
#include "kestrel/flight/grid_map_image.hpp"
#include "kestrel/flight/slam_map_image.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>

#include "kestrel/core/alloc_guard.hpp"
#include "kestrel/estimation/nav_filter.hpp"
#include "kestrel/slam/slam_params.hpp"
#include "kestrel/output/pgm_map.hpp"
#include "kestrel/output/plot.hpp"
#include "kestrel/output/tum_writer.hpp"
#include "kestrel/sim/flight_recorder.hpp"
#include "kestrel/sim/simulation.hpp"
#if defined(KESTREL_HAS_PNG)
#include "kestrel/output/png_writer.hpp"
#endif

namespace kestrel::flight {

// Task execution is measured on the host's real clock, even though releases follow the
// simulated one: the timing figures are what this machine's CPU took.
class AutonomyMission::RealClock final : public TimeSource {
 public:
  TimeUs now() const override {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return TimeUs{static_cast<int64_t>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000};
  }
};

namespace {

// A parameter file's error in the words every tool uses (params::describe).
std::string param_error_text(const std::string& path, const params::ParamError& err) {
  char buf[512];
  params::describe(path.c_str(), err, buf, sizeof(buf));
  return buf;
}

// The SRT-Star tree (paper 002 Figure 5): safe regions as light sector fans, nodes and their
// parent links, frontiers as crosses, the current waypoint as a ring.
void draw_srt_tree(const exploration::SrtStarPlanner& planner, output::Canvas& c) {
  const exploration::SrtStarTree& tree = planner.tree();
  for (const exploration::SrtNode& n : tree.nodes()) {
    for (uint16_t k = 0; k < n.sector_count; ++k) {
      const double a = n.sector_start_rad + (k + 0.5) * n.sector_width_rad;
      const double r = n.radius_mm[k] * 1e-3;
      c.world_line(n.position.x, n.position.y, n.position.x + r * std::cos(a), n.position.y + r * std::sin(a),
                   output::Rgb{200, 230, 200}, 1);
    }
  }
  for (const exploration::SrtNode& n : tree.nodes()) {
    if (n.parent != exploration::kNoNode) {
      const exploration::SrtNode& p = tree.nodes()[n.parent];
      c.world_line(p.position.x, p.position.y, n.position.x, n.position.y, output::colors::kGreen, 2);
    }
    c.world_circle(n.position.x, n.position.y, 3, output::colors::kGreen, true);
  }
  for (const exploration::Frontier& f : tree.frontiers()) {
    const int x = c.wx(f.position.x), y = c.wy(f.position.y);
    c.line(x - 3, y - 3, x + 3, y + 3, output::colors::kPurple, 2);
    c.line(x - 3, y + 3, x + 3, y - 3, output::colors::kPurple, 2);
  }
  if (planner.has_waypoint())
    c.world_circle(planner.waypoint().x, planner.waypoint().y, 6, output::colors::kPurple, false);
}

// The grid frontier explorer (paper 003 Figure 7): its occupied cells, the frontier cells of
// its last plan, the path flown and its goal, and the blacklisted goals.
void draw_frontier_state(const exploration::FrontierExplorer& f, output::Canvas& c) {
  const planning::OccupancyGrid& g = f.grid();
  const planning::CellBox box = g.drawn();
  const float half = 0.5f * g.geometry().cell_m;
  for (int y = box.y0; y <= box.y1; ++y) {
    for (int x = box.x0; x <= box.x1; ++x) {
      const bool wall = planning::occupancy::is_occupied(g.at(x, y));
      const bool frontier = f.frontier_cells().was_frontier(x, y);
      if (!wall && !frontier) continue;
      const Point2 p = g.geometry().centre_of({static_cast<int16_t>(x), static_cast<int16_t>(y)});
      c.rect(c.wx(p.x - half), c.wy(p.y + half), c.wx(p.x + half), c.wy(p.y - half),
             wall ? output::Rgb{90, 90, 90} : output::colors::kPurple, true);
    }
  }
  const exploration::FrontierPlan& plan = f.plan_in_flight();
  for (std::size_t i = 1; i < plan.path.size(); ++i)
    c.world_line(plan.path[i - 1].x, plan.path[i - 1].y, plan.path[i].x, plan.path[i].y, output::colors::kGreen, 2);
  if (plan.has_goal) c.world_circle(plan.frontier.x, plan.frontier.y, 6, output::colors::kPurple, false);
  for (const Point2& p : f.blacklist()) {
    const int x = c.wx(p.x), y = c.wy(p.y);
    c.line(x - 4, y - 4, x + 4, y + 4, output::colors::kRed, 2);
    c.line(x - 4, y + 4, x + 4, y - 4, output::colors::kRed, 2);
  }
}

bool parse_double(const std::string& s, double& out) {
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0' && std::isfinite(out);
}

// The explorer's distances from laser returns settable by name, or nullptr for another key.
float* explorer_distance(const std::string& key, exploration::Params& p) {
  if (key == "wall_target_m") return &p.wall.target_range_m;
  if (key == "wall_safe_m") return &p.wall.safe_range_m;
  if (key == "srt_clearance_m") return &p.srt.clearance_m;
  if (key == "approach_stop_m") return &p.approach.stop_distance_m;
  return nullptr;
}

// The explorer's on/off options, or nullptr for another key.
bool* explorer_switch(const std::string& key, exploration::Params& p) {
  if (key == "approach") return &p.approach.enabled;
  if (key == "srt_memory") return &p.srt.prefer_unvisited;
  if (key == "srt_rescue") return &p.srt.rescue_frontiers;
  if (key == "srt_beam_jumps") return &p.srt.discontinuity_needs_beam_jump;
  return nullptr;
}

}  // namespace

std::string parse_keep_outs(const std::string& text, exploration::SrtParams& srt) {
  srt.keep_out_count = 0;
  std::stringstream boxes(text);
  // Messages are built with append: GCC 12's -Wrestrict misreads operator+ chains here (ARM).
  std::string why;
  for (std::string box; std::getline(boxes, box, ';');) {
    std::stringstream fields(box);
    std::vector<double> v;
    for (std::string f; std::getline(fields, f, ',');) {
      double d = 0;
      if (!parse_double(f, d)) return why.append("'").append(f).append("' is not a number");
      v.push_back(d);
    }
    if (v.size() != 4) return why.append("expected x_min,y_min,x_max,y_max (m), got '").append(box).append("'");
    if (v[0] > v[2] || v[1] > v[3])
      return why.append("'").append(box).append("': the minimum corner must come first");
    if (srt.keep_out_count == exploration::kMaxKeepOuts)
      return why.append("more than ").append(std::to_string(exploration::kMaxKeepOuts)).append(" boxes");
    srt.keep_out[srt.keep_out_count++] = {static_cast<float>(v[0]), static_cast<float>(v[1]),
                                          static_cast<float>(v[2]), static_cast<float>(v[3])};
  }
  if (srt.keep_out_count == 0) return "no box";
  return "";
}

std::string load_waypoints(const std::string& path, autonomy::StackConfig& stack) {
  std::ifstream in(path);
  if (!in) return path + ": cannot be read";
  stack.waypoints.clear();
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ls(line);
    std::vector<double> v;
    std::string tok;
    while (ls >> tok) {
      double d;
      if (!parse_double(tok, d)) return path + ":" + std::to_string(n) + ": '" + tok + "' is not a number";
      v.push_back(d);
    }
    if (v.empty()) continue;
    if (v.size() < 3 || v.size() > 5)
      return path + ":" + std::to_string(n) + ": expected x y z [heading_deg [hold_s]], got " +
             std::to_string(v.size()) + " values";
    if (v[2] <= 0) return path + ":" + std::to_string(n) + ": z must be above the floor";
    if (v.size() == 5 && v[4] < 0) return path + ":" + std::to_string(n) + ": hold time must not be negative";
    mission::Waypoint w;
    w.position_m = {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
    w.heading_rad = v.size() >= 4 ? static_cast<float>(v[3] * M_PI / 180.0) : 0.0f;
    w.hold_s = v.size() == 5 ? static_cast<float>(v[4]) : 0.0f;
    if (!stack.waypoints.push_back(w))
      return path + ":" + std::to_string(n) + ": more than " +
             std::to_string(mission::MissionController::kMaxWaypoints) + " waypoints";
  }
  if (stack.waypoints.empty()) return path + ": no waypoints";
  return "";
}

std::string parse_flight_options(mission::MissionKind kind, const sim::MissionOptions& options, FlightOptions& out) {
  out.kind = kind;
  out.stack.mission_kind = kind;
  const char* mission_name = mission::to_string(kind);
  for (const auto& [key, value] : options.values) {
    double d = 0;
    if (key == "waypoints" && kind == mission::MissionKind::kWaypoints) {
      if (std::string e = load_waypoints(value, out.stack); !e.empty()) return e;
    } else if (key == "explorer" && kind == mission::MissionKind::kExplore) {
      const Result<exploration::ExplorerKind> k = exploration::parse_explorer_kind(value.c_str());
      if (!k.ok()) return "explorer: unknown explorer '" + value + "' (blend, wallfollow, srt or frontier)";
      out.stack.explorer_kind = k.value();
    } else if (key == "hover_s" && kind == mission::MissionKind::kHover) {
      if (!parse_double(value, d) || d < 0) return "hover_s: '" + value + "' is not a non-negative number";
      out.stack.mission.hover_duration_s = static_cast<float>(d);
    } else if (key == "explore_s" && kind == mission::MissionKind::kExplore) {
      if (!parse_double(value, d) || d < 0) return "explore_s: '" + value + "' is not a non-negative number";
      out.stack.mission.explore_time_limit_s = static_cast<float>(d);
    } else if (key == "srt_steer" && kind == mission::MissionKind::kExplore) {
      const Result<exploration::SteerUnflown> s = exploration::parse_steer_unflown(value.c_str());
      if (!s.ok()) return "srt_steer: expected off, restarted, every or root, got '" + value + "'";
      out.stack.explorer.srt.steer = s.value();
    } else if (key == "srt_retrace" && kind == mission::MissionKind::kExplore) {
      const Result<exploration::RetraceMode> m = exploration::parse_retrace_mode(value.c_str());
      if (!m.ok()) return "srt_retrace: expected off, guarded or on, got '" + value + "'";
      out.stack.explorer.srt.retrace = m.value();
    } else if (key == "srt_retrace_target" && kind == mission::MissionKind::kExplore) {
      const Result<exploration::RetraceTarget> t = exploration::parse_retrace_target(value.c_str());
      if (!t.ok()) return "srt_retrace_target: expected unflown or frontier, got '" + value + "'";
      out.stack.explorer.srt.retrace_target = t.value();
    } else if (key == "keepout" && kind == mission::MissionKind::kExplore) {
      if (std::string e = parse_keep_outs(value, out.stack.explorer.srt); !e.empty()) return "keepout: " + e;
    } else if (key == "keepout_drift_margin_m" && kind == mission::MissionKind::kExplore) {
      // The range SrtParams validates: named here so the error says which value was refused.
      if (!parse_double(value, d) || d < 0 || d > 10)
        return "keepout_drift_margin_m: '" + value + "' is not a distance in [0, 10] m";
      out.stack.explorer.srt.keep_out_drift_margin_m = static_cast<float>(d);
    } else if (key == "home_fix" && kind == mission::MissionKind::kExplore) {
      if (value != "on" && value != "off") return "home_fix: expected on or off, got '" + value + "'";
      out.stack.home_fix.enabled = value == "on";
    } else if (key == "home_fix_explore_m" && kind == mission::MissionKind::kExplore) {
      // The home fix searches while exploring too, within this of home (0: only flying home).
      if (!parse_double(value, d) || d < 0 || d > 12)
        return "home_fix_explore_m: '" + value + "' is not a distance in [0, 12] m";
      out.stack.home_fix.explore_radius_m = static_cast<float>(d);
    } else if (key == "takeoff_survey_rad" && kind == mission::MissionKind::kExplore) {
      // The home fix's turn after take-off, whichever the explorer (0: none; its reference
      // scans then see only what lies ahead).
      if (!parse_double(value, d) || d < 0 || d > 12.5)
        return "takeoff_survey_rad: '" + value + "' is not an angle in [0, 12.5] rad";
      out.stack.home_fix.survey_rad = out.stack.home_fix.frontier_survey_rad = static_cast<float>(d);
    } else if (key == "return_shortcut" && kind == mission::MissionKind::kExplore) {
      if (value != "on" && value != "off") return "return_shortcut: expected on or off, got '" + value + "'";
      out.stack.mission.return_shortcut = value == "on";
    } else if (key == "return_realign_s" && kind == mission::MissionKind::kExplore) {
      // Stalled this long on the way home, the trail ahead is laid onto the scan (0: never).
      if (!parse_double(value, d) || d < 0) return "return_realign_s: '" + value + "' is not a non-negative number";
      out.stack.mission.return_realign_s = static_cast<float>(d);
    } else if (bool* on = explorer_switch(key, out.stack.explorer);
               on != nullptr && kind == mission::MissionKind::kExplore) {
      if (value != "on" && value != "off") {
        std::string e = key;
        e.append(": expected on or off, got '").append(value).append("'");
        return e;
      }
      *on = value == "on";
    } else if (key == "srt_range_m" && kind == mission::MissionKind::kExplore) {
      if (!parse_double(value, d) || d <= 0 || d >= 65)
        return "srt_range_m: '" + value + "' is not a range in (0, 65) m";
      out.stack.explorer.srt.perception_range_m = static_cast<float>(d);
    } else if (key == "frontier_reach_m" && kind == mission::MissionKind::kExplore) {
      // How far the frontier explorer's rays draw (4 m by default, for both lasers).
      if (!parse_double(value, d) || d <= 0 || d > 30)
        return "frontier_reach_m: '" + value + "' is not a range in (0, 30] m";
      out.stack.explorer.frontier.reach_m = static_cast<float>(d);
    } else if (key == "frontier_relaxed_m" && kind == mission::MissionKind::kExplore) {
      // The frontier explorer's second search (0: none); at most its lethal distance (checked at start).
      if (!parse_double(value, d) || d < 0 || d > 2)
        return "frontier_relaxed_m: '" + value + "' is not a distance in [0, 2] m";
      out.stack.explorer.frontier.relaxed_lethal_m = static_cast<float>(d);
    } else if (key == "frontier_coastal" && kind == mission::MissionKind::kExplore) {
      // Coastal navigation: the share of the laser's range within which paths keep to walls (0: off).
      if (!parse_double(value, d) || d < 0 || d > 1)
        return "frontier_coastal: '" + value + "' is not a fraction in [0, 1]";
      out.stack.explorer.frontier.coastal_fraction = static_cast<float>(d);
    } else if (key == "speed_limit_mps" && kind == mission::MissionKind::kExplore) {
      // Section V's speed limit (0.5 m/s by default, paper 002's); the approach limiter
      // still bounds the closing speed on every return, unless approach=off.
      if (!parse_double(value, d) || d <= 0 || d > 5)
        return "speed_limit_mps: '" + value + "' is not a speed in (0, 5] m/s";
      out.stack.explorer.guidance.speed_limit_mps = static_cast<float>(d);
    } else if (key == "yaw_rate_limit_radps" && kind == mission::MissionKind::kExplore) {
      // Section V's yaw-rate limit on the heading command (0.5 rad/s by default).
      if (!parse_double(value, d) || d <= 0 || d > 10)
        return "yaw_rate_limit_radps: '" + value + "' is not a rate in (0, 10] rad/s";
      out.stack.explorer.guidance.yaw_rate_limit_radps = static_cast<float>(d);
    } else if (key == "look_across_s" && kind == mission::MissionKind::kExplore) {
      // Turn the heading across a degenerate match's axis after this long (0: off, the default).
      if (!parse_double(value, d) || d < 0 || d > 600)
        return "look_across_s: '" + value + "' is not a time in [0, 600] s";
      out.stack.explorer.look_across.after_s = static_cast<float>(d);
    } else if (key == "look_across_release_s" && kind == mission::MissionKind::kExplore) {
      if (!parse_double(value, d) || d < 0 || d > 600)
        return "look_across_release_s: '" + value + "' is not a time in [0, 600] s";
      out.stack.explorer.look_across.release_s = static_cast<float>(d);
    } else if (key == "approach_blind_mps" && kind == mission::MissionKind::kExplore) {
      if (!parse_double(value, d) || d < 0 || d > 10)
        return "approach_blind_mps: '" + value + "' is not a speed in [0, 10] m/s";
      out.stack.explorer.approach.blind_speed_mps = static_cast<float>(d);
    } else if (float* distance = explorer_distance(key, out.stack.explorer);
               distance != nullptr && kind == mission::MissionKind::kExplore) {
      // The explorer's distances from laser returns (modules/exploration/EXPERIMENTS.md, "Not
      // done": the same physical margins when the laser sees walls' faces,
      // sim.laser_sees_wall_thickness).
      // Their relations (r_safe < r_t, stop <= clearance) are checked when the stack starts.
      if (!parse_double(value, d) || d <= 0 || d > 5) {
        std::string why = key;  // append, not operator+: see parse_keep_outs
        return why.append(": '").append(value).append("' is not a distance in (0, 5] m");
      }
      *distance = static_cast<float>(d);
    } else if (key == "altitude_m" && kind != mission::MissionKind::kWaypoints) {
      // Paper 000 section 3.3: the laser sees only its own plane; an operator picks the height
      // that clears what it cannot see (iarc-arena's 1.0 m stair railing) and still sees the rest.
      if (!parse_double(value, d) || d < 0.3 || d > 3.0)
        return "altitude_m: '" + value + "' is not a height in [0.3, 3] m";
      out.stack.mission.takeoff_altitude_m = static_cast<float>(d);
    } else if (key == "clearance_m" && kind == mission::MissionKind::kExplore) {
      // The height kept over furniture the altimeter finds (autonomy/clearance_guard.hpp): 0 off.
      if (!parse_double(value, d) || d < 0 || d > 3)
        return "clearance_m: '" + value + "' is not a clearance in [0, 3] m";
      out.stack.clearance.min_clearance_m = static_cast<float>(d);
    } else if (key == "corridor_keys_s") {
      // The scan matcher's degenerate_key_interval_s: off by default (README, Exploration;
      // modules/exploration/EXPERIMENTS.md).
      if (!parse_double(value, d) || d < 0 || d > 60)
        return "corridor_keys_s: '" + value + "' is not a time in [0, 60] s";
      out.stack.matcher.degenerate_key_interval_s = static_cast<float>(d);
    } else if (key == "delay_s") {
      if (!parse_double(value, d) || d < 0 || d > 2) return "delay_s: '" + value + "' is not a delay in [0, 2] s";
      out.delay_s = d;
    } else if (key == "history") {
      if (value != "on" && value != "off") return "history: expected on or off, got '" + value + "'";
      out.use_measurement_time = value == "on";
    } else if (key == "ekf") {
      // Checked here, loaded by start() over the laser's defaults.
      params::ParamError err;
      if (estimation::load_ekf_params(value.c_str(), out.stack.ekf, err) != Status::kOk)
        return param_error_text(value, err);
      out.ekf_file = value;
    } else if (key == "slam") {
      // on, off, or a parameter file (modules/slam/include/kestrel/slam/slam_params.hpp) that
      // turns it on.
      if (value == "on" || value == "off") {
        out.slam_on = value == "on";
      } else {
        params::ParamError err;
        if (slam::load_slam_params(value.c_str(), out.stack.slam, err) != Status::kOk)
          return param_error_text(value, err);
        out.slam_on = true;
      }
    } else if (key == "controller") {
      params::ParamError err;
      if (control::load_controller_params(value.c_str(), out.stack.controller, err) != Status::kOk)
        return param_error_text(value, err);
    } else {
      return std::string("mission '") + mission_name + "' has no option '" + key + "'";
    }
  }
  if (kind == mission::MissionKind::kWaypoints && out.stack.waypoints.empty())
    return "mission 'waypoints' needs --waypoints FILE";
  return "";
}

AutonomyMission::AutonomyMission(FlightOptions options)
    : options_(std::move(options)), exec_clock_(std::make_unique<RealClock>()) {}

AutonomyMission::~AutonomyMission() = default;

Status AutonomyMission::start(sim::Simulation& sim) {
  hal::LaserScanner* laser = &sim.laser();
  if (options_.delay_s > 0) {
    delayed_ = std::make_unique<DelayedLaser>(sim.laser(), sim.clock(), Duration::from_s(options_.delay_s));
    laser = delayed_.get();
  }
  const autonomy::Devices devices{sim.clock(), *laser, sim.imu(), &sim.altimeter(), sim.flight_controller()};
  stack_ = std::make_unique<autonomy::AutonomyStack>(devices, *exec_clock_);
  autonomy::StackConfig cfg = options_.stack;
  const sim::VehicleState& t = sim.truth();
  cfg.home = Pose2{static_cast<float>(t.position_m.x()), static_cast<float>(t.position_m.y()),
                   static_cast<float>(t.yaw_rad)};
  cfg.use_measurement_time = options_.use_measurement_time;
  if (options_.ekf_for_laser) {
    cfg.ekf = autonomy::vehicle_ekf_params(laser->geometry().max_range_mm);
    params::ParamError err;
    if (!options_.ekf_file.empty() &&
        estimation::load_ekf_params(options_.ekf_file.c_str(), cfg.ekf, err) != Status::kOk) {
      failure_ = param_error_text(options_.ekf_file, err);
      return Status::kInvalidArgument;
    }
  }
  cfg.slam_enabled = options_.slam_on.value_or(autonomy::vehicle_slam_enabled(laser->geometry().max_range_mm));
  if (stack_->configure(cfg) != Status::kOk) {
    failure_ = std::string("autonomy stack configuration: ") + stack_->configure_error();
    return Status::kInvalidArgument;
  }
  if (!traces_dir_.empty() && cfg.slam_enabled) {
    const std::string path = traces_dir_ + "/slam_trace.csv";
    if (slam_trace_.open(path) != Status::kOk) {
      failure_ = "cannot write the SLAM trace '" + path + "'";
      return Status::kIoError;
    }
  }
  const Status s = stack_->start();
  if (s != Status::kOk) failure_ = std::string("autonomy stack start: ") + to_string(s);
  samples_.reserve(200000);
  return s;
}

sim::MissionState AutonomyMission::tick(sim::Simulation& sim) {
  // The loop proper: every allocation in here is one too many (DESIGN.md).
  while (stack_->next_release() <= sim.now()) {
    const uint64_t before = alloc_guard::count();
    alloc_guard::arm();
    stack_->poll();
    stack_->background_step();
    alloc_guard::disarm();
    allocs_in_loop_ += alloc_guard::count() - before;
    if (stack_->new_match()) {
      score(sim);
      if (trace_.is_open()) trace(sim);
    }
    if (slam_trace_.is_open() && stack_->slam_steps() != slam_steps_traced_) trace_slam(sim);
  }
  if (stack_->mission().phase() == mission::Phase::kHover) {
    const Eigen::Vector3d sp = stack_->setpoint().position_m.cast<double>();
    hover_sq_sum_ += (sim.truth().position_m - sp).squaredNorm();
    ++hover_n_;
  }
  if (stack_->finished()) return sim::MissionState::kDone;
  return sim::MissionState::kRunning;
}

void AutonomyMission::score(sim::Simulation& sim) {
  const NavState& nav = stack_->nav();
  if (!nav.valid) return;
  sim::VehicleState truth;
  if (sim.truth_at(nav.stamp, truth) != Status::kOk) return;
  EstimateSample s;
  s.t_s = nav.stamp.seconds();
  s.est_pos = nav.position_m.cast<double>();
  s.true_pos = truth.position_m;
  s.est_vel = nav.velocity_mps.cast<double>();
  s.true_vel = truth.velocity_mps;
  s.est_yaw = nav.heading_rad;
  s.true_yaw = truth.yaw_rad;
  // Non-finite samples are refused by both (a NaN estimate shows as fewer samples).
  (void)nav_error_.add({nav.stamp, s.est_pos, s.est_vel}, {nav.stamp, s.true_pos, s.true_vel});
  (void)drift_.add(s.est_pos.head<2>(), s.true_pos.head<2>(), !truth.on_ground);
  samples_.push_back(s);
  (void)runaways_.add(s.t_s, (s.est_pos - s.true_pos).head<2>().norm());
}

void AutonomyMission::trace(sim::Simulation& sim) {
  const scan_matching::ScanMatch& m = stack_->last_match();
  const NavState f = stack_->filter().state();
  sim::VehicleState at_scan, at_nav;
  const bool have_scan = sim.truth_at(m.measurement.stamp, at_scan) == Status::kOk;
  const bool have_nav = f.valid && sim.truth_at(f.stamp, at_nav) == Status::kOk;
  trace_.write(m, f, have_scan ? &at_scan : nullptr, have_nav ? &at_nav : nullptr);
}

void AutonomyMission::trace_slam(sim::Simulation& sim) {
  slam_steps_traced_ = stack_->slam_steps();
  const autonomy::SlamStep& step = stack_->last_slam_step();
  sim::VehicleState truth;
  const bool have_truth = sim.truth_at(step.stamp, truth) == Status::kOk;
  double true_level = std::nan("");
  namespace sf = slam::slam_flag;
  if (have_truth && (step.result.flags & sf::kMatched) != 0 && (step.result.flags & sf::kDrawn) == 0) {
    const Pose2 at{static_cast<float>(truth.position_m.x()), static_cast<float>(truth.position_m.y()),
                   static_cast<float>(truth.yaw_rad)};
    const slam::CompactSlam& s = stack_->slam();
    true_level = static_cast<double>(slam::mean_level(s.map(), s.last_scan(), step.frame.to_slam(at))) / slam::kSub;
  }
  slam_trace_.write(step, have_truth ? &truth : nullptr, true_level);
}

Status AutonomyMission::open_traces(const std::string& out_dir) {
  const Status s = trace_.open(out_dir + "/scan_trace.csv");
  if (s == Status::kOk) traces_dir_ = out_dir;
  return s;
}

std::optional<sim::EstimateError> estimate_error_at(const std::vector<EstimateSample>& samples, double t_s,
                                                    double max_age_s) {
  // A whole pass, not the newest few: stamps come in order today, and a stamp that went back
  // (or a NaN one) must not hide the sample sought. A contact ends the flight, so this runs
  // once or twice per run.
  const EstimateSample* best = nullptr;
  for (const EstimateSample& s : samples)
    if (std::isfinite(s.t_s) && s.t_s <= t_s && (best == nullptr || s.t_s > best->t_s)) best = &s;
  if (best == nullptr || !(t_s - best->t_s <= max_age_s)) return std::nullopt;
  const Eigen::Vector3d e = best->est_pos - best->true_pos;
  if (!e.head<2>().allFinite()) return std::nullopt;
  return sim::EstimateError{e.x(), e.y()};
}

std::optional<sim::EstimateError> AutonomyMission::estimate_error_at(TimeUs t) const {
  return flight::estimate_error_at(samples_, t.seconds(), kContactSampleMaxAgeS);
}

double AutonomyMission::hover_rms_m() const {
  return hover_n_ == 0 ? std::nan("") : std::sqrt(hover_sq_sum_ / static_cast<double>(hover_n_));
}

void AutonomyMission::metrics(sim::MissionMetrics& out) const {
  const metrics::EkfErrorStats nav = nav_error_.stats();
  const bool have = nav.position_m.count > 0;
  const double nan = std::nan("");
  if (options_.kind == mission::MissionKind::kHover) out.emplace_back("hover_rms_m", hover_rms_m());
  out.emplace_back("pos_err_mean_m", have ? nav.position_m.mean : nan);
  out.emplace_back("vel_err_mean_mps", have ? nav.velocity_mps.mean : nan);
  out.emplace_back("vel_err_std_mps", nav.velocity_mps.count > 1 ? nav.velocity_mps.std : nan);
  const metrics::HorizontalDrift d = drift_.result();
  out.emplace_back("pos_err_xy_max_m", d.airborne_m.count > 0 ? d.airborne_m.max : nan);
  out.emplace_back("pos_err_xy_far_m", d.samples > 0 ? d.far_error_m : nan);
  out.emplace_back("far_from_start_m", d.samples > 0 ? d.far_from_start_m : nan);
  out.emplace_back("pos_err_xy_final_m", d.samples > 0 ? d.final_error_m : nan);
  out.emplace_back("estimate_runaways", static_cast<double>(runaways_.runaways()));
  out.emplace_back("heap_allocs_after_arm", static_cast<double>(allocs_in_loop_));
  out.emplace_back("delay_s", options_.delay_s);
  out.emplace_back("state_history", options_.use_measurement_time ? 1.0 : 0.0);
  const autonomy::StackCounters& c = stack_->counters();
  out.emplace_back("stack_scans", c.scans);
  out.emplace_back("scans_matched", c.scans_matched);
  out.emplace_back("scans_rejected", c.scans_rejected);
  out.emplace_back("poses_gated", c.poses_gated);
  out.emplace_back("map_rebuilds", stack_->map_rebuilds());
  out.emplace_back("scans_lost", c.scans_lost);
  out.emplace_back("map_restarts", c.map_restarts);
  // The compact SLAM's own counts (all zero when it is off): scans it matched or drew, the
  // corrections it handed to the filter (nav.corrections and nav.corrections_rejected say what
  // the filter made of them), the scans drawn and those draw_min_curvature kept out.
  out.emplace_back("slam_scans", stack_->slam().counters().scans);
  out.emplace_back("slam_corrections", stack_->slam().counters().corrections);
  out.emplace_back("slam_drawn", stack_->slam().counters().drawn);
  out.emplace_back("slam_unpinned", stack_->slam().counters().unpinned);
  out.emplace_back("imu_silences", stack_->silences().imu);
  out.emplace_back("scan_silences", stack_->silences().scan);
  out.emplace_back("setpoints_sent", c.setpoints_sent);
  // The filter's own counts: what it refused and why (an out-of-range IMU sample, a measurement
  // from the future, ...), so a flight that drifted can be told from one fed bad input.
  const estimation::NavFilterCounters& nav_counters = stack_->filter().counters();
  for (const estimation::NavFilterCounterField& f : estimation::kNavFilterCounterFields)
    out.emplace_back(std::string("nav.") + f.name, nav_counters.*f.member);
  out.emplace_back("mission_finished", stack_->finished() ? 1.0 : 0.0);
  // What said the vehicle was down (all zero while it is not): a landing held up by something
  // the altimeter does not see is told from one the altimeter or the estimate saw through.
  for (std::size_t i = 1; i < mission::kTouchdownByCount; ++i) {  // 0 is kNone
    const auto by = static_cast<mission::TouchdownBy>(i);
    std::string key = "touchdown_by.";
    key.append(mission::to_string(by));
    out.emplace_back(std::move(key), stack_->mission().touchdown_by() == by ? 1.0 : 0.0);
  }
  out.emplace_back("returned_home", stack_->mission().returned_home() ? 1.0 : 0.0);
  out.emplace_back("return_shortcuts", stack_->mission().shortcuts());
  out.emplace_back("return_realignments", stack_->mission().realignments());
  // Home re-localisation (home_fix.hpp): reference scans drawn, scans searched on the way home,
  // fixes found, confirmed by the next search, and applied (or refused) by the filter.
  const autonomy::HomeFixCounters& hf = stack_->home_fix().counters();
  out.emplace_back("home_fix_references", hf.references);
  out.emplace_back("home_fix_searches", hf.searches);
  out.emplace_back("home_fix_found", hf.found);
  out.emplace_back("home_fix_no_fit", hf.no_fit);
  out.emplace_back("home_fix_no_gain", hf.no_gain);
  out.emplace_back("home_fix_ambiguous", hf.ambiguous);
  out.emplace_back("home_fix_sees_through", hf.sees_through);
  out.emplace_back("home_fix_returns_in_free", hf.returns_in_free);
  out.emplace_back("home_fix_confirmed", hf.confirmed);
  out.emplace_back("home_fixes", c.home_fixes);
  out.emplace_back("home_fixes_refused", c.home_fixes_refused);
  out.emplace_back("clearance_rises", c.clearance_rises);
  out.emplace_back("clearance_rises_weighed", c.clearance_rises_weighed);
  // When each phase began (its first time): an explore phase that ended well before
  // explore_s ran out of frontiers.
  for (std::size_t i = 0; i < mission::kPhaseCount; ++i) {
    const auto phase = static_cast<mission::Phase>(i);
    TimeUs at;
    if (!stack_->mission().first_entered(phase, at)) continue;
    std::string key = "phase_start_s.";
    key.append(mission::to_string(phase));
    out.emplace_back(std::move(key), at.seconds());
  }
  if (const exploration::Explorer* e = stack_->explorer(); e != nullptr) {
    out.emplace_back("approach_scaled", e->status().approach_scaled);
    out.emplace_back("approach_stops", e->status().approach_stops);
    out.emplace_back("look_across_turns", e->status().look_across_turns);
    out.emplace_back("return_setpoints_unbounded", c.guidance_rejected);
    out.emplace_back("explorer_finished", e->finished() ? 1.0 : 0.0);
    if (e->planner() != nullptr) {
      out.emplace_back("srt_restarts", e->planner()->restarts());
      // Why: a timeout or a full tree erases what the tree knew; exhausted is the search
      // starting once more after a tree ran out (the last of them after a look back).
      for (std::size_t i = 1; i < exploration::kRestartReasonCount; ++i) {  // 0 is kNone
        const auto why = static_cast<exploration::RestartReason>(i);
        std::string key = "srt_restarts.";
        key.append(exploration::to_string(why));
        out.emplace_back(std::move(key), e->planner()->restarts(why));
      }
      out.emplace_back("srt_blocked_arrivals", e->planner()->blocked_arrivals());
      out.emplace_back("srt_frontiers_handed_up", e->planner()->frontiers_handed_up());
      out.emplace_back("srt_steer_pauses", e->planner()->steer_pauses());
      out.emplace_back("srt_look_backs", e->planner()->look_backs());
      out.emplace_back("srt_retraces", e->planner()->retraces());
    }
    if (e->kind() == exploration::ExplorerKind::kFrontier) {
      const auto& f = static_cast<const exploration::FrontierExplorer&>(*e);
      const exploration::FrontierCounters k = f.counters();
      const std::pair<const char*, uint32_t> rows[] = {
          {"scans_offered", k.scans_offered}, {"scans_dropped", k.scans_dropped}, {"scans_drawn", k.scans_drawn},
          {"draw_errors", k.draw_errors}, {"plans", k.plans}, {"plans_dropped", k.plans_dropped},
          {"plans_taken", k.plans_taken}, {"search_failures", k.search_failures}, {"relaxed_plans", k.relaxed_plans},
          {"grid_restarts", k.grid_restarts}, {"homed", k.homed}, {"goals", k.goals},
          {"arrivals", k.arrivals}, {"stale_holds", k.stale_holds}, {"blacklisted", k.blacklisted},
          {"stuck", k.stuck}, {"looked_at", k.looked_at}, {"peak_open", k.peak_open}};
      for (const auto& [name, v] : rows) out.emplace_back(std::string("frontier.") + name, v);
    }
  }
  const Scheduler& s = stack_->scheduler();
  for (std::size_t i = 0; i < s.task_count(); ++i) {
    const std::string prefix = std::string("tasks.") + s.spec(i).name + ".";
    out.emplace_back(prefix + "us_mean", s.stats(i).mean_us());
    out.emplace_back(prefix + "us_max", static_cast<double>(s.stats(i).max_us));
    out.emplace_back(prefix + "deadline_misses", static_cast<double>(s.stats(i).deadline_misses()));
    out.emplace_back(prefix + "runs", static_cast<double>(s.stats(i).runs));
  }
}

Status AutonomyMission::write_outputs(const std::string& dir) const {
  // A trace that could not be written keeps neither the other trace nor the flight's files
  // from being written.
  const Status scan = trace_.flush();
  const Status slam = slam_trace_.flush();
  const Status files = write_flight_files(dir);
  return scan == Status::kOk && slam == Status::kOk && files == Status::kOk ? Status::kOk : Status::kIoError;
}

Status AutonomyMission::write_flight_files(const std::string& dir) const {
  output::TumWriter tum;
  if (tum.open(dir + "/trajectory_est.tum") != Status::kOk) return Status::kIoError;
  for (const EstimateSample& s : samples_)
    if (tum.write(s.t_s, s.est_pos.x(), s.est_pos.y(), s.est_pos.z(), s.est_yaw) != Status::kOk)
      return Status::kIoError;
  if (tum.close() != Status::kOk) return Status::kIoError;
  // The compact SLAM's map, when it ran (DESIGN.md's map.pgm + map.yaml), and as a picture:
  // its grey levels with the estimated path (slam_map.png).
  if (stack_ && stack_->slam().started()) {
    const output::GridImage map = slam_map_image(stack_->slam().map());
    if (map.width > 0 && output::write_map(dir + "/map", map) != Status::kOk) return Status::kIoError;
#if defined(KESTREL_HAS_PNG)
    if (map.width > 0) {
      constexpr int kPx = 3;  // pixels per cell
      output::Canvas c(map.width * kPx, map.height * kPx);
      c.set_world_view(map.origin_x_m, map.origin_y_m, kPx / map.resolution_m);
      const slam::SlamMap& m = stack_->slam().map();
      for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
          // The cell under this pixel block's centre; rows run down the canvas as y goes up.
          const double wx = map.origin_x_m + (x + 0.5) * map.resolution_m,
                       wy = map.origin_y_m + (y + 0.5) * map.resolution_m;
          const slam::SubPoint sp = m.to_sub(static_cast<float>(wx), static_cast<float>(wy));
          const uint8_t v = m.at(sp.x >> slam::kSubBits, sp.y >> slam::kSubBits);
          const int px = x * kPx, py = (map.height - 1 - y) * kPx;
          c.rect(px, py, px + kPx - 1, py + kPx - 1, output::Rgb{v, v, v}, true);
        }
      }
      for (std::size_t i = 1; i < samples_.size(); ++i)
        c.world_line(samples_[i - 1].est_pos.x(), samples_[i - 1].est_pos.y(), samples_[i].est_pos.x(),
                     samples_[i].est_pos.y(), output::colors::kOrange, 1);
      c.scale_bar(10, c.height() - 20, 5.0, output::colors::kBlue);
      if (output::write_png(dir + "/slam_map.png", c) != Status::kOk) return Status::kIoError;
    }
#endif
  }
  // Without the SLAM, the frontier explorer's grid is the flight's map.
  const exploration::Explorer* e = stack_ ? stack_->explorer() : nullptr;
  if (stack_ && !stack_->slam().started() && e != nullptr && e->kind() == exploration::ExplorerKind::kFrontier) {
    const output::GridImage grid = grid_map_image(static_cast<const exploration::FrontierExplorer&>(*e).grid());
    if (grid.width > 0 && output::write_map(dir + "/map", grid) != Status::kOk) return Status::kIoError;
  }
  if (options_.kind == mission::MissionKind::kExplore && recorder() != nullptr) {
    // The numbers behind coverage_vs_time.png, so a sweep can average runs on one plot
    // (kestrel-coverage-plot): one `t_s,coverage` row per sample, coverage as a fraction.
    std::ofstream csv(dir + "/coverage_vs_time.csv");
    if (!csv) return Status::kIoError;
    csv << "t_s,coverage\n";
    char row[64];
    for (const sim::FlightRecorder::CoverageSample& c : recorder()->coverage_series()) {
      std::snprintf(row, sizeof row, "%.3f,%.6f\n", c.t_s, c.coverage);
      csv << row;
    }
    if (!csv.flush()) return Status::kIoError;
  }
#if defined(KESTREL_HAS_PNG)
  // Paper 000 Figure 6: estimated against true position and velocity.
  output::Series ex{"estimate x", output::colors::kRed, {}, {}}, tx{"truth x", output::colors::kBlue, {}, {}};
  output::Series ey{"estimate y", output::colors::kOrange, {}, {}}, ty{"truth y", output::colors::kCyan, {}, {}};
  output::Series evx{"estimate vx", output::colors::kRed, {}, {}}, tvx{"truth vx", output::colors::kBlue, {}, {}};
  output::Series evy{"estimate vy", output::colors::kOrange, {}, {}}, tvy{"truth vy", output::colors::kCyan, {}, {}};
  for (const EstimateSample& s : samples_) {
    for (output::Series* se : {&ex, &tx, &ey, &ty, &evx, &tvx, &evy, &tvy}) se->x.push_back(s.t_s);
    ex.y.push_back(s.est_pos.x());
    tx.y.push_back(s.true_pos.x());
    ey.y.push_back(s.est_pos.y());
    ty.y.push_back(s.true_pos.y());
    evx.y.push_back(s.est_vel.x());
    tvx.y.push_back(s.true_vel.x());
    evy.y.push_back(s.est_vel.y());
    tvy.y.push_back(s.true_vel.y());
  }
  const output::Canvas plot = output::plot_panels(
      {{"position x", "m", {tx, ex}}, {"position y", "m", {ty, ey}}, {"velocity x", "m/s", {tvx, evx}},
       {"velocity y", "m/s", {tvy, evy}}},
      "time [s]", 1100, 230);
  if (output::write_png(dir + "/estimate_vs_truth.png", plot) != Status::kOk) return Status::kIoError;
  if (options_.kind == mission::MissionKind::kExplore && recorder() != nullptr) {
    // Issue 6: coverage of the reachable free area against time, with the 90 % line that
    // coverage_t90_s reports crossing.
    const sim::FlightRecorder& rec = *recorder();
    const char* kind = stack_ && stack_->explorer() ? exploration::to_string(stack_->explorer()->kind()) : "explore";
    output::Series cov{std::string("coverage (") + kind + ")", output::colors::kBlue, {}, {}};
    output::Series ninety{"90 %", output::colors::kGrey, {}, {}};
    for (const sim::FlightRecorder::CoverageSample& c : rec.coverage_series()) {
      cov.x.push_back(c.t_s);
      cov.y.push_back(100.0 * c.coverage);
    }
    if (!cov.x.empty()) {
      ninety.x = {0.0, cov.x.back()};
      ninety.y = {90.0, 90.0};
    }
    const output::Canvas cplot =
        output::plot_panels({{"coverage of the reachable area", "%", {cov, ninety}}}, "time [s]", 1000, 360);
    if (output::write_png(dir + "/coverage_vs_time.png", cplot) != Status::kOk) return Status::kIoError;
  }
#endif
  return Status::kOk;
}

std::vector<sim::Mission::LegendRow> AutonomyMission::legend() const {
  std::vector<LegendRow> rows = {{"ESTIMATED PATH", output::colors::kOrange}};
  const bool grid = stack_ && stack_->explorer() && stack_->explorer()->kind() == exploration::ExplorerKind::kFrontier;
  if (options_.kind == mission::MissionKind::kExplore && grid) {
    rows.push_back({"GRID: WALL CELLS", output::Rgb{90, 90, 90}});
    rows.push_back({"PATH TO THE FRONTIER", output::colors::kGreen});
    rows.push_back({"FRONTIER CELLS / GOAL", output::colors::kPurple});
    rows.push_back({"BLACKLISTED GOAL", output::colors::kRed});
    rows.push_back({"WAY HOME (TRAIL)", output::colors::kGrey});
  } else if (options_.kind == mission::MissionKind::kExplore) {
    rows.push_back({"SRT TREE", output::colors::kGreen});
    rows.push_back({"FRONTIER / WAYPOINT", output::colors::kPurple});
    rows.push_back({"WAY HOME (TRAIL)", output::colors::kGrey});
  }
  return rows;
}

void AutonomyMission::draw(output::Canvas& c) const {
  // The estimated path over the world (the true one is drawn by the simulator's renderer).
  for (std::size_t i = 1; i < samples_.size(); ++i)
    c.world_line(samples_[i - 1].est_pos.x(), samples_[i - 1].est_pos.y(), samples_[i].est_pos.x(),
                 samples_[i].est_pos.y(), output::colors::kOrange, 1);
  const exploration::Explorer* e = stack_ ? stack_->explorer() : nullptr;
  const exploration::SrtStarPlanner* planner = e != nullptr ? e->planner() : nullptr;
  if (planner != nullptr) draw_srt_tree(*planner, c);
  if (e != nullptr && e->kind() == exploration::ExplorerKind::kFrontier)
    draw_frontier_state(static_cast<const exploration::FrontierExplorer&>(*e), c);
  if (stack_) {
    const mission::BreadcrumbTrail& trail = stack_->mission().trail();
    for (std::size_t i = 0; i < trail.size(); ++i)
      c.world_circle(trail.point(i).x(), trail.point(i).y(), 1, output::colors::kGrey, true);
  }
}

}  // namespace kestrel::flight
