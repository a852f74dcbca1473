#include "kestrel/exploration/srt_star_planner.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::exploration {

const char* to_string(PlannerMode m) {
  switch (m) {
    case PlannerMode::kIdle: return "idle";
    case PlannerMode::kForward: return "forward";
    case PlannerMode::kBacktrack: return "backtrack";
    case PlannerMode::kFinished: return "finished";
  }
  return "unknown";
}

Status SrtStarPlanner::configure(const SrtParams& srt, const GuidanceParams& guidance) {
  Params check;
  check.srt = srt;
  check.guidance = guidance;
  if (check.validate() != Status::kOk) return Status::kInvalidArgument;
  srt_ = srt;
  guidance_ = guidance;
  reset();
  return Status::kOk;
}

void SrtStarPlanner::reset() {
  tree_.clear();
  tree_.coverage_margin_m = srt_.coverage_margin_m;
  prng_.reseed(srt_.seed);
  mode_ = PlannerMode::kIdle;
  waypoint_ = {};
  current_ = kNoNode;
  target_node_ = kNoNode;
  waypoints_issued_ = 0;
  restarts_ = 0;
  last_restart_ = RestartReason::kNone;
}

Status SrtStarPlanner::update(const Pose2& pose, const LaserScan& scan, TimeUs now, bool& new_waypoint) {
  new_waypoint = false;
  if (!pose.finite()) return Status::kInvalidArgument;
  if (scan.beam_count == 0) return Status::kInvalidArgument;
  const uint32_t issued = waypoints_issued_;

  if (mode_ == PlannerMode::kIdle) {
    if (Status st = grow(pose, scan, now); st != Status::kOk) return st;
  } else {
    const float dx = waypoint_.x - pose.x, dy = waypoint_.y - pose.y;
    const bool arrived = dx * dx + dy * dy < guidance_.arrival_distance_m * guidance_.arrival_distance_m;
    const bool late = (now - waypoint_time_).seconds() > static_cast<double>(guidance_.waypoint_time_limit_s);
    if (mode_ == PlannerMode::kFinished) {
      // Stays on the root; nothing left to explore.
    } else if (arrived && mode_ == PlannerMode::kBacktrack) {
      current_ = target_node_;
      target_node_ = kNoNode;
      choose_next(now);
    } else if (arrived) {
      if (Status st = grow(pose, scan, now); st != Status::kOk) return st;
    } else if (late) {
      restart(pose, scan, now, RestartReason::kTimeout);
    }
  }
  new_waypoint = waypoints_issued_ != issued;
  return Status::kOk;
}

Status SrtStarPlanner::grow(const Pose2& pose, const LaserScan& scan, TimeUs now) {
  if (sectors_.build(scan, srt_) != Status::kOk) return Status::kInvalidArgument;
  uint16_t id = kNoNode;
  const Status st = tree_.add_node(pose, sectors_, mode_ == PlannerMode::kIdle ? kNoNode : current_, id);
  if (st == Status::kCapacityExceeded) {
    restart(pose, scan, now, RestartReason::kTreeFull);
    return Status::kOk;
  }
  if (st != Status::kOk) return st;
  current_ = id;
  target_node_ = kNoNode;
  choose_next(now);
  return Status::kOk;
}

void SrtStarPlanner::restart(const Pose2& pose, const LaserScan& scan, TimeUs now, RestartReason why) {
  tree_.clear();
  mode_ = PlannerMode::kIdle;
  current_ = kNoNode;
  target_node_ = kNoNode;
  ++restarts_;
  last_restart_ = why;
  // The sectors were built from this scan a moment ago or are rebuilt now: either way the
  // new root is the current pose, and an empty tree always has room for it.
  (void)grow(pose, scan, now);
}

void SrtStarPlanner::choose_next(TimeUs now) {
  const SrtNode& node = tree_.nodes()[current_];
  // A sector too shallow for a step longer than the arrival distance would give a waypoint the
  // vehicle has already reached: its frontier cannot be pursued and is dropped.
  const float min_step = 2.0f * guidance_.arrival_distance_m;
  for (std::size_t live = tree_.frontier_count_of(current_); live > 0; --live) {
    const std::size_t fi = tree_.frontier_index_of(current_, prng_.below(static_cast<uint32_t>(live)));
    Frontier& f = tree_.frontier(fi);
    const float r_sector = static_cast<float>(node.radius_mm[f.sector]) * 1e-3f;
    if (r_sector - srt_.wall_clearance_m < min_step) {
      tree_.remove_frontier(fi);
      continue;
    }
    // SRT's step: a random fraction of the sector radius, kept clear of the sector's obstacle.
    const float lo = srt_.step_min_fraction * r_sector, hi = srt_.step_max_fraction * r_sector;
    float dist = lo + (hi - lo) * prng_.uniform();
    dist = std::min(dist, r_sector - srt_.wall_clearance_m);
    dist = std::max(dist, min_step);
    // Random bearing in the middle of the sector: its edges border the neighbours' obstacles.
    const float u = 0.2f + 0.6f * prng_.uniform();
    const float a = node.sector_start_rad + (static_cast<float>(f.sector) + u) * node.sector_width_rad;
    const Point2 p{node.position.x + dist * std::cos(a), node.position.y + dist * std::sin(a)};
    if (++f.attempts >= srt_.max_attempts_per_frontier) tree_.remove_frontier(fi);
    mode_ = PlannerMode::kForward;
    set_waypoint(p, now);
    return;
  }
  if (node.parent != kNoNode) {
    mode_ = PlannerMode::kBacktrack;
    target_node_ = node.parent;
    set_waypoint(tree_.nodes()[node.parent].position, now);
    return;
  }
  mode_ = PlannerMode::kFinished;
  target_node_ = kNoNode;
  set_waypoint(node.position, now);
}

void SrtStarPlanner::set_waypoint(Point2 p, TimeUs now) {
  waypoint_ = p;
  waypoint_time_ = now;
  ++waypoints_issued_;
}

}  // namespace kestrel::exploration
