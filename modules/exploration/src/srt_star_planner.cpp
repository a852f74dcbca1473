#include "kestrel/exploration/srt_star_planner.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace kestrel::exploration {

const char* to_string(PlannerMode m) {
  switch (m) {
    case PlannerMode::kIdle:
      return "idle";
    case PlannerMode::kForward:
      return "forward";
    case PlannerMode::kBacktrack:
      return "backtrack";
    case PlannerMode::kFinished:
      return "finished";
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
  aligning_ = false;
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
    const float radius = aligning_ ? 0.5f * guidance_.arrival_distance_m : guidance_.arrival_distance_m;
    const bool arrived = dx * dx + dy * dy < radius * radius;
    const bool late = (now - waypoint_time_).seconds() > static_cast<double>(guidance_.waypoint_time_limit_s);
    if (mode_ == PlannerMode::kFinished) {
      // Stays on the root; nothing left to explore.
    } else if (arrived && mode_ == PlannerMode::kBacktrack) {
      aligning_ = false;
      current_ = target_node_;
      target_node_ = kNoNode;
      choose_next(pose, scan, now);
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
  choose_next(pose, scan, now);
  return Status::kOk;
}

void SrtStarPlanner::restart(const Pose2& pose, const LaserScan& scan, TimeUs now, RestartReason why) {
  tree_.clear();
  aligning_ = false;
  mode_ = PlannerMode::kIdle;
  current_ = kNoNode;
  target_node_ = kNoNode;
  ++restarts_;
  last_restart_ = why;
  // The sectors were built from this scan a moment ago or are rebuilt now: either way the
  // new root is the current pose, and an empty tree always has room for it.
  (void)grow(pose, scan, now);
}

bool SrtStarPlanner::path_clear(const Pose2& pose, const LaserScan& scan, Point2 p) const {
  const float c = std::cos(pose.theta), s = std::sin(pose.theta);
  const float wx = p.x - pose.x, wy = p.y - pose.y;
  const float bx = c * wx + s * wy, by = -s * wx + c * wy;  // the waypoint in the scan's frame
  const float len2 = bx * bx + by * by;
  const float rho = srt_.clearance_m;
  const float reach = std::sqrt(len2) + rho;
  for (std::size_t i = 0; i < scan.beam_count; ++i) {
    const uint16_t r_mm = scan.range_mm[i];
    if (r_mm < kMinValidRangeMm) continue;
    const float r = static_cast<float>(r_mm) * 1e-3f;
    if (r >= reach) continue;  // too far to come within rho of the segment
    const float a = scan.angle_of(i);
    const float qx = r * std::cos(a), qy = r * std::sin(a);
    const float u = len2 > 0.0f ? std::clamp((qx * bx + qy * by) / len2, 0.0f, 1.0f) : 0.0f;
    const float dx = qx - u * bx, dy = qy - u * by;
    if (dx * dx + dy * dy < rho * rho) return false;
  }
  return true;
}

void SrtStarPlanner::choose_next(const Pose2& pose, const LaserScan& scan, TimeUs now) {
  const SrtNode& node = tree_.nodes()[current_];
  // A waypoint must be at least min_step away along a ray with room for the vehicle. The rays
  // of the frontier's own sector come first, then those of the sectors 1, 2, ... up to
  // ray_search_sectors to either side: beside a door jamb the frontier's own bearing can be
  // blocked while a nearby one leads through. A frontier with no such ray cannot be pursued
  // from here and is dropped.
  const float min_step = 2.0f * guidance_.arrival_distance_m;
  const uint16_t min_step_mm = static_cast<uint16_t>(std::lround(min_step * 1000.0f));
  constexpr uint16_t kRays = SectorScan::kRaysPerSector;
  for (std::size_t live = tree_.frontier_count_of(current_); live > 0; --live) {
    const std::size_t fi = tree_.frontier_index_of(current_, prng_.below(static_cast<uint32_t>(live)));
    Frontier& f = tree_.frontier(fi);
    std::array<uint16_t, 2 * kRays> candidates{};  // sector * kRays + ray
    uint16_t n = 0;
    for (int dist = 0; dist <= srt_.ray_search_sectors && n == 0; ++dist) {
      for (int side = -1; side <= 1; side += 2) {
        if (dist == 0 && side > 0) continue;
        const int sector = static_cast<int>(f.sector) + side * dist;
        if (sector < 0 || sector >= node.sector_count) continue;
        for (uint16_t j = 0; j < kRays; ++j) {
          const uint16_t q = static_cast<uint16_t>(sector * kRays + j);
          if (node.clear_mm[q] >= min_step_mm) candidates[n++] = q;
        }
      }
    }
    // SRT's random direction and step, validated (Freda and Oriolo's Valid()): the vehicle
    // is up to d away from the node after a backtrack, so the straight path from where it is
    // must keep the clearance from the returns of the scan it has just taken.
    bool found = false;
    Point2 p{};
    while (n > 0 && !found) {
      const uint16_t k = static_cast<uint16_t>(prng_.below(n));
      const uint16_t q = candidates[k];
      candidates[k] = candidates[--n];
      const uint16_t sector = q / kRays, ray = q % kRays;
      // A random fraction of the sector's radius, within the ray's clear distance.
      const float r_clear = static_cast<float>(node.clear_mm[q]) * 1e-3f;
      const float r_sector = static_cast<float>(node.radius_mm[sector]) * 1e-3f;
      const float lo = srt_.step_min_fraction * r_sector, hi = srt_.step_max_fraction * r_sector;
      const float dist = std::clamp(lo + (hi - lo) * prng_.uniform(), min_step, r_clear);
      const float a = node.ray_angle(sector, ray);
      p = {node.position.x + dist * std::cos(a), node.position.y + dist * std::sin(a)};
      found = path_clear(pose, scan, p);
    }
    if (!found) {
      tree_.remove_frontier(fi);
      continue;
    }
    if (++f.attempts >= srt_.max_attempts_per_frontier) tree_.remove_frontier(fi);
    mode_ = PlannerMode::kForward;
    set_waypoint(p, now);
    return;
  }
  if (node.parent != kNoNode) {
    mode_ = PlannerMode::kBacktrack;
    // The tree edge is safe, but the vehicle may be up to d beside the node: if the straight
    // path from where it is to the parent is not clear, it first closes in on the node.
    const float ox = node.position.x - pose.x, oy = node.position.y - pose.y;
    const float half_d = 0.5f * guidance_.arrival_distance_m;
    const Point2 parent = tree_.nodes()[node.parent].position;
    if (ox * ox + oy * oy > half_d * half_d && !path_clear(pose, scan, parent)) {
      aligning_ = true;
      target_node_ = current_;
      set_waypoint(node.position, now);
      return;
    }
    target_node_ = node.parent;
    set_waypoint(parent, now);
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
