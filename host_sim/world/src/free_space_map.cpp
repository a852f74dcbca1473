#include "kestrel/sim/free_space_map.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::sim {

FreeSpaceMap::FreeSpaceMap(const World& world, double resolution_m)
    : res_(resolution_m > 0 ? resolution_m : 0.1) {
  const Bounds2 b = world.bounds();
  origin_ = b.min - Eigen::Vector2d(2 * res_, 2 * res_);
  w_ = static_cast<int>(std::ceil((b.max.x() - origin_.x()) / res_)) + 3;
  h_ = static_cast<int>(std::ceil((b.max.y() - origin_.y()) / res_)) + 3;
  cells_.assign(static_cast<std::size_t>(w_) * h_, kFree);
  auto mark = [&](const Eigen::Vector2d& p) {
    int ix = 0, iy = 0;
    cell_of(p.x(), p.y(), ix, iy);
    if (in_map(ix, iy)) cells_[idx(ix, iy)] = kOccupied;
  };
  // Segments: dense samples (a quarter cell apart) close every gap a 4-connected fill could
  // leak through.
  for (const Segment& s : world.segments()) {
    const double len = (s.b - s.a).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(len / (res_ * 0.25))));
    for (int k = 0; k <= n; ++k) mark(s.a + (s.b - s.a) * (static_cast<double>(k) / n));
  }
  for (const Obstacle& o : world.obstacles) {
    Eigen::Vector2d lo = o.polygon[0], hi = o.polygon[0];
    for (const auto& p : o.polygon) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    cell_of(lo.x(), lo.y(), x0, y0);
    cell_of(hi.x(), hi.y(), x1, y1);
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) {
        const Eigen::Vector2d c = origin_ + Eigen::Vector2d((ix + 0.5) * res_, (iy + 0.5) * res_);
        if (in_map(ix, iy) && point_in_polygon(o.polygon, c)) cells_[idx(ix, iy)] = kOccupied;
      }
  }
  int sx = 0, sy = 0;
  cell_of(world.start.x, world.start.y, sx, sy);
  if (!in_map(sx, sy) || cells_[idx(sx, sy)] != kFree) return;
  std::vector<std::pair<int, int>> stack{{sx, sy}};
  cells_[idx(sx, sy)] = kReachable;
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    ++reachable_;
    const int nb[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const auto& d : nb) {
      const int nx = x + d[0], ny = y + d[1];
      // Cells on the map border are never reachable: an open world does not count the
      // outside as free space to cover.
      if (nx <= 0 || ny <= 0 || nx >= w_ - 1 || ny >= h_ - 1) continue;
      if (cells_[idx(nx, ny)] != kFree) continue;
      cells_[idx(nx, ny)] = kReachable;
      stack.emplace_back(nx, ny);
    }
  }
}

void FreeSpaceMap::cell_of(double x, double y, int& ix, int& iy) const {
  ix = static_cast<int>(std::floor((x - origin_.x()) / res_));
  iy = static_cast<int>(std::floor((y - origin_.y()) / res_));
}

}  // namespace kestrel::sim
