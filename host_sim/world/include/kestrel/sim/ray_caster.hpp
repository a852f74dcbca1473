#pragma once
// Casts 3D laser beams into a World. The scan plane of a 2D laser on a flying vehicle is
// tilted by its roll and pitch, so each beam is a 3D ray: it climbs or descends as it goes,
// passes over low furniture and under hanging cabinets, and may end on the floor or the
// ceiling (paper 000, section 3.3: "obstacles suddenly appear or disappear").
//
// Steps per beam: project the ray onto the floor plane; walk the uniform grid of segments
// along that projection (Amanatides-Woo DDA); intersect each listed segment exactly (2D
// line-segment intersection), keeping a hit only if the ray's height there lies inside the
// segment's [z_min, z_max]; a beam entering an obstacle's footprint above its top (or below
// its bottom) hits the top (bottom) face if it crosses that plane inside the footprint;
// glass lets the beam pass, a railing returns it with its probability; stop once the nearest
// hit lies inside the current cell. Floor (z = 0) and ceiling returns end the walk early.
// Limitation: a beam starting above an obstacle's footprint (the vehicle right over a table)
// does not see that obstacle's top.
#include <cstdint>
#include <vector>

#include "kestrel/sim/random.hpp"
#include "kestrel/sim/segment_grid.hpp"
#include "kestrel/sim/world.hpp"

namespace kestrel::sim {

struct RayHit {
  enum class Kind : uint8_t { kNone, kSurface, kFloor, kCeiling };
  Kind kind = Kind::kNone;
  double range_m = 0;  // along the 3D beam
  int segment = -1;    // for kSurface: index into RayCaster::grid().segments()
  Material material = Material::kOpaque;
};

class RayCaster {
 public:
  explicit RayCaster(const World& world, double cell_m = 1.0,
                     WallSurfaces walls = WallSurfaces::kCentreLines);

  // `dir` need not be unit length. `railing_rng` decides railing returns; with nullptr a
  // railing returns when its probability is >= 0.5 (deterministic tests and the renderer).
  RayHit cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double max_range_m,
              Rng* railing_rng = nullptr);

  const SegmentGrid& grid() const { return grid_; }
  double ceiling_m() const { return ceiling_; }

 private:
  SegmentGrid grid_;
  std::vector<std::vector<Eigen::Vector2d>> polygons_;  // World::obstacles' footprints
  double ceiling_;
  std::vector<uint32_t> seen_;
  uint32_t stamp_ = 0;
};

}  // namespace kestrel::sim
