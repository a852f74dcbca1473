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
// Valid()). Unguarded (SRT alone), a vehicle back up to d beside its node whose every path
// towards a frontier is blocked first closes in on the node (within d / 2, once per visit) and
// chooses again, rather than dropping the frontier. Otherwise the parent is the next waypoint
// (previousWaypoint, backtracking); if the vehicle, up to d beside the node, has no clear
// straight path to the parent, it first closes in on the node (within d / 2). Exploration is
// finished when the root owns no frontier: the
// waypoint stays on the root, so the vehicle returns to where it started.
//
// Running out is not trusted at once: a tree that runs out starts once more where the vehicle
// is (section V's restarts leave trees that know only what they saw since, and the first tree
// drops frontiers it has no path to). When that fresh tree runs out too, the vehicle first
// turns on the spot to face what its root scan's blind arc hid (kLookBack: the heading command
// is the root's heading plus pi, the waypoint holds) and grows one more tree from the scan
// taken there. Only a tree that then runs out too ends exploration; a turn not done within the
// waypoint time limit ends it as well.
//
// With srt.prefer_unvisited the frontier is drawn at random among those of the current node that
// lie where the vehicle has not flown (VisitedGrid, kept across section V's restarts), and
// among all of them only when none does; off, among all of them, as in paper 002. A forward
// waypoint the time limit gives up counts as visited, with its frontier. A steered draw
// (srt.steer: by default in trees grown after a restart) is among the frontiers whose bearing
// from the node faces the most cells never flown (UnflownBearings: within 16 m, +-35 degrees,
// inside the flown area's bounding box), counted once per choice as a work item of its own;
// after a steered waypoint the time limit gave up, the draws are unsteered until a forward
// waypoint is reached. Poses given while an arrival step is under way are not remembered as
// flown.
//
// With srt.retrace (kAlways, or kGuarded for a guarded planner: params.hpp), a tree that runs
// out on its root first looks along the path flown
// (FlownHistory, recorded from the poses given, loops kept):
// UnflownBearings counted at every kRetraceStride-th trail point, from the newest back, as work
// items of the arrival step. If the most unflown cells any trail point has in reach are at least
// kRetraceGainQuarters / 4 times those where the vehicle is and at least kRetraceMinUnflown,
// and that point lies kRetraceStepM or more away, the vehicle flies back along the trail
// (kRetrace: legs of up to kRetraceStepM that pass within kRetraceDeviationM of every trail
// point they skip, each end but the last arrived at within the distance, from kRetraceDeviationM
// to kRetraceArrivalM, that keeps the turn onto the next leg within kRetraceDeviationM of it,
// the turn measured from where the vehicle started the leg; the last end within d; a loop is
// skipped where an earlier point lies within kRetraceLoopM of the one reached, the vehicle's
// own place when the retrace begins included) and a fresh tree (steered, as any after a
// restart, even after a steering pause) grows where it ends; the trail is cut back to there (or,
// when the time limit ends the retrace, to the point last reached). Each leg's successor is
// found when the leg begins, its work counted in that update(). Else the run-out goes on as
// above; the trail is looked along at most once until a forward waypoint is reached. The trail
// is not recorded while retracing; the time limit during a retrace restarts exploration where
// the vehicle is, as for any waypoint. Paper 002 has no memory across its restarts: seed 1 of
// gt-building's URG-04LX flights restarted 11 times in the building's east half, its west rooms
// never entered (EXPERIMENTS.md).
//
// Defined behaviours: a frontier is given max_attempts_per_frontier waypoints and then dropped,
// and a frontier with no valid waypoint is dropped at once (so a frontier that cannot be seen
// past never traps the planner). With srt.rescue_frontiers, frontiers are not lost beside
// walls: a path is blocked only by the returns it comes within the clearance of, not by those
// it leaves behind (a vehicle already inside the clearance of a wall can fly away from it), and
// a mid frontier (an open sector) with no valid waypoint from its node moves to the nearest
// ancestor that scanned its direction, where backtracking comes, unless its node was itself
// grown by such a handed-up frontier (which bounds the tree). When the waypoint is not reached
// within the time limit, or the tree is full when a node must be added, the tree is erased and
// exploration restarts from the current pose with a new root.
//
// The arrival step (sectors and their erosion, the new node and its frontiers, the choice of
// the next waypoint) costs several million instructions on the Verdex, more than a guidance
// cycle's share, so it runs in slices: at most srt.arrival_work_per_cycle work units
// (work_units.hpp) per update(), and the item under way (the largest: one return's erosion over
// every ray, 2.8 k units, or one search along the retrace's trail, up to 4.3 k), on a copy of
// the arrival's pose and scan. Meanwhile busy() is true, waypoint() stays where it was (the
// waypoint just reached; the vehicle's position when exploration starts or restarts), the poses
// and scans given are not used and the time limit does not run. The result, once done, is the
// one a single call would give (tested); the new waypoint's time is that of the call that
// finishes it.
#include <array>
#include <bitset>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/core/time.hpp"
#include "kestrel/exploration/params.hpp"
#include "kestrel/core/prng.hpp"
#include "kestrel/exploration/sector_scan.hpp"
#include "kestrel/exploration/srt_star_tree.hpp"
#include "kestrel/exploration/unflown_bearings.hpp"
#include "kestrel/exploration/visited_grid.hpp"
#include "kestrel/exploration/flown_history.hpp"

namespace kestrel::exploration {

enum class PlannerMode : uint8_t {
  kIdle,       // no tree yet: the next update starts exploration
  kForward,    // heading for a new waypoint drawn in a frontier sector
  kBacktrack,  // heading back to the parent node
  kLookBack,   // turning on the spot to face the laser's blind arc before a last fresh tree
  kRetrace,    // flying back along the path flown to where a fresh tree is to grow
  kFinished,   // the root owns no frontier: waypoint is the root
};
const char* to_string(PlannerMode m);

// kExhausted: a tree ran out of frontiers, and exploration started once more from where the
// vehicle is (backtrack_or_finish says when); kRetraced: it started once more where a retrace
// along the path flown ended.
enum class RestartReason : uint8_t { kNone, kTimeout, kTreeFull, kExhausted, kRetraced };
inline constexpr std::size_t kRestartReasonCount = static_cast<std::size_t>(RestartReason::kRetraced) + 1;
const char* to_string(RestartReason r);

// Index (into tree.frontiers()) of one of `node`'s `live` frontiers, drawn at random: with a
// `visited` grid among those that lie where the vehicle has not flown, when there are any;
// else (or without a grid) among all of them. tree.frontiers().size() when `live` is 0.
std::size_t draw_frontier(const SrtStarTree& tree, uint16_t node, std::size_t live, const VisitedGrid* visited,
                          Prng& prng);

// Index of one of `node`'s frontiers drawn at random among those whose bearing from the node
// faces at least 4/5 of the most unflown cells any of them faces (`bearings`, counted from the
// node); tree.frontiers().size() when none faces any.
std::size_t draw_toward_unflown(const SrtStarTree& tree, uint16_t node, const UnflownBearings& bearings, Prng& prng);

class SrtStarPlanner {
 public:
  // kInvalidArgument for invalid parameters (the planner keeps its previous configuration).
  // `guarded`: the vehicle's commands pass the approach limiter, so a backtrack held off its
  // node may leave for the parent without the straight-path check (never for SRT alone).
  Status configure(const SrtParams& srt, const GuidanceParams& guidance, bool guarded = false);
  void reset();  // forget the tree; the PRNG restarts from the seed

  // Algorithm 1, lines 2-10, for a vehicle at `pose` (world frame) with the scan just taken
  // there, at time `now`. Returns kOk, or kInvalidArgument for a non-finite pose or a scan that
  // cannot be divided into sectors (nothing changes then). Sets `new_waypoint` when the
  // waypoint changed in this call.
  Status update(const Pose2& pose, const LaserScan& scan, TimeUs now, bool& new_waypoint);

  PlannerMode mode() const { return mode_; }
  bool finished() const { return mode_ == PlannerMode::kFinished; }
  bool has_waypoint() const { return mode_ != PlannerMode::kIdle || busy(); }
  bool busy() const { return step_ != Step::kNone; }  // an arrival step is being worked on
  uint32_t last_work() const { return last_work_; }    // work units the last update() used
  Point2 waypoint() const { return waypoint_; }
  // The heading the vehicle at `pose` should turn to: towards the waypoint, or the look-back
  // heading. False when it should keep its heading command: on top of the waypoint (atan2 says
  // nothing) and while an arrival step is worked on (the waypoint is the one just reached, a
  // few cm off in any direction: turning towards it would leave the laser facing anywhere
  // when the next waypoint comes).
  bool heading_target(const Pose2& pose, float& heading_rad) const;
  uint32_t look_backs() const { return look_backs_; }  // turns to face the blind arc
  uint16_t current_node() const { return current_; }     // node the vehicle is leaving or at
  uint16_t target_node() const { return target_node_; }  // node of a backtrack, else kNoNode
  bool aligning() const { return aligning_; }
  const SrtStarTree& tree() const { return tree_; }
  const SectorScan& last_sectors() const { return sectors_; }
  uint32_t waypoints_issued() const { return waypoints_issued_; }
  uint32_t restarts() const { return restarts_; }
  RestartReason last_restart_reason() const { return last_restart_; }
  uint32_t restarts(RestartReason why) const { return restarts_by_[static_cast<std::size_t>(why)]; }
  uint32_t blocked_arrivals() const { return blocked_arrivals_; }  // see GuidanceParams::blocked_*
  // Frontiers moved to an ancestor because their own node had no path to them.
  uint32_t frontiers_handed_up() const { return frontiers_handed_up_; }
  // Times steer_unflown was paused because a steered waypoint was not reached in time.
  uint32_t steer_pauses() const { return steer_pauses_; }
  bool steer_paused() const { return steer_paused_; }
  uint32_t steered_draws() const { return steered_draws_; }  // frontiers drawn by steering
  uint32_t retraces() const { return retraces_; }            // retraces begun (srt.retrace)
  // srt.retrace holds for this planner: kAlways, or kGuarded and the planner is guarded.
  bool retraces_enabled() const {
    return srt_.retrace == RetraceMode::kAlways || (srt_.retrace == RetraceMode::kGuarded && guarded_);
  }
  // How near the retrace's waypoint counts as reached; 0 for the last, reached within d.
  float retrace_arrival_m() const { return retrace_arrival_m_; }
  const FlownHistory& trail() const { return trail_; }

  static constexpr std::size_t kRetraceStride = 4;       // trail points between two counts
  static constexpr uint32_t kRetraceGainQuarters = 5;    // the best point against where it is
  static constexpr uint32_t kRetraceMinUnflown = 64;     // weighted cells (unflown_bearings.hpp)
  static constexpr uint32_t kRetraceMinFrontier = 16;    // ... of the frontier (retrace_target)
  static constexpr float kRetraceStepM = 2.0f;
  static constexpr float kRetraceArrivalM = 0.8f;  // at most; less before a turn (no corner cut)
  // An earlier point this near is the same place: under FlownHistory's spacing, so that the
  // point before on the same path is not taken for one.
  static constexpr float kRetraceLoopM = 0.4f;
  static constexpr float kRetraceDeviationM = 0.15f;  // a leg passes this near every point it skips
  TimeUs waypoint_time() const { return waypoint_time_; }
  const VisitedGrid& visited() const { return visited_; }  // where the vehicle has flown

 private:
  // kRetraceBegin: the first leg back is found, the leg after it (for the turn) is the item.
  enum class Step : uint8_t { kNone, kSectors, kTree, kPick, kDraw, kPath, kTrailScan, kRetraceBegin };
  // Starts the arrival step's slices on a copy of (pose, scan).
  Status start_grow(const Pose2& pose, const LaserScan& scan);
  void start_choose(const Pose2& pose, const LaserScan& scan);
  bool steers_this_draw() const;  // srt.steer's choice, and not paused
  void restart_tree(RestartReason why);
  // Runs slices of the arrival step until it is done or the cycle's budget is used.
  void work_on_arrival(TimeUs now);
  uint32_t begin_node();
  uint32_t pick_frontier(TimeUs now);
  uint32_t draw_candidate(TimeUs now);
  // The frontier's candidate paths were blocked from where the vehicle is, beside its node
  // after a backtrack: closes in on the node to choose again from there. False when the vehicle
  // is guarded (the blend), already near the node, or has closed in on it once this visit.
  bool close_in_to_choose(TimeUs now);
  // The arrival pose is more than d / 2 from `node`: worth closing in on before leaving it.
  bool off_node(Point2 node) const;
  // Frontier i has no path from its node: it moves to the nearest ancestor that can take it,
  // or is dropped. Returns the work units spent.
  uint32_t hand_up_or_drop(std::size_t i);
  uint32_t backtrack_or_finish(TimeUs now);
  // The root ran out: starts once more, looks back, or finishes (after any retrace).
  uint32_t run_out_on_root(TimeUs now);
  // srt.retrace: counts the next trail point; when the trail is done, retraces or runs out.
  uint32_t scan_trail(TimeUs now);
  // The earliest visit, from trail_best_ on, of where trail point `last` is (last if none is
  // within kRetraceLoopM); adds its work units to `work`.
  std::size_t earliest_visit(std::size_t last, uint32_t& work) const;
  // The end of the next leg back from trail point `from`, for a vehicle at `at` (on or near
  // it): the point before, or further back up to kRetraceStepM while every point the leg skips
  // lies within kRetraceDeviationM of it (no corner cut). Adds its work units to `work`.
  std::size_t next_leg(std::size_t from, Point2 at, uint32_t& work) const;
  // Flying back along the trail, the vehicle at `pose`: the leg after, or the fresh tree.
  // Returns the work units spent.
  uint32_t advance_retrace(const Pose2& pose, const LaserScan& scan, TimeUs now, Status& status);
  // The waypoint is trail point trail_next_, the leg to it starting where the vehicle is,
  // `leg_start`. Finds the leg after it (retrace_after_reached_, retrace_after_next_) and from
  // the turn onto it how early
  // the waypoint counts as arrived at (retrace_arrival_m_). Returns the work units spent.
  uint32_t set_retrace_waypoint(Point2 leg_start, TimeUs now);
  // The straight path from the arrival pose to `p` against the returns of the arrival scan.
  uint32_t start_path(Point2 p, bool backtrack);
  uint32_t check_path(uint32_t budget, TimeUs now);
  void set_waypoint(Point2 p, TimeUs now);
  // Whether the segment a-b enters a keep-out box grown by the clearance (SrtParams::keep_out),
  // a strip lengthened by `along` >= 0 on its long side: keep_out_drift_margin_m for what is
  // seen through it (frontiers, kept or handed up). Paths and waypoints keep the box as given:
  // a frontier seen beside the box is dropped before it can draw a waypoint there, which was
  // enough (EXPERIMENTS.md). The grid frontier explorer has no such step, so its paths take
  // the lengthened box.
  bool crosses_keep_out(Point2 a, Point2 b, float along = 0.0f) const;
  // steer_unflown: widens the flown grid's extent to the arrival scan's returns.
  uint32_t widen_extent_to_returns();
  // The retrace counts the coarse grid's frontier: the scans given mark its laser layers.
  bool marks_seen() const { return retraces_enabled() && srt_.retrace_target == RetraceTarget::kFrontier; }
  // Marks a slice of the scan's beams (the next in turn) on the visited grid's laser layers.
  // Returns the work units it cost.
  uint32_t mark_seen(const Pose2& pose, const LaserScan& scan);
  // Drops the current node's frontiers whose sight line from the node crosses a keep-out box.
  uint32_t drop_frontiers_seen_through_keep_outs();

  SrtParams srt_{};
  GuidanceParams guidance_{};
  SrtStarTree tree_;
  SectorScan sectors_;
  VisitedGrid visited_;  // cleared by reset(), not by section V's restarts
  UnflownBearings bearings_;     // steer_unflown: counted once per choice, from its node
  bool bearings_counted_ = false;
  bool drawn_steered_ = false;    // the frontier being tried was drawn by steering
  bool pursued_steered_ = false;  // ... and the one the forward waypoint serves
  bool steer_paused_ = false;     // a steered waypoint timed out: unsteered until one is reached
  uint32_t steer_pauses_ = 0;
  uint32_t steered_draws_ = 0;
  Prng prng_{1};
  PlannerMode mode_ = PlannerMode::kIdle;
  Point2 waypoint_{};
  uint16_t current_ = kNoNode;
  uint16_t target_node_ = kNoNode;
  bool aligning_ = false;  // backtracking: closing in on the node before leaving for its parent
  bool straight_to_parent_ = false;  // the closing in was held off: leave for the parent as is
  bool path_blocked_ = false;        // a candidate path of the frontier being tried was blocked
  uint16_t closed_in_on_ = kNoNode;  // closed in on this node to choose again (once per visit)
  bool pursuing_handed_up_ = false;          // the forward waypoint serves a handed-up frontier
  std::bitset<kMaxNodes> grown_by_handed_up_;  // nodes reached so: their frontiers stay theirs
  bool guarded_ = false;
  TimeUs waypoint_time_{};
  float closest_m_ = 0;  // nearest the vehicle has come to the waypoint, and when
  TimeUs closest_at_{};
  uint32_t blocked_arrivals_ = 0;
  uint32_t frontiers_handed_up_ = 0;
  uint32_t waypoints_issued_ = 0;
  uint32_t restarts_ = 0;
  std::array<uint32_t, kRestartReasonCount> restarts_by_{};  // kNone's entry stays 0
  RestartReason last_restart_ = RestartReason::kNone;
  bool looked_back_ = false;  // since the last kTimeout or kTreeFull restart (or the start)
  float look_heading_ = 0;    // kLookBack: the heading to turn to
  uint32_t look_backs_ = 0;
  FlownHistory trail_;  // srt.retrace: the path flown, in order
  bool trail_scanned_ = false;  // since the last forward arrival: a run-out looks only once
  std::size_t trail_next_ = 0;  // the trail scan's next point (counting down), or the
                                // retrace's current trail point
  std::size_t trail_best_ = 0;  // the trail point with the most unflown cells in reach
  std::size_t trail_reached_ = 0;  // retracing: the earliest visit of the point last reached
  float retrace_arrival_m_ = 0;    // retracing: the waypoint counts as reached this near (0: d)
  // Retracing: the leg after the current one, found when the current one began (the trail
  // does not change meanwhile): the earliest visit of the current end, and the next end.
  std::size_t retrace_after_reached_ = 0, retrace_after_next_ = 0;
  uint32_t unflown_best_ = 0, unflown_here_ = 0;
  uint16_t seen_phase_ = 0;  // mark_seen: the slice of beams marked next
  uint32_t retraces_ = 0;

  // The arrival step in progress.
  Step step_ = Step::kNone;
  Pose2 job_pose_{};
  LaserScan job_scan_{};
  bool job_from_idle_ = false;  // a root is grown (start or restart), not a child
  uint32_t last_work_ = 0;
  std::size_t live_ = 0;        // frontiers of the current node not yet tried in this choice
  std::size_t frontier_ = 0;    // index of the frontier being tried
  Point2 pursued_{};            // the frontier the forward waypoint was drawn towards
  std::array<uint16_t, 2 * SectorScan::kRaysPerSector> candidates_{};  // sector * kRays + ray
  uint16_t candidate_count_ = 0;
  struct PathCheck {
    Point2 target{};      // world frame
    float bx = 0, by = 0;  // target in the frame of the scan's clockwise edge
    float len2 = 0, reach = 0;
    std::size_t next_beam = 0;
    bool blocked = false;
    bool backtrack = false;  // a check of the way to the parent, not of a new waypoint
  } path_;
  float edge_cos_ = 1, edge_sin_ = 0;  // of the arrival scan's clockwise edge, world frame
};

}  // namespace kestrel::exploration
