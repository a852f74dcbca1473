#pragma once
// Parameters of the compact exploration strategy of paper 002 (Pravitra, Chowdhary, Johnson):
// the wall-following velocity field (section III), the SRT-Star frontier planner (section IV,
// after Freda and Oriolo) and the blending and practical limits (Algorithm 1, section V).
// One struct, defaults and units inline; capacities are compile-time constants.
#include <array>
#include <cstddef>
#include <cstdint>

#include "kestrel/core/keep_out.hpp"
#include "kestrel/core/status.hpp"

namespace kestrel::exploration {

inline constexpr std::size_t kMaxSectors = 64;                      // sectors per scan (SRT-Star LSR)
inline constexpr std::size_t kMaxNodes = 256;                       // SRT nodes (waypoints reached)
inline constexpr std::size_t kMaxFrontiers = 512;                   // live frontier points of the whole tree
inline constexpr std::size_t kMaxLocalFrontiers = 3 * kMaxSectors;  // per scan: mid, left, right
// Operator keep-out boxes (core/keep_out.hpp): SRT-Star sends the vehicle into or through none,
// grown by its clearance; the flight home's shortcut keeps out of them too (the composition
// hands the mission the same boxes).
using kestrel::KeepOut;
using kestrel::kMaxKeepOuts;

// How equation 3's sum over the n in-range beams is scaled. The paper sums plainly, so its
// K_wf is a gain per beam and the field grows with the laser's resolution; kPerRadian weights
// every beam by the angle it covers (the sum becomes an integral over the scan), so one gain
// serves the URG-04LX and the UTM-30LX alike.
enum class FieldNormalisation : uint8_t {
  kPerRadian,       // v = K * sum(...) * |angle step|: gain in 1/(s rad), laser-independent
  kPaperSum,        // v = K * sum(...): paper 002 equation 3 literally, gain per beam
  kPerInRangeBeam,  // v = K * sum(...) / n: mean over in-range beams
};

struct WallFollowParams {
  float target_range_m = 1.0f;  // r_t: distance from the walls the vehicle tries to keep
  float safe_range_m = 0.65f;   // r_safe: beams closer than this use K_safe (must be < r_t);
                                // 0.5 m let the 0.27 m vehicle clip door jambs in closed loop
  float gain_wf = 0.1f;         // K_wf, 1/s (per radian of scan under kPerRadian)
  float gain_safe = 10.0f;      // K_safe, 1/s: "orders of magnitude" above K_wf, beats K_fr
                                // even when only a door jamb's few beams are inside r_safe
  float max_range_m = 4.0f;     // beams beyond this are not "in range" (URG-04LX reach), so a
                                // 30 m laser does not make far walls dominate the field
  FieldNormalisation normalisation = FieldNormalisation::kPerRadian;
};

// Which of SRT-Star's draws steer towards the building not yet flown (UnflownBearings; not in
// paper 002, which draws among the node's frontiers alike). Section V's restarts erase the
// tree, and a fresh tree knows only what it sees from then on: it is the fresh trees that fly
// back over rooms already explored, so by default only they are steered. Steered at every
// node, trees in iarc-arena's 15 m rooms kept sweeping the room they were in (its unflown
// cells are the nearest); the first tree has its own frontiers to remember the building by.
enum class SteerUnflown : uint8_t {
  kNever,         // paper 002: every draw alike among the node's frontiers
  kAfterRestart,  // every draw of a tree grown after a restart (of any reason)
  kEveryNode,     // every draw
  kFromRootOnly,  // the draws a tree makes while it is its root alone: where each tree goes first
};
inline constexpr SteerUnflown kSteerUnflownModes[] = {SteerUnflown::kNever, SteerUnflown::kAfterRestart,
                                                      SteerUnflown::kEveryNode, SteerUnflown::kFromRootOnly};
// "off", "restarted", "every", "root" (kestrel-sim's srt_steer=...).
const char* to_string(SteerUnflown s);
// kInvalidArgument for any other name, or nullptr.
Result<SteerUnflown> parse_steer_unflown(const char* name);

// When a tree that runs out on its root first flies back along the path flown to where more is
// unflown (srt_star_planner.hpp, srt.retrace; not in paper 002). The way back replays the path
// flown, which is only as far from the walls as the flight out was: SRT alone, whose position
// set-points nothing guards, flies the kinematic building's 1.2 m gap 0.2 m from its jamb, and
// with the retrace on it grazed a wall on 4 of 10 flights (0.12-0.19 m from the vehicle's
// centre, its radius 0.2 m; without, none comes nearer than 0.21 m), so kGuarded retraces only
// a planner whose explorer's commands pass the approach limiter (the blend).
enum class RetraceMode : uint8_t {
  kOff,
  kGuarded,
  kAlways,
};
inline constexpr RetraceMode kRetraceModes[] = {RetraceMode::kOff, RetraceMode::kGuarded, RetraceMode::kAlways};
// "off", "guarded", "on" (kestrel-sim's srt_retrace=...).
const char* to_string(RetraceMode m);
// kInvalidArgument for any other name, or nullptr.
Result<RetraceMode> parse_retrace_mode(const char* name);

// What the retrace counts in reach of a point of the path flown (unflown_bearings.hpp). Cells
// never flown are there wherever the vehicle has not been, behind walls and outside an L of the
// building included, so a retrace counting them almost never lets exploration end before the
// time limit (7 of 150 URG-04LX flights in gt-building; EXPERIMENTS.md). The frontier of what
// the nodes' scans showed (a cell never seen, beside one seen free, not a wall) is empty where
// the building is done, so a flight ends when no point of its path has any left.
enum class RetraceTarget : uint8_t {
  kUnflown,   // cells never flown, inside the flown area's bounding box
  kFrontier,  // the coarse grid's frontier of the nodes' scans (visited_grid.hpp)
};
inline constexpr RetraceTarget kRetraceTargets[] = {RetraceTarget::kUnflown, RetraceTarget::kFrontier};
// "unflown", "frontier" (kestrel-sim's srt_retrace_target=...).
const char* to_string(RetraceTarget t);
// kInvalidArgument for any other name, or nullptr.
Result<RetraceTarget> parse_retrace_target(const char* name);

struct SrtParams {
  uint16_t sector_count = 32;             // sectors the scan is divided into (<= kMaxSectors)
  float perception_range_m = 3.5f;        // R_p: a sector with no return closer is obstacle-free
  float discontinuity_m = 1.0f;           // radius jump between adjacent sectors that is a frontier
  bool discontinuity_needs_beam_jump = true;  // ... when one of the two sectors also holds a
                                              // jump that large between consecutive beams: not
                                              // a wall seen aslant (sector_scan.hpp; not in
                                              // paper 002, whose sectors' radii alone decide)
  float step_min_fraction = 0.5f;         // new waypoint between these fractions of the sector
  float step_max_fraction = 0.9f;         //   radius (SRT's alpha), ...
  float clearance_m = 0.4f;               // ... inside the sector's clear radius: a disc of this
                                          // radius moved along any bearing of the sector up to
                                          // there touches no return (vehicle radius + margin)
  uint8_t ray_search_sectors = 3;         // a frontier's waypoint may use rays this many sectors off
                                          // (6 let more kinematic flights through doors, 6 -> 9 of
                                          // 10, but in kestrel-sim twice as many gt-building flights
                                          // collided: the extra, oblique waypoints pass door jambs
                                          // closely while the estimate drifts)
  float coverage_margin_m = 0.05f;        // a frontier this deep inside another safe region is gone
  uint8_t max_attempts_per_frontier = 2;  // waypoints drawn for one frontier before it is dropped
  bool prefer_unvisited = false;          // draw first among the frontiers where the vehicle has
                                          // not flown (visited_grid.hpp; not in paper 002)
  bool rescue_frontiers = false;          // keep frontiers lost beside walls: a path may leave a
                                          // return it starts within the clearance of, and an open
                                          // sector's frontier with no path from its node goes to
                                          // an ancestor (srt_star_planner.hpp; not in paper 002)
  RetraceMode retrace = RetraceMode::kGuarded;  // a tree that runs out with little unflown in
                                                // reach first flies back along the path it came
                                                // by to where more is (srt_star_planner.hpp; not
                                                // in paper 002). Guarded since session 41: the
                                                // URG-04LX's gt-building flights through every
                                                // room without a contact 125 of 150 against 107
                                                // (EXPERIMENTS.md, *Retracing the path flown*)
  RetraceTarget retrace_target = RetraceTarget::kUnflown;  // what draws it back (and, when
                                                           // none is left, ends exploration)
  SteerUnflown steer = SteerUnflown::kAfterRestart;  // which draws face the building not yet
                                                    // flown (unflown_bearings.hpp; not in
                                                    // paper 002, whose draws kNever makes)
  uint32_t seed = 1;                      // PRNG seed: runs are deterministic per seed
  uint32_t arrival_work_per_cycle = 15000;  // work units (about 100 Verdex instructions each,
                                            // work_units.hpp) of the arrival step per guidance
                                            // cycle: 1.5 M of the guidance share's 2 M cycles;
                                            // 0 does the whole step in the arriving cycle
  std::array<KeepOut, kMaxKeepOuts> keep_out{};  // the first keep_out_count are used:
  uint8_t keep_out_count = 0;                    // waypoints and their straight paths stay out
                                                 // of them, frontiers seen through them are
                                                 // dropped
  // How far the estimate that places the boxes may have drifted along a window's wall: a strip
  // box (KeepOut::lengthened) is taken that much longer for what is seen through it (SRT-Star
  // drops such frontiers) and, by the grid frontier explorer, as an obstacle to its paths: the
  // map, and the window's gap in it, lie in the estimate's frame, the box where the operator
  // put it. The price: an opening in the same wall within this plus the clearance of the box's
  // ends is not seen through (SRT-Star) or flown through (grid frontiers) either. 2 m:
  // iarc-arena's URG-04LX flights over 30 minutes touching nothing, blend 9 -> 31 of 60 with
  // every room kept, grid frontiers 26 -> 49 of 60; 3 m closed room C's door, 4 m along
  // (EXPERIMENTS.md; in neither paper).
  float keep_out_drift_margin_m = 2.0f;
};

struct GuidanceParams {
  float arrival_distance_m = 0.3f;      // d of Algorithm 1
  float gain_fr = 0.5f;                 // K_fr, 1/s (equation 5)
  float speed_limit_mps = 0.5f;         // section V
  float yaw_rate_limit_radps = 0.5f;    // section V, on the heading command
  float waypoint_time_limit_s = 30.0f;  // section V: exceeded -> erase the SRT and restart
  float blocked_arrival_distance_m = 0.8f;  // within this of the waypoint and no nearer for
  float blocked_time_s = 5.0f;              // this long: arrived as closely as the walls allow
                                            // (a waypoint the estimate's shift put against a
                                            // wall; approach stop distance 0.4 m + d + margin)
  float altitude_m = 1.0f;              // constant altitude command (section II)
  float cruise_speed_mps = 0.3f;        // wall-following baseline only: speed along the wall
  float wall_hold_gain = 0.5f;          // wall-following baseline only, 1/s: pulls the nearest
                                        // return to r_t (the field alone centres in a room)
};

// Facing across an axis the scan matcher reports it cannot measure (look_across.hpp): every
// explorer's heading; not in the papers.
struct LookAcrossParams {
  float after_s = 0.0f;    // degenerate this long before turning across (0 = off)
  float release_s = 2.0f;  // and back towards the target once the match has been clear this long
  // kInvalidArgument unless both are finite and within [0, 600] s.
  Status validate() const;
};

// The approach limiter (approach_limiter.hpp): the velocity-commanding explorers (blend,
// wallfollow) and the flight home (Explorer::bound_velocity) never close on a laser return
// faster than gain * (range - stop_distance_m). Not part of paper 002, whose blend keeps off
// walls only on balance; off reproduces the paper (and leaves the flight home unbounded).
struct ApproachParams {
  bool enabled = true;
  float stop_distance_m = 0.4f;  // vehicle radius 0.27 m + 0.13 m for the controller's lag; at
                                 // most the SRT clearance (checked), so every waypoint stays
                                 // reachable; 0.95 m gaps
                                 // (gt-building's inner room) leave 7.5 cm either side
  float gain = 1.0f;             // 1/s: 0.5 m/s is allowed from 0.9 m, 0.25 m/s at r_safe
  float blind_speed_mps = 0.1f;  // closing speed allowed towards any direction the laser does not
                                 // see (the arc behind it): a creep while the heading turns

  // kInvalidArgument unless 0 < stop_distance_m <= 2, 0 < gain <= 10 and
  // 0 <= blind_speed_mps <= 10 (finite).
  Status validate() const;
};

// The grid frontier explorer (frontier_explorer.hpp; paper 003 section 3.2, after Yamauchi): an
// occupancy grid drawn from the laser at level 3, the nearest accessible frontier by path
// cost, a Dijkstra path to it, flown as the blend flies its waypoints.
struct FrontierParams {
  float cell_m = 0.12f;          // grid cell: 512 of them span 61 m around home
  float reach_m = 4.0f;          // rays draw up to here: the URG-04LX's reach, so that with the
                                 // UTM-30LX too a room counts as explored once flown into
  float lethal_m = 0.40f;        // the planner enters no cell nearer an obstacle: at least the
                                 // approach limiter's stop distance (checked by the explorer's
                                 // configure), which would hold
                                 // the vehicle off a narrower gap (gt-building's 0.95 m gap
                                 // keeps a cell or two)
  float relaxed_lethal_m = 0.35f;  // with no frontier accessible, the search is run again with
                                   // this: walls drawn twice a few decimetres apart (the
                                   // estimate had drifted) narrow a door on the grid that is
                                   // wide enough in truth; the limiter and the field fly the
                                   // real one (0: no second search). Above the vehicle's 0.27 m
                                   // and a wall's 0.05 m half thickness: a cell's centre may
                                   // lie 6 cm from the wall it holds, and a jamb seen edge-on
                                   // is not in the scan the limiter works on
  float soft_m = 0.90f;          // between lethal_m and this a step costs more, up to
  uint8_t soft_penalty = 30;     //   this much at lethal_m (a straight step costs 10): paths
                                 //   keep to the middle of doors
  float coastal_fraction = 0.6f;  // coastal navigation: paths keep within this fraction of the
  uint8_t coastal_penalty = 10;   //   laser's range of a wall, a step farther costing this much
                                  //   more (10: double); a laser whose range is beyond what
                                  //   the obstacle distance holds (85 cells) has none
  float min_frontier_m = 0.5f;   // narrower frontiers are ignored (paper 003: "wide enough to
                                 // accommodate the exploring UAS")
  float goal_inset_m = 0.3f;     // the flight ends this far short of the frontier, in known free
                                 // space (paper 003: "a predefined distance apart")
  float lookahead_m = 1.0f;      // the carrot along the path: K_fr * 1 m is the speed limit
  float field_weight = 1.0f;     // the wall-following field's share of the command (0: none)
  float draw_period_s = 0.1f;    // scans drawn at most this often (the UTM-30LX's 40 Hz: 1 in 4)
  float replan_period_s = 1.0f;  // planned at least this often, and on arrival (a plan older
                                 // than 5 s is not flown: level 3 has stalled)
  float progress_m = 0.5f;       // a goal whose path has not shortened by this within
  float patience_s = 15.0f;      //   this long is blacklisted (paper 003), and so is one
  float goal_time_limit_s = 60.0f;  // not reached within this
  float blacklist_radius_m = 0.6f;  // frontier cells this close to a blacklisted goal are no
                                    // longer frontier cells
  float goal_match_m = 1.5f;     // a frontier whose nearest cell is this close to the goal's is
                                 // the same goal (its nearest cell moves as the vehicle does)
  float look_distance_m = 1.5f;  // a goal looked at from within this (in the laser's fan) for
  uint16_t looks_to_give_up = 20;  //   this many scans drawn and still a frontier is given up:
                                   //   what lies behind it cannot be seen from here (a wall seen
                                   //   edge-on, whose line the rays pass along)
  float stuck_radius_m = 1.0f;   // paper 004's stuck detection: a vehicle that has not left a
  float stuck_time_s = 20.0f;    //   disc of this radius for this long gives its goal up
                                 //   (whatever the goal: two frontiers that flicker in and out
                                 //   of the grid take turns and restart every goal's timers)
  float switch_margin_m = 1.0f;  // a frontier replaces the current goal only if this much nearer
  uint8_t empty_plans_to_finish = 3;  // plans in a row with no accessible frontier: explored,
  uint8_t max_grid_restarts = 2;      // unless inaccessible ones are left: then the grid is
                                      // forgotten and drawn again from where the vehicle is, at
                                      // most this many times (walls drawn while the estimate
                                      // ran away shut the rest of the building off; paper 002's
                                      // section V restarts for the same reason)

  // kInvalidArgument for a value outside its domain (checked by Params::validate).
  Status validate() const;
};

struct Params {
  WallFollowParams wall;
  SrtParams srt;
  GuidanceParams guidance;
  ApproachParams approach;
  FrontierParams frontier;
  LookAcrossParams look_across;

  // kInvalidArgument when a value is outside its domain (non-finite, negative, r_safe >= r_t,
  // more sectors than kMaxSectors, ...).
  Status validate() const;
};

}  // namespace kestrel::exploration
