#pragma once
// SRT-Star waypoint sequencing: lines 2-10 of paper 002's Algorithm 1, plus the waypoint-to-
// waypoint time limit of section V.
//
// On arrival within d of the commanded waypoint (or at the start): if the vehicle came forward,
// the scan is divided into sectors and stored as a new node, child of the node it left
// (updateSRT); if it came back by backtracking, the node it returned to becomes current. Then,
// if the current node still owns a frontier, a new waypoint is drawn at random (seeded PRNG)
// in the sector of one of its frontiers (newWaypoint): a random ray of the sector (or, when
// all of the sector's rays are blocked for the vehicle, of a sector up to ray_search_sectors
// away) at a random fraction of the sector radius within the ray's clear distance, and only if
// the straight path from the vehicle keeps the clearance from the scan just taken (SRT's
// Valid()). Otherwise the parent is the next waypoint (previousWaypoint, backtracking); if the
// vehicle, up to d beside the node, has no clear straight path to the parent, it first closes
// in on the node (within d / 2). Exploration is finished when the root owns no frontier: the
// waypoint stays on the root, so the vehicle returns to where it started.
//
// Defined behaviours: a frontier is given max_attempts_per_frontier waypoints and then dropped,
// and a frontier with no valid waypoint is dropped at once (so a frontier that cannot be seen
// past never traps the planner); when the waypoint is not reached within the time limit, or
// the tree is full when a node must be added, the tree is erased and exploration restarts from
// the current pose with a new root.
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/core/time.hpp"
#include "kestrel/exploration/params.hpp"
#include "kestrel/exploration/prng.hpp"
#include "kestrel/exploration/sector_scan.hpp"
#include "kestrel/exploration/srt_star_tree.hpp"

namespace kestrel::exploration {

enum class PlannerMode : uint8_t {
  kIdle,       // no tree yet: the next update starts exploration
  kForward,    // heading for a new waypoint drawn in a frontier sector
  kBacktrack,  // heading back to the parent node
  kFinished,   // the root owns no frontier: waypoint is the root
};
const char* to_string(PlannerMode m);

enum class RestartReason : uint8_t { kNone, kTimeout, kTreeFull };

class SrtStarPlanner {
 public:
  // kInvalidArgument for invalid parameters (the planner keeps its previous configuration).
  Status configure(const SrtParams& srt, const GuidanceParams& guidance);
  void reset();  // forget the tree; the PRNG restarts from the seed

  // Algorithm 1, lines 2-10, for a vehicle at `pose` (world frame) with the scan just taken
  // there, at time `now`. Returns kOk, or kInvalidArgument for a non-finite pose or a scan that
  // cannot be divided into sectors (nothing changes then). Sets `new_waypoint` when the
  // waypoint changed in this call.
  Status update(const Pose2& pose, const LaserScan& scan, TimeUs now, bool& new_waypoint);

  PlannerMode mode() const { return mode_; }
  bool finished() const { return mode_ == PlannerMode::kFinished; }
  bool has_waypoint() const { return mode_ != PlannerMode::kIdle; }
  Point2 waypoint() const { return waypoint_; }
  uint16_t current_node() const { return current_; }     // node the vehicle is leaving or at
  uint16_t target_node() const { return target_node_; }  // node of a backtrack, else kNoNode
  bool aligning() const { return aligning_; }
  const SrtStarTree& tree() const { return tree_; }
  const SectorScan& last_sectors() const { return sectors_; }
  uint32_t waypoints_issued() const { return waypoints_issued_; }
  uint32_t restarts() const { return restarts_; }
  RestartReason last_restart_reason() const { return last_restart_; }
  TimeUs waypoint_time() const { return waypoint_time_; }

 private:
  void restart(const Pose2& pose, const LaserScan& scan, TimeUs now, RestartReason why);
  Status grow(const Pose2& pose, const LaserScan& scan, TimeUs now);
  void choose_next(const Pose2& pose, const LaserScan& scan, TimeUs now);
  // Whether the straight path from pose to p keeps the clearance from every return of scan.
  bool path_clear(const Pose2& pose, const LaserScan& scan, Point2 p) const;
  void set_waypoint(Point2 p, TimeUs now);

  SrtParams srt_{};
  GuidanceParams guidance_{};
  SrtStarTree tree_;
  SectorScan sectors_;
  Prng prng_{1};
  PlannerMode mode_ = PlannerMode::kIdle;
  Point2 waypoint_{};
  uint16_t current_ = kNoNode;
  uint16_t target_node_ = kNoNode;
  bool aligning_ = false;  // backtracking: closing in on the node before leaving for its parent
  TimeUs waypoint_time_{};
  uint32_t waypoints_issued_ = 0;
  uint32_t restarts_ = 0;
  RestartReason last_restart_ = RestartReason::kNone;
};

}  // namespace kestrel::exploration
