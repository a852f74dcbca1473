#pragma once
// The Sensor-based Random Tree of SRT-Star (paper 002 section IV; Freda and Oriolo, ICRA 2005).
// Nodes are the waypoints the vehicle reached, each with the sectors of the scan taken there:
// its Local Safe Region, in the world frame. Frontier points are the potential branches. The
// union of the safe regions grows as the tree grows, so a frontier that falls inside a newly
// acquired safe region is removed (it has been seen past); new frontiers that already lie inside
// an older safe region are never added.
//
// Fixed capacity: kMaxNodes nodes and kMaxFrontiers frontiers. A node that does not fit is
// refused with kCapacityExceeded (the planner then restarts the tree); frontiers that do not fit
// are dropped and counted. Safe-region tests cost one distance check per node and one atan2 for
// the nodes within reach, and run only when a node is added.
#include <array>
#include <cstdint>

#include "kestrel/core/se2.hpp"
#include "kestrel/core/static_vector.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/exploration/params.hpp"
#include "kestrel/exploration/sector_scan.hpp"

namespace kestrel::exploration {

inline constexpr uint16_t kNoNode = 0xFFFFu;

struct SrtNode {
  Point2 position;             // m, world frame
  float heading_rad = 0;       // vehicle heading when the scan was taken
  float sector_start_rad = 0;  // world angle of sector 0's clockwise edge
  float sector_width_rad = 0;
  uint16_t sector_count = 0;
  uint16_t parent = kNoNode;
  uint16_t reach_mm = 0;                          // largest sector radius: cheap rejection in safe-region tests
  std::array<uint16_t, kMaxSectors> radius_mm{};  // perceived: the safe region
  // Clear distance of each sector's rays (SectorScan::kRaysPerSector each): where to fly.
  std::array<uint16_t, kMaxSectors * SectorScan::kRaysPerSector> clear_mm{};
  float ray_angle(uint16_t s, uint16_t j) const {
    return sector_start_rad +
           (static_cast<float>(s) + (static_cast<float>(j) + 0.5f) / SectorScan::kRaysPerSector) * sector_width_rad;
  }

  // The sector holding world point p, or -1 when p is outside the scanned field of view.
  int sector_of(Point2 p) const;
  // Strictly inside the safe region by at least margin_m. Adds the test's work units (see
  // SectorScan's work namespace) to *used when given.
  bool contains(Point2 p, float margin_m, uint32_t* used = nullptr) const;
};

struct Frontier {
  Point2 position;          // m, world frame
  uint16_t node = kNoNode;  // the node whose scan produced it
  uint8_t sector = 0;       // its sector in that node
  FrontierKind kind = FrontierKind::kMid;
  uint8_t attempts = 0;  // waypoints drawn towards it so far
  bool handed_up = false;  // its own node had no path to it; now an ancestor's (the planner's)
};

class SrtStarTree {
 public:
  void clear();

  // Adds a node at `pose` with the safe region and frontiers of `sectors` (body frame of the
  // pose), child of `parent` (kNoNode for the root). Removes old frontiers the new safe region
  // covers, adds the new frontiers no other safe region covers. kCapacityExceeded (tree
  // unchanged) when no node slot is left; kInvalidArgument for a non-finite pose, an empty
  // sector set or an unknown parent.
  Status add_node(const Pose2& pose, const SectorScan& sectors, uint16_t parent, uint16_t& id);

  // The same in slices, for a caller with a time budget per cycle: begin_node() checks and
  // appends the node (same results as add_node); advance() then removes the older frontiers the
  // new region covers and adds the node's own, stopping once it has used `budget` work units
  // (SectorScan's work namespace; it may overrun by one region test), and returns the units
  // used. adding() until it is done. `sectors` must be the object begin_node() got, unchanged,
  // and the tree must not be changed otherwise in between.
  Status begin_node(const Pose2& pose, const SectorScan& sectors, uint16_t parent, uint16_t& id);
  uint32_t advance(const SectorScan& sectors, uint32_t budget);
  bool adding() const { return stage_ != Stage::kIdle; }

  // Whether p lies inside any node's safe region (by margin_m), ignoring node `except`.
  bool in_safe_region(Point2 p, float margin_m, uint16_t except = kNoNode) const;

  const IVector<SrtNode>& nodes() const { return nodes_; }
  const IVector<Frontier>& frontiers() const { return frontiers_; }
  std::size_t frontier_count_of(uint16_t node) const;
  // Index into frontiers() of the k-th live frontier of `node` (k < frontier_count_of(node)).
  std::size_t frontier_index_of(uint16_t node, std::size_t k) const;
  Frontier& frontier(std::size_t i) { return frontiers_[i]; }
  void remove_frontier(std::size_t i) { frontiers_.swap_remove(i); }
  bool full() const { return nodes_.full(); }

  uint32_t frontiers_dropped() const { return frontiers_dropped_; }  // did not fit
  uint32_t frontiers_removed() const { return frontiers_removed_; }  // covered by a new region
  float coverage_margin_m = 0.05f;                                   // set from SrtParams by the planner

 private:
  enum class Stage : uint8_t { kIdle, kPrune, kPlace, kTest };
  StaticVector<SrtNode, kMaxNodes> nodes_;
  StaticVector<Frontier, kMaxFrontiers> frontiers_;
  uint32_t frontiers_dropped_ = 0;
  uint32_t frontiers_removed_ = 0;
  // The node being added: the frontier or local frontier next in turn, and for a local
  // frontier placed in the world, the next older node to test it against.
  Stage stage_ = Stage::kIdle;
  std::size_t cursor_ = 0;
  std::size_t test_node_ = 0;
  Frontier placed_{};
  float new_cos_ = 1, new_sin_ = 0;  // of the new node's heading
};

}  // namespace kestrel::exploration
