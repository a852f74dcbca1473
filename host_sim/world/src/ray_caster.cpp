#include "kestrel/sim/ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace kestrel::sim {

namespace {

bool returns_from(Material material, double return_probability, Rng* railing_rng) {
  if (material == Material::kGlass) return false;
  if (material != Material::kRailing) return true;
  return railing_rng ? railing_rng->bernoulli(return_probability) : return_probability >= 0.5;
}

}  // namespace

RayCaster::RayCaster(const World& world, double cell_m, WallSurfaces walls, FacesOverStart faces_over_start)
    : grid_(world.segments(walls), cell_m), ceiling_(world.ceiling_m), faces_over_start_(faces_over_start) {
  for (const Obstacle& o : world.obstacles) {
    Footprint f;
    f.polygon = o.polygon;
    f.lo = f.hi = o.polygon.empty() ? Eigen::Vector2d::Zero() : o.polygon.front();
    for (const Eigen::Vector2d& v : o.polygon) {
      f.lo = f.lo.cwiseMin(v);
      f.hi = f.hi.cwiseMax(v);
    }
    f.z_min = o.z_min;
    f.z_max = o.z_max;
    f.material = o.material;
    f.return_probability = o.return_probability;
    footprints_.push_back(std::move(f));
  }
  const std::vector<Segment>& segs = grid_.segments();
  for (std::size_t i = segs.size(); i-- > 0;) {
    if (segs[i].obstacle >= 0) footprints_[static_cast<std::size_t>(segs[i].obstacle)].segment = static_cast<int>(i);
  }
  footprints_by_cell_.resize(static_cast<std::size_t>(grid_.nx()) * static_cast<std::size_t>(grid_.ny()));
  for (std::size_t k = 0; k < footprints_.size(); ++k) {
    const Footprint& f = footprints_[k];
    if (f.polygon.size() < 3) continue;
    const int x0 = std::max(0, grid_.cell_x(f.lo.x())), x1 = std::min(grid_.nx() - 1, grid_.cell_x(f.hi.x()));
    const int y0 = std::max(0, grid_.cell_y(f.lo.y())), y1 = std::min(grid_.ny() - 1, grid_.cell_y(f.hi.y()));
    for (int iy = y0; iy <= y1; ++iy) {
      for (int ix = x0; ix <= x1; ++ix) {
        footprints_by_cell_[static_cast<std::size_t>(iy) * static_cast<std::size_t>(grid_.nx()) +
                            static_cast<std::size_t>(ix)]
            .push_back(static_cast<uint32_t>(k));
      }
    }
  }
  seen_.assign(grid_.segments().size(), 0);
}

double RayCaster::face_over_start(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, Rng* railing_rng,
                                  RayHit& face) const {
  double best = std::numeric_limits<double>::infinity();
  if (faces_over_start_ == FacesOverStart::kMissed || dir.z() == 0) return best;
  const int ix = grid_.cell_x(origin.x()), iy = grid_.cell_y(origin.y());
  if (!grid_.in_grid(ix, iy)) return best;
  const Eigen::Vector2d p = origin.head<2>();
  for (const uint32_t k : footprints_by_cell_[static_cast<std::size_t>(iy) * static_cast<std::size_t>(grid_.nx()) +
                                              static_cast<std::size_t>(ix)]) {
    const Footprint& f = footprints_[k];
    if (p.x() < f.lo.x() || p.x() > f.hi.x() || p.y() < f.lo.y() || p.y() > f.hi.y()) continue;
    double t = -1;
    if (dir.z() < 0 && origin.z() > f.z_max) t = (f.z_max - origin.z()) / dir.z();
    if (dir.z() > 0 && origin.z() < f.z_min) t = (f.z_min - origin.z()) / dir.z();
    if (!(t > 0) || t >= best || !point_in_polygon(f.polygon, p)) continue;
    // Over the footprint at the start, and still over it where the beam reaches the face: a
    // beam that leaves it first passes beside the obstacle.
    if (!point_in_polygon(f.polygon, (origin + dir * t).head<2>())) continue;
    if (!returns_from(f.material, f.return_probability, railing_rng)) continue;
    best = t;
    face.kind = RayHit::Kind::kSurface;
    face.range_m = t;
    face.segment = f.segment;
    face.material = f.material;
  }
  return best;
}

RayHit RayCaster::cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir_in,
                       double max_range_m, Rng* railing_rng) {
  RayHit hit;
  const double norm = dir_in.norm();
  if (!(norm > 0) || !std::isfinite(norm) || !origin.allFinite() || !(max_range_m > 0)) return hit;
  const Eigen::Vector3d dir = dir_in / norm;
  const double hn = std::hypot(dir.x(), dir.y());  // horizontal metres per metre of beam
  const double z0 = origin.z();

  // The beam's 3D length at which it reaches the floor or ceiling, if it does within range.
  double t_plane = std::numeric_limits<double>::infinity();
  RayHit::Kind plane_kind = RayHit::Kind::kNone;
  if (dir.z() < 0 && z0 >= 0) {
    t_plane = z0 / -dir.z();
    plane_kind = RayHit::Kind::kFloor;
  } else if (dir.z() > 0 && ceiling_ > 0 && z0 <= ceiling_) {
    t_plane = (ceiling_ - z0) / dir.z();
    plane_kind = RayHit::Kind::kCeiling;
  }
  // A face of the obstacle the beam starts over (or under) is a plane nearer than the floor.
  RayHit face;
  const double t_face = face_over_start(origin, dir, railing_rng, face);
  if (t_face < t_plane) {
    t_plane = t_face;
    plane_kind = RayHit::Kind::kSurface;
  }
  const double t_limit = std::min(max_range_m, t_plane);
  auto finish_plane = [&]() {
    if (plane_kind != RayHit::Kind::kNone && t_plane <= max_range_m) {
      hit.kind = plane_kind;
      hit.range_m = t_plane;
      if (plane_kind == RayHit::Kind::kSurface) {
        hit.segment = face.segment;
        hit.material = face.material;
      }
    }
    return hit;
  };
  if (hn < 1e-9 || grid_.segments().empty()) return finish_plane();

  // Work in horizontal distance s along the unit 2D direction u; height z = z0 + slope * s.
  const Eigen::Vector2d p(origin.x(), origin.y());
  const Eigen::Vector2d u(dir.x() / hn, dir.y() / hn);
  const double slope = dir.z() / hn;
  const double s_limit = t_limit * hn;

  // Clip to the grid rectangle (slab test) so the walk starts inside it.
  const double cell = grid_.cell_m();
  const Eigen::Vector2d lo = grid_.origin();
  const Eigen::Vector2d hi = lo + Eigen::Vector2d(grid_.nx() * cell, grid_.ny() * cell);
  double s_in = 0, s_out = s_limit;
  for (int k = 0; k < 2; ++k) {
    if (std::fabs(u[k]) < 1e-15) {
      if (p[k] < lo[k] || p[k] > hi[k]) return finish_plane();
    } else {
      double a = (lo[k] - p[k]) / u[k], b = (hi[k] - p[k]) / u[k];
      if (a > b) std::swap(a, b);
      s_in = std::max(s_in, a);
      s_out = std::min(s_out, b);
    }
  }
  if (s_in > s_out) return finish_plane();

  if (++stamp_ == 0) {  // wrapped: clear the mailboxes once every 4 billion rays
    std::fill(seen_.begin(), seen_.end(), 0);
    stamp_ = 1;
  }
  const Eigen::Vector2d start = p + u * s_in;
  int ix = std::min(grid_.nx() - 1, std::max(0, grid_.cell_x(start.x())));
  int iy = std::min(grid_.ny() - 1, std::max(0, grid_.cell_y(start.y())));
  const int step_x = u.x() > 0 ? 1 : -1, step_y = u.y() > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const double dsx = std::fabs(u.x()) > 1e-15 ? cell / std::fabs(u.x()) : inf;
  const double dsy = std::fabs(u.y()) > 1e-15 ? cell / std::fabs(u.y()) : inf;
  double next_x = std::fabs(u.x()) > 1e-15
                      ? ((lo.x() + (ix + (step_x > 0 ? 1 : 0)) * cell) - p.x()) / u.x()
                      : inf;
  double next_y = std::fabs(u.y()) > 1e-15
                      ? ((lo.y() + (iy + (step_y > 0 ? 1 : 0)) * cell) - p.y()) / u.y()
                      : inf;

  const std::vector<Segment>& segs = grid_.segments();
  double best_s = inf;
  while (true) {
    for (const uint32_t* it = grid_.cell_begin(ix, iy); it != grid_.cell_end(ix, iy); ++it) {
      if (seen_[*it] == stamp_) continue;
      seen_[*it] = stamp_;
      const Segment& sg = segs[*it];
      // Solve p + s u = a + w (b - a) for s >= 0, w in [0, 1].
      const Eigen::Vector2d e = sg.b - sg.a;
      const double den = u.x() * e.y() - u.y() * e.x();
      if (std::fabs(den) < 1e-15) continue;  // parallel: a grazing beam sees no surface
      const Eigen::Vector2d d = sg.a - p;
      const double s = (d.x() * e.y() - d.y() * e.x()) / den;
      const double w = (d.x() * u.y() - d.y() * u.x()) / den;
      if (s <= 1e-9 || w < 0 || w > 1 || s >= best_s || s > s_limit) continue;
      const double z = z0 + slope * s;
      if (z < sg.z_min || z > sg.z_max) {
        // Over or under this face. Entering an obstacle's footprint (CCW polygon: the beam
        // runs against the edge's outward normal (e.y, -e.x)) it may still meet the top
        // or bottom face further in.
        if (sg.obstacle < 0 || sg.material == Material::kGlass) continue;
        if (u.x() * e.y() - u.y() * e.x() >= 0) continue;  // leaving, not entering
        double s_face = -1;
        if (z > sg.z_max && slope < 0) s_face = (sg.z_max - z0) / slope;
        if (z < sg.z_min && slope > 0) s_face = (sg.z_min - z0) / slope;
        if (s_face < s || s_face >= best_s || s_face > s_limit) continue;
        if (!point_in_polygon(footprints_[static_cast<std::size_t>(sg.obstacle)].polygon, p + u * s_face)) continue;
        if (!returns_from(sg.material, sg.return_probability, railing_rng)) continue;
        best_s = s_face;
        hit.segment = static_cast<int>(*it);
        hit.material = sg.material;
        continue;
      }
      if (!returns_from(sg.material, sg.return_probability, railing_rng)) continue;
      best_s = s;
      hit.segment = static_cast<int>(*it);
      hit.material = sg.material;
    }
    const double cell_exit = std::min(next_x, next_y);
    if (best_s <= cell_exit || cell_exit > s_out) break;
    if (next_x < next_y) {
      ix += step_x;
      next_x += dsx;
    } else {
      iy += step_y;
      next_y += dsy;
    }
    if (!grid_.in_grid(ix, iy)) break;
  }
  if (best_s <= s_limit) {
    hit.kind = RayHit::Kind::kSurface;
    hit.range_m = best_s / hn;
    return hit;
  }
  hit.segment = -1;
  return finish_plane();
}

}  // namespace kestrel::sim
