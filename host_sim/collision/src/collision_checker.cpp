#include "kestrel/sim/collision_checker.hpp"

#include <ccd/ccd.h>
#include <ccd/vec3.h>

#include <algorithm>
#include <cmath>

namespace kestrel::sim {
namespace {

struct CylinderShape {
  Eigen::Vector3d center;
  Eigen::Matrix3d rot;  // body to world
  double radius, half_height;
};

void cylinder_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* c = static_cast<const CylinderShape*>(obj);
  const Eigen::Vector3d d_world(ccdVec3X(dir), ccdVec3Y(dir), ccdVec3Z(dir));
  const Eigen::Vector3d d = c->rot.transpose() * d_world;
  const double n = std::hypot(d.x(), d.y());
  Eigen::Vector3d s(0, 0, d.z() >= 0 ? c->half_height : -c->half_height);
  if (n > 1e-12) {
    s.x() = c->radius * d.x() / n;
    s.y() = c->radius * d.y() / n;
  }
  const Eigen::Vector3d w = c->center + c->rot * s;
  ccdVec3Set(out, w.x(), w.y(), w.z());
}

void cylinder_center(const void* obj, ccd_vec3_t* out) {
  const auto* c = static_cast<const CylinderShape*>(obj);
  ccdVec3Set(out, c->center.x(), c->center.y(), c->center.z());
}

void prism_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* p = static_cast<const CollisionChecker::Prism*>(obj);
  double best = -1e300;
  Eigen::Vector2d v = p->polygon[0];
  for (const auto& q : p->polygon) {
    const double dot = q.x() * ccdVec3X(dir) + q.y() * ccdVec3Y(dir);
    if (dot > best) {
      best = dot;
      v = q;
    }
  }
  ccdVec3Set(out, v.x(), v.y(), ccdVec3Z(dir) >= 0 ? p->z_max : p->z_min);
}

void prism_center(const void* obj, ccd_vec3_t* out) {
  const auto* p = static_cast<const CollisionChecker::Prism*>(obj);
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& q : p->polygon) c += q;
  c /= static_cast<double>(p->polygon.size());
  ccdVec3Set(out, c.x(), c.y(), 0.5 * (p->z_min + p->z_max));
}

}  // namespace

CollisionChecker::CollisionChecker(const World& world, const SegmentGrid& grid,
                                   double body_radius_m, double body_height_m)
    : grid_(grid), radius_(body_radius_m), height_(body_height_m) {
  const double t = world.wall_thickness_m;
  for (const Wall& w : world.walls) {
    const Eigen::Vector2d d = (w.b - w.a).normalized();
    const Eigen::Vector2d n(-d.y() * t / 2, d.x() * t / 2);
    Prism p;
    // The thin box also extends half a thickness past each end, so corners close.
    const Eigen::Vector2d a = w.a - d * (t / 2), b = w.b + d * (t / 2);
    p.polygon = {a - n, b - n, b + n, a + n};
    p.z_min = w.z_min;
    p.z_max = w.z_max;
    p.line = w.line;
    pieces_.push_back(std::move(p));
  }
  for (const Obstacle& o : world.obstacles) pieces_.push_back({o.polygon, o.z_min, o.z_max, o.line});
  // The grid lists segment centre lines; a wall's box reaches half a thickness beyond them.
  reach_ = std::hypot(radius_, height_ / 2) + t;
  seen_segments_.assign(grid_.segments().size(), 0);
  seen_pieces_.assign(pieces_.size(), 0);
}

bool CollisionChecker::check(const VehicleState& state, Contact& out) {
  if (++stamp_ == 0) {
    std::fill(seen_segments_.begin(), seen_segments_.end(), 0);
    std::fill(seen_pieces_.begin(), seen_pieces_.end(), 0);
    stamp_ = 1;
  }
  const Eigen::Vector2d c(state.position_m.x(), state.position_m.y());
  const Eigen::Vector2d r(reach_, reach_);
  candidates_.clear();
  const std::vector<Segment>& segs = grid_.segments();
  grid_.for_each_in_box(c - r, c + r, seen_segments_, stamp_, [&](uint32_t si) {
    const int piece = segs[si].piece;
    if (seen_pieces_[static_cast<std::size_t>(piece)] == stamp_) return;
    seen_pieces_[static_cast<std::size_t>(piece)] = stamp_;
    candidates_.push_back(piece);
  });
  std::sort(candidates_.begin(), candidates_.end());  // deterministic order

  CylinderShape body{state.position_m, state.rotation(), radius_, height_ / 2};
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = cylinder_support;
  ccd.center1 = cylinder_center;
  ccd.support2 = prism_support;
  ccd.center2 = prism_center;
  ccd.max_iterations = 100;
  ccd.mpr_tolerance = 1e-6;
  bool found = false;
  for (const int piece : candidates_) {
    const Prism& p = pieces_[static_cast<std::size_t>(piece)];
    // Cheap vertical reject before the narrow phase.
    const double reach_z = radius_ + height_ / 2;
    if (state.position_m.z() - reach_z > p.z_max || state.position_m.z() + reach_z < p.z_min) continue;
    ++tested_;
    ccd_real_t depth = 0;
    ccd_vec3_t dir, pos;
    if (ccdMPRPenetration(&body, &p, &ccd, &depth, &dir, &pos) != 0) continue;
    if (!found || depth > out.depth_m) {
      out.stamp = state.stamp;
      out.position_m = Eigen::Vector3d(ccdVec3X(&pos), ccdVec3Y(&pos), ccdVec3Z(&pos));
      out.depth_m = depth;
      out.piece = piece;
      out.line = p.line;
      found = true;
    }
  }
  return found;
}

}  // namespace kestrel::sim
