#include "kestrel/exploration/frontier_explorer.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::exploration {

using planning::Cell;
using planning::CellBox;
using planning::ObstacleDistance;

namespace {
// Within this of facing the frontier, the laser (240 or 270 degrees) has it well inside its fan.
constexpr float kFacingRad = 0.35f;
// Cells the grid must learn for that to count as progress (a metre of corridor's width, say).
constexpr uint32_t kNewCellsForProgress = 40;
// Older than this, a plan is not flown (level 3 stalled): replan_period_s is at most 60 s.
constexpr Duration kMaxPlanAge = Duration::from_ms(5000);

// Metres as path cost (planning::GridSearch: 10 per straight cell).
uint32_t cost_of(float metres, float cell_m) { return static_cast<uint32_t>(std::lround(metres / cell_m * 10.0f)); }

}  // namespace

Status FrontierExplorer::configure_strategy() {
  const bool ok = !params_.approach.enabled || params_.approach.stop_distance_m <= params_.frontier.lethal_m;
  return ok ? Status::kOk : Status::kInvalidArgument;
}

void FrontierExplorer::reset_strategy() {
  plan_ = FrontierPlan{};
  have_plan_ = false;
  leg_ = 0;
  arrived_seq_ = 0;
  arrival_pending_ = false;
  offered_ = false;
  level2_ = FrontierCounters{};
  // Level 3 forgets at its next step: on a board it may be running now.
  reset_requested_.store(true, std::memory_order_release);
  finished_.store(false, std::memory_order_release);
}

FrontierCounters FrontierExplorer::counters() const {
  FrontierCounters c = level3_;
  c.scans_offered = level2_.scans_offered;
  c.scans_dropped = level2_.scans_dropped;
  c.plans_taken = level2_.plans_taken;
  c.arrivals = level2_.arrivals;
  c.stale_holds = level2_.stale_holds;
  return c;
}

// ---- level 2 ----

Point2 FrontierExplorer::carrot(const Pose2& pose) {
  const planning::PathPoints& path = plan_.path;
  if (path.size() == 1) return path[0];
  // The nearest point on the legs from the current one on (a few ahead: the path may have been
  // cut short by the vehicle itself).
  std::size_t best_leg = leg_;
  float best_t = 0, best_d = INFINITY;
  for (std::size_t i = leg_; i + 1 < path.size() && i < leg_ + 4; ++i) {
    const float ax = path[i].x, ay = path[i].y, bx = path[i + 1].x, by = path[i + 1].y;
    const float lx = bx - ax, ly = by - ay, l2 = lx * lx + ly * ly;
    const float t = l2 > 1e-9f ? std::clamp(((pose.x - ax) * lx + (pose.y - ay) * ly) / l2, 0.0f, 1.0f) : 1.0f;
    const float d = std::hypot(ax + t * lx - pose.x, ay + t * ly - pose.y);
    if (d < best_d) {
      best_d = d;
      best_leg = i;
      best_t = t;
    }
  }
  leg_ = best_leg;
  // lookahead_m further along the path from there.
  float left = params_.frontier.lookahead_m;
  std::size_t i = best_leg;
  float t = best_t;
  while (i + 1 < path.size()) {
    const float lx = path[i + 1].x - path[i].x, ly = path[i + 1].y - path[i].y, len = std::hypot(lx, ly);
    const float rest = (1.0f - t) * len;
    if (rest >= left && len > 1e-6f) {
      const float u = t + left / len;
      return {path[i].x + u * lx, path[i].y + u * ly};
    }
    left -= rest;
    ++i;
    t = 0;
  }
  return path.back();
}

Status FrontierExplorer::plan(const Pose2& pose, const LaserScan& scan, TimeUs now, GuidanceSetpoint& out,
                              float& heading_target) {
  const FrontierParams& fp = params_.frontier;
  // Down to level 3: the scan, the pose it was taken at, and whether the plan's end was reached.
  if (!offered_ || now - last_offer_ >= Duration::from_s(fp.draw_period_s) || arrival_pending_) {
    staging_.scan = scan;
    staging_.pose = pose;
    staging_.arrived = arrival_pending_;
    if (to_level3_.push(staging_)) {
      ++level2_.scans_offered;
      last_offer_ = now;
      offered_ = true;
      arrival_pending_ = false;
    } else {
      ++level2_.scans_dropped;
    }
  }
  // Up from level 3: the newest plan.
  while (to_level2_.pop(incoming_)) {
    plan_ = incoming_;
    have_plan_ = true;
    leg_ = 0;
    ++level2_.plans_taken;
  }
  Eigen::Vector2f v = wall_following_velocity(scan, pose.theta) * fp.field_weight;
  status_.has_target = false;
  status_.v_fr.setZero();
  // A plan level 3 has not renewed for kMaxPlanAge (it plans at least every replan_period_s)
  // is not flown: the vehicle holds on the field alone until level 3 is back.
  const bool fresh = have_plan_ && now - plan_.stamp <= kMaxPlanAge;
  if (have_plan_ && !fresh) ++level2_.stale_holds;
  if (fresh && plan_.has_goal && !plan_.path.empty()) {
    const Point2 c = carrot(pose);
    status_.has_target = true;
    status_.target = c;
    const float dx = c.x - pose.x, dy = c.y - pose.y;
    status_.v_fr = {params_.guidance.gain_fr * dx, params_.guidance.gain_fr * dy};
    v += status_.v_fr;
    const float arrival = params_.guidance.arrival_distance_m;
    if (distance(plan_.path.back(), {pose.x, pose.y}) > arrival) {
      // Facing the way it flies: the laser's blind arc stays behind.
      if (std::hypot(dx, dy) > arrival) heading_target = std::atan2(dy, dx);
    } else if (plan_.homing) {
      // Home: level 3 judges it by the pose it is given.
    } else {
      // At the end: face the frontier, so that the laser has looked at it (one behind the
      // vehicle, in the blind arc, is cleared by turning). Arrived once it faces it.
      heading_target = std::atan2(plan_.frontier.y - pose.y, plan_.frontier.x - pose.x);
      if (plan_.seq != arrived_seq_ && std::fabs(wrap_angle(heading_target - pose.theta)) <= kFacingRad) {
        arrived_seq_ = plan_.seq;
        arrival_pending_ = true;
        ++level2_.arrivals;
      }
    }
  }
  out.mode = GuidanceSetpoint::Mode::kVelocity;
  out.velocity_mps = {v.x(), v.y(), 0.0f};
  return Status::kOk;
}

// ---- level 3 ----

void FrontierExplorer::reset_level3() {
  grid_ready_ = false;
  clusters_.clear();
  blacklist_count_ = blacklist_next_ = 0;
  arrived_ = planned_ = goal_active_ = stuck_armed_ = homing_ = false;
  seq_ = 0;
  empty_plans_ = 0;
  level3_ = FrontierCounters{};
}

void FrontierExplorer::background_step() {
  if (!configured()) return;
  if (reset_requested_.exchange(false, std::memory_order_acq_rel)) reset_level3();
  bool drew = false;
  while (to_level3_.pop(work_)) {
    if (!grid_ready_) {
      const BeamGeometry& g = field_.geometry();
      planning::GridParams gp;
      gp.cell_m = params_.frontier.cell_m;
      gp.reach_m = params_.frontier.reach_m;
      if (grid_.configure(gp, {work_.pose.x, work_.pose.y}, g.beam_count, g.first_angle_rad, g.angle_step_rad) !=
          Status::kOk) {
        ++level3_.draw_errors;
        continue;
      }
      grid_ready_ = true;
      (void)grid_.geometry().to_cell(work_.pose.x, work_.pose.y, home_cell_);
    }
    if (grid_.draw(work_.scan, work_.pose) != Status::kOk) {
      ++level3_.draw_errors;
      continue;
    }
    ++level3_.scans_drawn;
    pose_ = work_.pose;
    stamp_ = work_.scan.stamp;
    look_at_goal();
    arrived_ = arrived_ || work_.arrived;
    drew = true;
  }
  if (!drew) return;
  if (!planned_ || arrived_ || stamp_ - last_plan_ >= Duration::from_s(params_.frontier.replan_period_s))
    replan(stamp_);
}

void FrontierExplorer::add_to_blacklist(const Point2& p) {
  blacklist_[blacklist_next_] = p;
  blacklist_next_ = (blacklist_next_ + 1) % kMaxBlacklist;
  blacklist_count_ = std::min(blacklist_count_ + 1, kMaxBlacklist);
  ++level3_.blacklisted;
  goal_active_ = false;
}

// Paper 003: "In case for a specified time no progress towards a goal pose is achieved, the
// currently pursued goal pose will be put on a blacklist." Also given up: a goal held longer
// than goal_time_limit_s, and one reached whose frontier is still there (the laser cannot
// clear it from where the planner can go: seen through a gap too narrow to fly).
void FrontierExplorer::judge_goal(TimeUs now) {
  if (!goal_active_) {
    stuck_armed_ = false;  // hovering with nothing to fly to is not being stuck
    return;
  }
  const FrontierParams& fp = params_.frontier;
  const Point2 goal = grid_.geometry().centre_of(goal_cell_);
  // Progress is the path to the goal shortening, or the grid learning cells (a flight that
  // sees new ground is exploring, wherever it heads).
  const uint16_t c = search_.cost(goal_cell_);
  if (c != planning::GridSearch::kUnreached && c + cost_of(fp.progress_m, fp.cell_m) <= best_cost_) {
    best_cost_ = c;
    last_progress_ = now;
  }
  if (grid_.known_cells() >= known_at_progress_ + kNewCellsForProgress) {
    known_at_progress_ = grid_.known_cells();
    last_progress_ = now;
  }
  const bool still_there = FrontierClusterFinder::is_frontier(grid_, goal_cell_.x, goal_cell_.y);
  const Point2 here{pose_.x, pose_.y};
  if (!stuck_armed_ || distance(here, stuck_anchor_) > fp.stuck_radius_m) {
    stuck_anchor_ = here;
    stuck_since_ = now;
    stuck_armed_ = true;
  }
  if (arrived_ && still_there) {
    add_to_blacklist(goal);
  } else if (still_there && looks_ >= fp.looks_to_give_up) {
    ++level3_.looked_at;
    add_to_blacklist(goal);
  } else if (now - stuck_since_ > Duration::from_s(fp.stuck_time_s)) {
    ++level3_.stuck;
    stuck_since_ = now;
    add_to_blacklist(goal);
  } else if (now - last_progress_ > Duration::from_s(fp.patience_s) ||
             now - goal_since_ > Duration::from_s(fp.goal_time_limit_s)) {
    last_progress_ = now;  // the next goal gets its own patience
    add_to_blacklist(goal);
  }
}

void FrontierExplorer::look_at_goal() {
  if (!goal_active_) return;
  const Point2 goal = grid_.geometry().centre_of(goal_cell_);
  const float dx = goal.x - pose_.x, dy = goal.y - pose_.y;
  if (std::hypot(dx, dy) > params_.frontier.look_distance_m) return;
  // Inside the fan, with a margin of a tenth of it on either side.
  const BeamGeometry& g = field_.geometry();
  const float half = 0.4f * std::fabs(g.angle_step_rad) * static_cast<float>(g.beam_count);
  const float mid = g.first_angle_rad + 0.5f * g.angle_step_rad * static_cast<float>(g.beam_count - 1);
  if (std::fabs(wrap_angle(std::atan2(dy, dx) - pose_.theta - mid)) <= half && looks_ < 0xFFFF) ++looks_;
}

bool FrontierExplorer::in_blacklist(const Point2& p) const {
  for (std::size_t i = 0; i < blacklist_count_; ++i)
    if (distance(blacklist_[i], p) <= params_.frontier.blacklist_radius_m) return true;
  return false;
}

void FrontierExplorer::replan(TimeUs now) {
  const FrontierParams& fp = params_.frontier;
  const planning::GridGeometry& geo = grid_.geometry();
  planned_ = true;
  last_plan_ = now;
  ++level3_.plans;
  // The operator's keep-out boxes are obstacles to the planner (kept lethal_m off even by the
  // relaxed search): a window the beams pass is no way through. Lengthened along their wall by
  // the drift margin: the map, and the window's gap in it, lie in the estimate's frame, the box
  // where the operator put it, and an estimate drifted along the wall finds the gap beside it.
  std::array<CellBox, kMaxKeepOuts> blocked{};
  std::size_t n_blocked = 0;
  for (std::size_t i = 0; i < params_.srt.keep_out_count && i < kMaxKeepOuts; ++i) {
    const KeepOut k = params_.srt.keep_out[i].lengthened(params_.srt.keep_out_drift_margin_m);
    const auto clamp_cell = [&](float x, float y) {
      const float fx = std::clamp((x - geo.origin.x) / geo.cell_m, 0.0f, static_cast<float>(planning::kGridSide - 1));
      const float fy = std::clamp((y - geo.origin.y) / geo.cell_m, 0.0f, static_cast<float>(planning::kGridSide - 1));
      return Cell{static_cast<int16_t>(fx), static_cast<int16_t>(fy)};
    };
    // Grown by what the relaxed search gives up: no search comes nearer than lethal_m.
    const float grow = fp.relaxed_lethal_m > 0.0f ? fp.lethal_m - std::min(fp.relaxed_lethal_m, fp.lethal_m) : 0.0f;
    // A box wholly off the grid blocks nothing: clamped, it would block the edge's cells.
    const float side = static_cast<float>(planning::kGridSide) * geo.cell_m;
    if (k.x_max + grow < geo.origin.x || k.x_min - grow > geo.origin.x + side || k.y_max + grow < geo.origin.y ||
        k.y_min - grow > geo.origin.y + side)
      continue;
    const Cell a = clamp_cell(k.x_min - grow, k.y_min - grow), b = clamp_cell(k.x_max + grow, k.y_max + grow);
    blocked[n_blocked++] = {a.x, a.y, b.x, b.y};
  }
  const CellBox box = grid_.drawn().grown(2);
  distance_.compute(grid_, box, {blocked.data(), n_blocked});
  Cell start;
  if (!geo.to_cell(pose_.x, pose_.y, start) || !box.contains(start.x, start.y)) {
    ++level3_.search_failures;
    return;
  }
  if (!search_frontiers(fp.lethal_m, box, start)) return;
  if (homing_) {
    // The relaxed search, if the strict one finds no way home.
    if (!search_.reached(home_cell_) && fp.relaxed_lethal_m > 0.0f &&
        !search_frontiers(fp.relaxed_lethal_m, box, start))
      return;
    plan_home();
    return;
  }
  if (fp.relaxed_lethal_m > 0.0f && fp.relaxed_lethal_m < fp.lethal_m && clusters_.empty()) {
    if (!search_frontiers(fp.relaxed_lethal_m, box, start)) return;
    if (!clusters_.empty()) ++level3_.relaxed_plans;
  }
  judge_goal(now);
  arrived_ = false;

  // The current goal's cell stays the goal while it is still a frontier cell the search
  // reaches, unless a frontier switch_margin_m cheaper appears (two frontiers alike in cost
  // would otherwise take turns); else the cheapest frontier.
  const FrontierCluster* best = clusters_.empty() ? nullptr : &clusters_[0];
  bool keep = false;
  if (goal_active_ && search_.reached(goal_cell_) &&
      FrontierClusterFinder::is_frontier(grid_, goal_cell_.x, goal_cell_.y) && !in_blacklist(geo.centre_of(goal_cell_)))
    keep = best == nullptr || !(best->cost + cost_of(fp.switch_margin_m, geo.cell_m) < search_.cost(goal_cell_));
  const bool have_goal = keep || best != nullptr;
  const Cell target = keep ? goal_cell_ : (best != nullptr ? best->nearest : Cell{});
  // A new goal, or the same one (a goal's nearest cell moves as its frontier recedes).
  const bool same_goal =
      have_goal && goal_active_ && distance(geo.centre_of(target), geo.centre_of(goal_cell_)) <= fp.goal_match_m;

  outgoing_ = FrontierPlan{};
  outgoing_.stamp = now;
  if (!have_goal) {
    goal_active_ = false;
    if (empty_plans_ < 255) ++empty_plans_;
    if (empty_plans_ >= fp.empty_plans_to_finish) {
      if (finder_.inaccessible() > 0 && level3_.grid_restarts < fp.max_grid_restarts) {
        // Frontiers are left that no path reaches: the grid, not the building, is closed.
        grid_.clear();
        blacklist_count_ = blacklist_next_ = 0;
        empty_plans_ = 0;
        stuck_armed_ = false;
        ++level3_.grid_restarts;
      } else {
        homing_ = true;
        plan_home();
        return;
      }
    }
    publish();
    return;
  }
  empty_plans_ = 0;
  if (!same_goal) {
    if (!goal_active_) {
      last_progress_ = now;
      known_at_progress_ = grid_.known_cells();
    }
    goal_active_ = true;
    goal_since_ = now;
    looks_ = 0;
    best_cost_ = search_.cost(target);
    ++level3_.goals;
  }
  goal_cell_ = target;
  if (search_.path_to(target, path_cells_) != Status::kOk && path_cells_.empty()) {
    ++level3_.search_failures;
    return;
  }
  // The flight ends goal_inset_m short of the frontier, in known free space.
  const Point2 frontier = geo.centre_of(target);
  while (path_cells_.size() > 1 && distance(geo.centre_of(path_cells_.back()), frontier) < fp.goal_inset_m)
    path_cells_.pop_back();
  outgoing_.has_goal = true;
  outgoing_.frontier = frontier;
  (void)planning::simplify_path(grid_, distance_, path_cells_, outgoing_.path, coastal_units());
  publish();
}

uint8_t FrontierExplorer::coastal_units() const {
  const FrontierParams& fp = params_.frontier;
  if (fp.coastal_penalty == 0 || !(fp.coastal_fraction > 0.0f)) return 0;
  const float coast_m = fp.coastal_fraction * static_cast<float>(field_.geometry().max_range_mm) * 1e-3f;
  const uint8_t u = ObstacleDistance::units_of(coast_m, grid_.geometry().cell_m);
  // Beyond the distance's reach, or not beyond the soft band: no coast to keep to.
  return u >= ObstacleDistance::kFar || u <= ObstacleDistance::units_of(fp.soft_m, grid_.geometry().cell_m) ? 0 : u;
}

bool FrontierExplorer::search_frontiers(float lethal_m, const CellBox& box, Cell start) {
  const FrontierParams& fp = params_.frontier;
  const float cell_m = grid_.geometry().cell_m;
  planning::SearchCosts costs{ObstacleDistance::units_of(lethal_m, cell_m),
                              ObstacleDistance::units_of(fp.soft_m, cell_m), fp.soft_penalty};
  const uint8_t coast = coastal_units();
  if (coast > 0) {
    costs.far = coast;
    costs.far_penalty = fp.coastal_penalty;
  }
  const Status st = search_.run(grid_, distance_, box, start, costs);
  level3_.peak_open = std::max<uint32_t>(level3_.peak_open, static_cast<uint32_t>(search_.peak_open()));
  if (st != Status::kOk) {
    ++level3_.search_failures;
    clusters_.clear();
    return false;
  }
  const uint16_t min_cells = static_cast<uint16_t>(std::max(1.0f, std::ceil(fp.min_frontier_m / cell_m)));
  std::array<ExcludedDisc, kMaxBlacklist> discs{};
  const int radius = static_cast<int>(std::lround(fp.blacklist_radius_m / cell_m));
  std::size_t n = 0;
  for (std::size_t i = 0; i < blacklist_count_; ++i) {
    Cell c;
    if (grid_.geometry().to_cell(blacklist_[i].x, blacklist_[i].y, c)) discs[n++] = {c, radius};
  }
  finder_.find(grid_, search_, box, min_cells, {discs.data(), n}, distance_, costs.lethal, clusters_);
  return true;
}

void FrontierExplorer::plan_home() {
  outgoing_ = FrontierPlan{};
  outgoing_.stamp = stamp_;
  const planning::GridGeometry& geo = grid_.geometry();
  const Point2 home = geo.centre_of(home_cell_);
  const bool arrived = arrived_ || distance(home, {pose_.x, pose_.y}) <= params_.guidance.arrival_distance_m;
  arrived_ = false;
  if (arrived || search_.path_to(home_cell_, path_cells_) != Status::kOk) {
    // Home, or no way there on the grid: the mission takes over (its trail home, then landing).
    finished_.store(true, std::memory_order_release);
    if (arrived) level3_.homed = 1;
    publish();
    return;
  }
  outgoing_.has_goal = true;
  outgoing_.homing = true;
  outgoing_.frontier = home;
  (void)planning::simplify_path(grid_, distance_, path_cells_, outgoing_.path, coastal_units());
  publish();
}

void FrontierExplorer::publish() {
  outgoing_.seq = ++seq_;
  if (!to_level2_.push(outgoing_)) ++level3_.plans_dropped;
}

}  // namespace kestrel::exploration
