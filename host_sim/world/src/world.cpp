#include "kestrel/sim/world.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::sim {

const char* to_string(Material m) {
  switch (m) {
    case Material::kOpaque: return "opaque";
    case Material::kGlass: return "glass";
    case Material::kRailing: return "railing";
  }
  return "?";
}

std::vector<Segment> World::segments(WallSurfaces surfaces) const {
  std::vector<Segment> out;
  int piece = 0;
  for (const Wall& w : walls) {
    if (surfaces == WallSurfaces::kBoxOutlines && w.material == Material::kOpaque && wall_thickness_m > 0) {
      const std::array<Eigen::Vector2d, 4> box = wall_outline(w, wall_thickness_m);
      for (std::size_t i = 0; i < box.size(); ++i)
        out.push_back({box[i], box[(i + 1) % box.size()], w.z_min, w.z_max, w.material,
                       w.return_probability, piece, -1});
    } else {
      out.push_back({w.a, w.b, w.z_min, w.z_max, w.material, w.return_probability, piece, -1});
    }
    ++piece;
  }
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const Obstacle& o = obstacles[k];
    const std::size_t n = o.polygon.size();
    for (std::size_t i = 0; i < n; ++i) {
      out.push_back({o.polygon[i], o.polygon[(i + 1) % n], o.z_min, o.z_max, o.material,
                     o.return_probability, piece, static_cast<int>(k)});
    }
    ++piece;
  }
  return out;
}

Bounds2 World::bounds() const {
  Bounds2 b;
  bool first = true;
  auto grow = [&](const Eigen::Vector2d& p) {
    if (first) {
      b.min = b.max = p;
      first = false;
    } else {
      b.min = b.min.cwiseMin(p);
      b.max = b.max.cwiseMax(p);
    }
  };
  grow(Eigen::Vector2d(start.x, start.y));
  for (const Wall& w : walls) {
    grow(w.a);
    grow(w.b);
  }
  for (const Obstacle& o : obstacles)
    for (const auto& p : o.polygon) grow(p);
  return b;
}

std::array<Eigen::Vector2d, 4> wall_outline(const Wall& wall, double thickness_m) {
  const double h = thickness_m / 2;
  const Eigen::Vector2d d = (wall.b - wall.a).normalized();
  const Eigen::Vector2d n(-d.y() * h, d.x() * h);  // d turned left
  const Eigen::Vector2d a = wall.a - d * h, b = wall.b + d * h;
  return {a - n, b - n, b + n, a + n};
}

double polygon_signed_area(const std::vector<Eigen::Vector2d>& poly) {
  double twice = 0;  // shoelace
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    twice += poly[j].x() * poly[i].y() - poly[i].x() * poly[j].y();
  return 0.5 * twice;
}

bool point_in_polygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  bool inside = false;
  const std::size_t n = poly.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

int World::room_at(double x, double y) const {
  // Rooms may nest (gt-building's inner room lies inside its north-east room): the smallest
  // room containing the point is the one it is in.
  const Eigen::Vector2d p(x, y);
  int best = -1;
  double best_area = 0;
  for (std::size_t i = 0; i < rooms.size(); ++i) {
    if (!point_in_polygon(rooms[i].polygon, p)) continue;
    const double area = std::fabs(polygon_signed_area(rooms[i].polygon));
    if (best < 0 || area < best_area) {
      best = static_cast<int>(i);
      best_area = area;
    }
  }
  return best;
}

}  // namespace kestrel::sim
