#pragma once
// Vehicle-world contacts. The vehicle is a cylinder around its rotors, tilted with its true
// attitude; every wall is a thin box (its segment thickened to World::wall_thickness_m) and
// every obstacle a prism over its convex polygon, each over its own height range. Narrow
// phase: libccd's MPR (Minkowski Portal Refinement), which also gives the depth and a contact
// point. Broad phase: a uniform grid (the ray caster's cells) listing every piece whose
// bounding box overlaps a cell, footprint interiors included, queried with the cylinder's
// bounding box, so only pieces near the vehicle are tested. The floor is not a contact
// (the vehicle lands on it); a world's ceiling is (piece kCeilingPiece): a vehicle whose
// height estimate runs away climbs into it, where without it it would fly out over the walls
// unseen and untouched.
#include <Eigen/Core>
#include <vector>

#include "kestrel/core/time.hpp"
#include "kestrel/sim/segment_grid.hpp"
#include "kestrel/sim/vehicle.hpp"
#include "kestrel/sim/world.hpp"

namespace kestrel::sim {

struct Contact {
  TimeUs stamp;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // a point of the overlap, world frame
  double depth_m = 0;                                    // penetration depth
  int piece = -1;    // World piece: walls 0..W-1, then obstacles; kCeilingPiece
  int line = 0;      // the piece's line in the world source (0 for the ceiling)
};

inline constexpr int kCeilingPiece = -2;

class CollisionChecker {
 public:
  CollisionChecker(const World& world, const SegmentGrid& grid, double body_radius_m,
                   double body_height_m);

  // The deepest contact of the body at `state`, if any: true and `out` filled.
  bool check(const VehicleState& state, Contact& out);
  std::size_t pieces_tested() const { return tested_; }

  struct Prism {
    std::vector<Eigen::Vector2d> polygon;  // convex, counter-clockwise
    double z_min = 0, z_max = 0;
    int line = 0;
  };

 private:
  const SegmentGrid& grid_;
  std::vector<Prism> pieces_;
  double radius_, height_, reach_;
  double ceiling_m_ = 0;  // World::ceiling_m: 0, none
  std::vector<uint32_t> cell_start_;  // compressed rows: pieces per grid cell
  std::vector<int> cell_pieces_;
  std::vector<uint32_t> seen_pieces_;
  uint32_t stamp_ = 0;
  std::vector<int> candidates_;
  std::size_t tested_ = 0;
};

}  // namespace kestrel::sim
