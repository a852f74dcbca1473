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
// hit lies inside the current cell. Floor (z = 0) and ceiling returns end the walk early, and
// so does the top (bottom) face of an obstacle whose footprint the beam starts over (under):
// the vehicle over a table, whose deflected altimeter beams meet the table top (paper 000);
// FacesOverStart::kMissed keeps the simulator's older model, in which such a beam missed them.
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

// Whether a beam starting over (under) an obstacle's footprint meets its top (bottom) face
// (SimConfig::laser_sees_tops_from_above): kMet is the world as it is, the default; kMissed, the
// model the README's exploration figures were flown with until session 58, reads the floor under
// a vehicle over a table.
enum class FacesOverStart : uint8_t { kMissed, kMet };

class RayCaster {
 public:
  explicit RayCaster(const World& world, double cell_m = 1.0,
                     WallSurfaces walls = WallSurfaces::kCentreLines,
                     FacesOverStart faces_over_start = FacesOverStart::kMet);

  // `dir` need not be unit length. `railing_rng` decides railing returns; with nullptr a
  // railing returns when its probability is >= 0.5 (deterministic tests and the renderer).
  RayHit cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double max_range_m,
              Rng* railing_rng = nullptr);

  const SegmentGrid& grid() const { return grid_; }
  double ceiling_m() const { return ceiling_; }

 private:
  // A World obstacle's footprint and what a beam meets on its top and bottom faces.
  struct Footprint {
    std::vector<Eigen::Vector2d> polygon;
    Eigen::Vector2d lo, hi;  // the polygon's bounding box
    double z_min = 0, z_max = 0;
    Material material = Material::kOpaque;
    double return_probability = 1;
    int segment = -1;  // its first edge in grid_.segments(): a face hit's RayHit::segment
  };
  // The nearest face met by a beam starting over (under) a footprint and descending (climbing)
  // to its top (bottom) while still over it, as a 3D length along the unit `dir`; infinity if
  // none. Fills `face` with the hit (kind kSurface) when there is one.
  double face_over_start(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, Rng* railing_rng,
                         RayHit& face) const;

  SegmentGrid grid_;
  std::vector<Footprint> footprints_;                    // World::obstacles, in order
  std::vector<std::vector<uint32_t>> footprints_by_cell_;  // per grid cell: footprints whose box overlaps it
  double ceiling_;
  FacesOverStart faces_over_start_;
  std::vector<uint32_t> seen_;
  uint32_t stamp_ = 0;
};

}  // namespace kestrel::sim
