#pragma once
// The world's reachable free area, for the `coverage` metric: the world is rasterised into a
// coarse occupancy grid (every wall and obstacle footprint is occupied, whatever its height,
// since the vehicle cannot cross it at flight height in general), then flood-filled
// (4-connected) from the start pose. Coverage is the fraction of reachable cells seen.
#include <cstdint>
#include <vector>

#include "kestrel/sim/world.hpp"

namespace kestrel::sim {

class FreeSpaceMap {
 public:
  explicit FreeSpaceMap(const World& world, double resolution_m = 0.1);

  double resolution_m() const { return res_; }
  int width() const { return w_; }
  int height() const { return h_; }
  Eigen::Vector2d origin() const { return origin_; }
  bool in_map(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < w_ && iy < h_; }
  bool occupied(int ix, int iy) const { return in_map(ix, iy) && cells_[idx(ix, iy)] == kOccupied; }
  bool reachable(int ix, int iy) const { return in_map(ix, iy) && cells_[idx(ix, iy)] == kReachable; }
  // Cell containing world point (x, y); may be outside the map.
  void cell_of(double x, double y, int& ix, int& iy) const;
  std::size_t reachable_cells() const { return reachable_; }
  double reachable_area_m2() const { return static_cast<double>(reachable_) * res_ * res_; }

 private:
  enum : uint8_t { kFree = 0, kOccupied = 1, kReachable = 2 };
  std::size_t idx(int ix, int iy) const { return static_cast<std::size_t>(iy) * w_ + ix; }

  double res_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int w_ = 0, h_ = 0;
  std::vector<uint8_t> cells_;
  std::size_t reachable_ = 0;
};

}  // namespace kestrel::sim
