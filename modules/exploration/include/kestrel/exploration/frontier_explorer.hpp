#pragma once
// The grid frontier explorer of paper 003 (Gäbel, Krüger, Bestmann, sections 3.2 and 3.3, after
// Yamauchi 1997): the laser draws an occupancy grid; the frontiers between its known free and
// its unknown cells are the places to go; the nearest accessible one, by the cost of the
// Dijkstra path to it, is flown to; a goal that sees no progress for a while is blacklisted;
// when no accessible frontier is left the building is explored, and the explorer flies home
// along the grid's path there (the Dijkstra search from the vehicle reaches home too) and then
// reports finished; the mission lands it there. With no way home on the grid it reports
// finished at once, and the mission flies its breadcrumb trail home as for the other explorers.
// Paper 003 picks the frontier of least Euclidean distance; this one takes the path's cost,
// which is what the flight costs (a frontier behind a wall is not near).
//
// The two levels of paper 000 Figure 4, and what crosses between them:
//   level 2, step() on every scan: hands the scan and the pose to level 3 (at most every
//     draw_period_s), takes the newest plan, and flies it as paper 002's blend flies its
//     waypoints: v = field_weight * v_wf + K_fr (carrot - x), the carrot lookahead_m along the
//     path, the heading towards the carrot, then the base's speed, yaw-rate and approach limits.
//   level 3, background_step(): draws the scans, and at least every replan_period_s (at once
//     after an arrival) computes the obstacle distance, the search, the frontiers and the path.
// Scans go down and plans come up through one-slot lock-free queues (core RingBuffer, SPSC):
// neither level waits, a full queue drops the newest (counted). background_step() runs on one
// background thread on a board, or in lockstep after every poll in the simulator.
//
// The grid is centred on the first pose the explorer is stepped with (the take-off point).
// Memory: about 1.4 MiB, inside this object (grid, obstacle distance, search costs).
#include <array>
#include <atomic>
#include <span>

#include "kestrel/core/ring_buffer.hpp"
#include "kestrel/exploration/explorer_base.hpp"
#include "kestrel/exploration/frontier_clusters.hpp"
#include "kestrel/planning/grid_search.hpp"
#include "kestrel/planning/obstacle_distance.hpp"
#include "kestrel/planning/occupancy_grid.hpp"
#include "kestrel/planning/path_simplify.hpp"

namespace kestrel::exploration {

inline constexpr std::size_t kMaxBlacklist = 64;  // a full blacklist forgets its oldest goal

// What level 3 hands the loop.
struct FrontierPlan {
  uint32_t seq = 0;           // 1, 2, ... per plan published
  TimeUs stamp;               // of the newest scan drawn before it
  bool has_goal = false;      // false: no accessible frontier (the loop hovers)
  bool homing = false;        // explored: the goal is home, the path the grid's way there
  Point2 frontier;            // the frontier cell the flight heads for (home, when homing)
  planning::PathPoints path;  // from the vehicle's cell, ending goal_inset_m short of the frontier
};

struct FrontierCounters {
  // Level 2's (written by step()).
  uint32_t scans_offered = 0;
  uint32_t scans_dropped = 0;  // level 3 had not taken the previous one
  uint32_t plans_taken = 0;
  uint32_t arrivals = 0;
  uint32_t stale_holds = 0;    // steps that held because level 3's plan was older than 5 s
  // Level 3's (written by background_step()).
  uint32_t scans_drawn = 0;
  uint32_t draw_errors = 0;    // a scan off the grid or of another geometry
  uint32_t plans = 0;
  uint32_t plans_dropped = 0;  // the loop had not taken the previous one
  uint32_t search_failures = 0;  // the search's open pool overflowed: no plan that time
  uint32_t relaxed_plans = 0;    // plans that needed the relaxed lethal distance
  uint32_t grid_restarts = 0;    // grids forgotten with inaccessible frontiers left
  uint32_t homed = 0;            // 1: flew home on the grid before reporting finished
  uint32_t goals = 0;            // frontiers chosen
  uint32_t blacklisted = 0;      // goals given up: no progress, too long, stuck, or reached and still a frontier
  uint32_t stuck = 0;            // ... of those, by the stuck detection
  uint32_t looked_at = 0;        // ... of those, looked at from near and not cleared
  uint32_t peak_open = 0;        // the search's largest wave front
};

class FrontierExplorer final : public ExplorerBase {
 public:
  ExplorerKind kind() const override { return ExplorerKind::kFrontier; }
  bool finished() const override { return finished_.load(std::memory_order_acquire); }
  const SrtStarPlanner* planner() const override { return nullptr; }
  void background_step() override;

  // For pictures, metrics and tests. Level 3's state (grid, frontiers, blacklist) may only be
  // read while level 3 is idle: after the flight, or between lockstep steps.
  const planning::OccupancyGrid& grid() const { return grid_; }
  const FrontierClusters& frontiers() const { return clusters_; }
  const FrontierClusterFinder& frontier_cells() const { return finder_; }
  std::span<const Point2> blacklist() const { return {blacklist_.data(), blacklist_count_}; }
  const FrontierPlan& plan_in_flight() const { return plan_; }  // level 2's copy
  FrontierCounters counters() const;

 private:
  struct MapInput {
    LaserScan scan;
    Pose2 pose;
    bool arrived = false;  // the loop reached the end of the plan it flies
  };

  Status plan(const Pose2& pose, const LaserScan& scan, TimeUs now, GuidanceSetpoint& out,
              float& heading_target) override;
  // kInvalidArgument for a lethal distance below the approach limiter's stop distance: the
  // limiter would hold the vehicle out of the gaps the planner sends it through.
  Status configure_strategy() override;
  void reset_strategy() override;

  // Level 2.
  Point2 carrot(const Pose2& pose);
  // Level 3.
  void reset_level3();
  void replan(TimeUs now);
  // The search from the vehicle's cell and the frontiers it reaches; false when the search
  // could not be run (it is counted).
  bool search_frontiers(float lethal_m, const planning::CellBox& box, planning::Cell start);
  // Counts a scan drawn with the goal near and in the laser's fan.
  void look_at_goal();
  // The coastal distance in chamfer units (0: none for this laser).
  uint8_t coastal_units() const;
  void judge_goal(TimeUs now);
  bool in_blacklist(const Point2& p) const;
  void add_to_blacklist(const Point2& p);
  void publish();
  // Explored: the path home, or finished when there is none (or the vehicle is home).
  void plan_home();

  // Level 2 only.
  FrontierPlan plan_{};
  FrontierPlan incoming_{};
  MapInput staging_{};
  bool have_plan_ = false;
  std::size_t leg_ = 0;          // the path leg the vehicle flies along
  uint32_t arrived_seq_ = 0;     // the plan whose end was reached (reported once)
  bool arrival_pending_ = false;
  TimeUs last_offer_{};
  bool offered_ = false;
  FrontierCounters level2_{};

  // Crossing.
  RingBuffer<MapInput, 2> to_level3_;
  RingBuffer<FrontierPlan, 2> to_level2_;
  std::atomic<bool> finished_{false};
  std::atomic<bool> reset_requested_{false};

  // Level 3 only.
  MapInput work_{};
  planning::OccupancyGrid grid_;
  planning::ObstacleDistance distance_;
  planning::GridSearch search_;
  FrontierClusterFinder finder_;
  FrontierClusters clusters_;
  planning::PathCells path_cells_;
  FrontierPlan outgoing_{};
  std::array<Point2, kMaxBlacklist> blacklist_{};
  std::size_t blacklist_count_ = 0, blacklist_next_ = 0;
  bool grid_ready_ = false;
  Pose2 pose_{};                 // the newest scan's
  TimeUs stamp_{};
  bool arrived_ = false;
  bool planned_ = false;
  TimeUs last_plan_{};
  uint32_t seq_ = 0;
  uint8_t empty_plans_ = 0;
  bool homing_ = false;          // explored: flying home on the grid
  planning::Cell home_cell_{};   // the grid's centre: the first pose stepped
  // The goal being flown to: its frontier cell, since when, and the best path cost seen.
  bool goal_active_ = false;
  planning::Cell goal_cell_{};
  TimeUs goal_since_{}, last_progress_{};
  uint16_t best_cost_ = 0;
  uint32_t known_at_progress_ = 0;  // the grid's known cells when progress was last seen
  uint16_t looks_ = 0;              // scans drawn with the goal near and in the laser's fan
  // The stuck detection's disc: where the vehicle was when it last left the previous one.
  Point2 stuck_anchor_{};
  TimeUs stuck_since_{};
  bool stuck_armed_ = false;
  FrontierCounters level3_{};
};

}  // namespace kestrel::exploration
