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
    : grid_(grid), radius_(body_radius_m), height_(body_height_m), ceiling_m_(world.ceiling_m) {
  for (const Wall& w : world.walls) {
    const std::array<Eigen::Vector2d, 4> box = wall_outline(w, world.wall_thickness_m);
    Prism p;
    p.polygon.assign(box.begin(), box.end());
    p.z_min = w.z_min;
    p.z_max = w.z_max;
    p.line = w.line;
    pieces_.push_back(std::move(p));
  }
  for (const Obstacle& o : world.obstacles) pieces_.push_back({o.polygon, o.z_min, o.z_max, o.line});
  reach_ = std::hypot(radius_, height_ / 2);
  // Cell lists of every piece's bounding box (two passes: count, then fill).
  const std::size_t ncell = static_cast<std::size_t>(grid_.nx()) * grid_.ny();
  auto for_cells = [&](const Prism& p, auto&& f) {
    Eigen::Vector2d lo = p.polygon[0], hi = p.polygon[0];
    for (const auto& q : p.polygon) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const int x0 = std::max(0, grid_.cell_x(lo.x())), x1 = std::min(grid_.nx() - 1, grid_.cell_x(hi.x()));
    const int y0 = std::max(0, grid_.cell_y(lo.y())), y1 = std::min(grid_.ny() - 1, grid_.cell_y(hi.y()));
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) f(static_cast<std::size_t>(iy) * grid_.nx() + ix);
  };
  std::vector<uint32_t> count(ncell + 1, 0);
  for (const Prism& p : pieces_) for_cells(p, [&](std::size_t c) { ++count[c + 1]; });
  cell_start_.assign(ncell + 1, 0);
  for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] = cell_start_[c] + count[c + 1];
  cell_pieces_.assign(cell_start_[ncell], 0);
  std::vector<uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < pieces_.size(); ++i)
    for_cells(pieces_[i], [&](std::size_t c) { cell_pieces_[fill[c]++] = static_cast<int>(i); });
  seen_pieces_.assign(pieces_.size(), 0);
  candidates_.reserve(pieces_.size());  // never grows in flight
}

bool CollisionChecker::check(const VehicleState& state, Contact& out) {
  if (++stamp_ == 0) {
    std::fill(seen_pieces_.begin(), seen_pieces_.end(), 0);
    stamp_ = 1;
  }
  const Eigen::Vector2d c(state.position_m.x(), state.position_m.y());
  candidates_.clear();
  if (!c.allFinite()) return false;
  if (ceiling_m_ > 0 && std::isfinite(state.position_m.z())) {
    // The cylinder's highest point: its axis tilted by the attitude, its rim raised by the tilt.
    const double up = std::clamp(state.rotation()(2, 2), -1.0, 1.0);
    const double top = state.position_m.z() + std::fabs(up) * height_ / 2 + std::sqrt(1 - up * up) * radius_;
    if (top >= ceiling_m_) {
      out.stamp = state.stamp;
      out.position_m = Eigen::Vector3d(c.x(), c.y(), ceiling_m_);
      out.depth_m = top - ceiling_m_;
      out.piece = kCeilingPiece;
      out.line = 0;
      return true;
    }
  }
  const int x0 = std::max(0, grid_.cell_x(c.x() - reach_)), x1 = std::min(grid_.nx() - 1, grid_.cell_x(c.x() + reach_));
  const int y0 = std::max(0, grid_.cell_y(c.y() - reach_)), y1 = std::min(grid_.ny() - 1, grid_.cell_y(c.y() + reach_));
  for (int iy = y0; iy <= y1; ++iy)
    for (int ix = x0; ix <= x1; ++ix) {
      const std::size_t cell = static_cast<std::size_t>(iy) * grid_.nx() + ix;
      for (uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
        const int piece = cell_pieces_[k];
        if (seen_pieces_[static_cast<std::size_t>(piece)] == stamp_) continue;
        seen_pieces_[static_cast<std::size_t>(piece)] = stamp_;
        candidates_.push_back(piece);
      }
    }
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
