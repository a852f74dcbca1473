#pragma once
// A uniform grid over the world's segments: each cell lists the segments whose bounding box
// touches it (compressed rows, built once). The ray caster walks it cell by cell (DDA) and
// the collision checker uses it as its broad phase.
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
  // Calls f(segment_index) once for every segment listed in a cell overlapping the box;
  // `seen` is caller scratch of segments().size() entries, `stamp` a fresh nonzero value.
  template <class F>
  void for_each_in_box(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                       std::vector<uint32_t>& seen, uint32_t stamp, F&& f) const {
    const int x0 = std::max(0, cell_x(lo.x())), x1 = std::min(nx_ - 1, cell_x(hi.x()));
    const int y0 = std::max(0, cell_y(lo.y())), y1 = std::min(ny_ - 1, cell_y(hi.y()));
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix)
        for (const uint32_t* p = cell_begin(ix, iy); p != cell_end(ix, iy); ++p) {
          if (seen[*p] == stamp) continue;
          seen[*p] = stamp;
          f(*p);
        }
  }
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
