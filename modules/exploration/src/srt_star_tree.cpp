#include "kestrel/exploration/srt_star_tree.hpp"

#include <algorithm>
#include <cmath>

#include "kestrel/core/angle.hpp"

namespace kestrel::exploration {

int SrtNode::sector_of(Point2 p) const {
  const float a = std::atan2(p.y - position.y, p.x - position.x);
  float rel = a - sector_start_rad;
  // Bring rel into [0, 2 pi): the sectors start at sector_start_rad and go counter-clockwise.
  rel = wrap_angle(rel);
  if (rel < 0.0f) rel += 2.0f * kPi<float>;
  const float idx = rel / sector_width_rad;
  if (!(idx >= 0.0f) || idx >= static_cast<float>(sector_count)) return -1;
  return static_cast<int>(idx);
}

bool SrtNode::contains(Point2 p, float margin_m, uint32_t* used) const {
  const float dx = p.x - position.x, dy = p.y - position.y;
  const float d2 = dx * dx + dy * dy;
  const float reach = static_cast<float>(reach_mm) * 1e-3f - margin_m;
  if (used != nullptr) *used += work::kRegionTest;
  if (reach <= 0.0f || d2 >= reach * reach) return false;
  if (used != nullptr) *used += work::kRegionAngle;
  const int s = sector_of(p);
  if (s < 0) return false;
  const float r = static_cast<float>(radius_mm[static_cast<std::size_t>(s)]) * 1e-3f - margin_m;
  return r > 0.0f && d2 < r * r;
}

void SrtStarTree::clear() {
  nodes_.clear();
  frontiers_.clear();
  stage_ = Stage::kIdle;
}

bool SrtStarTree::in_safe_region(Point2 p, float margin_m, uint16_t except) const {
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    if (i != except && nodes_[i].contains(p, margin_m)) return true;
  return false;
}

Status SrtStarTree::add_node(const Pose2& pose, const SectorScan& sectors, uint16_t parent, uint16_t& id) {
  if (Status st = begin_node(pose, sectors, parent, id); st != Status::kOk) return st;
  (void)advance(sectors, work::kUnbounded);
  return Status::kOk;
}

Status SrtStarTree::begin_node(const Pose2& pose, const SectorScan& sectors, uint16_t parent, uint16_t& id) {
  id = kNoNode;
  stage_ = Stage::kIdle;
  if (!pose.finite() || sectors.count() == 0) return Status::kInvalidArgument;
  if (parent != kNoNode && parent >= nodes_.size()) return Status::kInvalidArgument;
  if (nodes_.full()) return Status::kCapacityExceeded;

  SrtNode node;
  node.position = {pose.x, pose.y};
  node.heading_rad = pose.theta;
  node.sector_start_rad = wrap_angle(pose.theta + sectors.start_rad());
  node.sector_width_rad = sectors.width_rad();
  node.sector_count = sectors.count();
  node.parent = parent;
  for (uint16_t s = 0; s < sectors.count(); ++s) {
    node.radius_mm[s] = sectors.radius_mm(s);
    for (uint16_t j = 0; j < SectorScan::kRaysPerSector; ++j)
      node.clear_mm[s * SectorScan::kRaysPerSector + j] = sectors.clear_mm(s, j);
    node.reach_mm = std::max(node.reach_mm, sectors.radius_mm(s));
  }
  (void)nodes_.push_back(node);  // cannot fail: checked full() above
  id = static_cast<uint16_t>(nodes_.size() - 1);
  new_cos_ = std::cos(pose.theta);
  new_sin_ = std::sin(pose.theta);
  stage_ = Stage::kPrune;
  cursor_ = 0;
  return Status::kOk;
}

uint32_t SrtStarTree::advance(const SectorScan& sectors, uint32_t budget) {
  uint32_t used = 0;
  if (stage_ == Stage::kIdle) return used;
  const SrtNode& added = nodes_.back();
  const uint16_t id = static_cast<uint16_t>(nodes_.size() - 1);
  // Frontiers of older nodes now seen past.
  for (; stage_ == Stage::kPrune && used < budget;) {
    if (cursor_ == frontiers_.size()) {
      stage_ = Stage::kPlace;
      cursor_ = 0;
    } else if (added.contains(frontiers_[cursor_].position, coverage_margin_m, &used)) {
      frontiers_.swap_remove(cursor_);
      ++frontiers_removed_;
    } else {
      ++cursor_;
    }
  }
  // The new node's frontiers, unless an older safe region already covers them.
  const IVector<LocalFrontier>& local = sectors.frontiers();
  while ((stage_ == Stage::kPlace || stage_ == Stage::kTest) && used < budget) {
    if (stage_ == Stage::kPlace) {
      if (cursor_ == local.size()) {
        stage_ = Stage::kIdle;
        break;
      }
      const LocalFrontier& lf = local[cursor_];
      const float bx = lf.range_m * std::cos(lf.angle_rad), by = lf.range_m * std::sin(lf.angle_rad);
      placed_ = Frontier{};
      placed_.position = {added.position.x + new_cos_ * bx - new_sin_ * by,
                          added.position.y + new_sin_ * bx + new_cos_ * by};
      placed_.node = id;
      placed_.sector = lf.sector;
      placed_.kind = lf.kind;
      used += work::kTableEntry;
      test_node_ = 0;
      stage_ = Stage::kTest;
      continue;
    }
    // kTest: one older node per pass, so a tree of many nodes is spread as well.
    bool covered = false;
    for (; test_node_ < nodes_.size() && used < budget && !covered; ++test_node_)
      if (test_node_ != id) covered = nodes_[test_node_].contains(placed_.position, coverage_margin_m, &used);
    if (!covered && test_node_ < nodes_.size()) continue;  // out of budget: resume here
    if (!covered && !frontiers_.push_back(placed_)) ++frontiers_dropped_;
    ++cursor_;
    stage_ = Stage::kPlace;
  }
  return used;
}

std::size_t SrtStarTree::frontier_count_of(uint16_t node) const {
  std::size_t n = 0;
  for (const Frontier& f : frontiers_) n += f.node == node ? 1 : 0;
  return n;
}

std::size_t SrtStarTree::frontier_index_of(uint16_t node, std::size_t k) const {
  for (std::size_t i = 0; i < frontiers_.size(); ++i) {
    if (frontiers_[i].node != node) continue;
    if (k == 0) return i;
    --k;
  }
  return frontiers_.size();
}

}  // namespace kestrel::exploration
