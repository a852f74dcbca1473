#pragma once
// A uniform grid over the world's segments: each cell lists the segments whose bounding box
// touches it (compressed rows, built once). The ray caster walks it cell by cell (DDA) and
// the collision checker shares its cell layout for its broad phase.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "kestrel/sim/world.hpp"

namespace kestrel::sim {

class SegmentGrid {
 public:
  // `cell_m` is the cell size; the grid covers the segments' bounds plus one cell.
  SegmentGrid(std::vector<Segment> segments, double cell_m);

  const std::vector<Segment>& segments() const { return segments_; }
  double cell_m() const { return cell_; }
  Eigen::Vector2d origin() const { return origin_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  bool in_grid(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < nx_ && iy < ny_; }
  // Segments listed in cell (ix, iy), which must be in the grid.
  const uint32_t* cell_begin(int ix, int iy) const { return &items_[start_[index(ix, iy)]]; }
  const uint32_t* cell_end(int ix, int iy) const { return &items_[0] + start_[index(ix, iy) + 1]; }
  int cell_x(double x) const { return static_cast<int>(std::floor((x - origin_.x()) / cell_)); }
  int cell_y(double y) const { return static_cast<int>(std::floor((y - origin_.y()) / cell_)); }

 private:
  std::size_t index(int ix, int iy) const { return static_cast<std::size_t>(iy) * nx_ + ix; }

  std::vector<Segment> segments_;
  double cell_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int nx_ = 1, ny_ = 1;
  std::vector<uint32_t> start_;  // nx*ny + 1 offsets into items_
  std::vector<uint32_t> items_;
};

}  // namespace kestrel::sim
