#include "kestrel/sim/segment_grid.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::sim {

SegmentGrid::SegmentGrid(std::vector<Segment> segments, double cell_m)
    : segments_(std::move(segments)), cell_(cell_m > 0 ? cell_m : 1.0) {
  Eigen::Vector2d lo(0, 0), hi(0, 0);
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    const Eigen::Vector2d a = s.a.cwiseMin(s.b), b = s.a.cwiseMax(s.b);
    lo = i == 0 ? a : lo.cwiseMin(a);
    hi = i == 0 ? b : hi.cwiseMax(b);
  }
  origin_ = lo - Eigen::Vector2d(cell_, cell_);
  nx_ = std::max(1, static_cast<int>(std::ceil((hi.x() - origin_.x()) / cell_)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil((hi.y() - origin_.y()) / cell_)) + 1);
  const std::size_t ncell = static_cast<std::size_t>(nx_) * ny_;
  std::vector<uint32_t> count(ncell + 1, 0);
  // Two passes (count, then fill) give compact rows without per-cell vectors. A segment is
  // listed in every cell its supercover touches, found by sampling at a quarter cell.
  auto visit = [&](const Segment& s, auto&& on_cell) {
    const double len = (s.b - s.a).norm();
    const int steps = std::max(1, static_cast<int>(std::ceil(len / (cell_ * 0.25))));
    int last = -1;
    for (int k = 0; k <= steps; ++k) {
      const Eigen::Vector2d p = s.a + (s.b - s.a) * (static_cast<double>(k) / steps);
      // The 3x3 neighbourhood of each sample guarantees the supercover despite sampling.
      const int cx = cell_x(p.x()), cy = cell_y(p.y());
      const int key = cy * nx_ + cx;
      if (key == last) continue;
      last = key;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (in_grid(cx + dx, cy + dy)) on_cell(index(cx + dx, cy + dy));
    }
  };
  std::vector<uint32_t> mark(ncell, 0);
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    visit(segments_[i], [&](std::size_t c) {
      if (mark[c] == i + 1) return;
      mark[c] = static_cast<uint32_t>(i + 1);
      ++count[c + 1];
    });
  }
  start_.assign(ncell + 1, 0);
  for (std::size_t c = 0; c < ncell; ++c) start_[c + 1] = start_[c] + count[c + 1];
  items_.assign(std::max<uint32_t>(1, start_[ncell]), 0);
  std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
  std::fill(mark.begin(), mark.end(), 0);
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    visit(segments_[i], [&](std::size_t c) {
      if (mark[c] == i + 1) return;
      mark[c] = static_cast<uint32_t>(i + 1);
      items_[fill[c]++] = static_cast<uint32_t>(i);
    });
  }
}

}  // namespace kestrel::sim
