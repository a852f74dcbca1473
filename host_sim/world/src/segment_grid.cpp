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
  // listed in every cell it touches: the cells of its bounding box whose rectangle, grown by
  // a small margin so that rounding in the ray walk never misses a corner, is not entirely
  // on one side of the segment's line.
  const double eps = 1e-6 * cell_ + 1e-9;
  auto visit = [&](const Segment& s, auto&& on_cell) {
    const Eigen::Vector2d lo_s = s.a.cwiseMin(s.b), hi_s = s.a.cwiseMax(s.b);
    const int x0 = std::max(0, cell_x(lo_s.x() - eps)), x1 = std::min(nx_ - 1, cell_x(hi_s.x() + eps));
    const int y0 = std::max(0, cell_y(lo_s.y() - eps)), y1 = std::min(ny_ - 1, cell_y(hi_s.y() + eps));
    const Eigen::Vector2d d = s.b - s.a;
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) {
        const double cx0 = origin_.x() + ix * cell_ - eps, cx1 = origin_.x() + (ix + 1) * cell_ + eps;
        const double cy0 = origin_.y() + iy * cell_ - eps, cy1 = origin_.y() + (iy + 1) * cell_ + eps;
        int pos = 0, neg = 0;
        for (const Eigen::Vector2d& c : {Eigen::Vector2d(cx0, cy0), Eigen::Vector2d(cx1, cy0),
                                         Eigen::Vector2d(cx0, cy1), Eigen::Vector2d(cx1, cy1)}) {
          const double side = d.x() * (c.y() - s.a.y()) - d.y() * (c.x() - s.a.x());
          pos += side >= 0 ? 1 : 0;
          neg += side <= 0 ? 1 : 0;
        }
        if (pos > 0 && neg > 0) on_cell(index(ix, iy));
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
