#pragma once
// SRT-Star perception, paper 002 section IV after Freda and Oriolo (ICRA 2005): the scan is
// divided into equal angular sectors. A sector's radius is its nearest return (at most the
// perception range R_p): the circular sector of that radius is obstacle-free, and the union of
// the sectors is the star-shaped Local Safe Region of the waypoint. Each sector has a left, a
// mid and a right point (Fig. 3): the mid-point is a frontier when the whole sector is
// obstacle-free (no return within R_p); the left or right point is a frontier when the sector
// reaches much farther than its neighbour on that side (a range discontinuity: a doorway, the
// end of a wall). With SrtParams::discontinuity_needs_beam_jump (the default; not in paper 002)
// one of the two sectors must also hold an end of a range jump by that much between two
// consecutive beams: a wall seen aslant steps the sectors' radii, nearest return by nearest
// return, by more than the threshold with no gap in it (a 2 m corridor's walls, seen from inside
// it), and the point such a step makes lies on the wall, where no later safe region can cover
// it, so only flying there removes it (EXPERIMENTS.md). For the jumps a kNoReturn beam
// reads as the scan's max_range_mm (as 65.535 m when that is below kMinValidRangeMm), and
// kTooNear, kDropout and kDeflected beams are stepped over. The test is per sector: a far
// sector along a long wall, where neighbouring beams of a fine laser (the UTM-30LX's 0.25
// degrees) already differ by more than the threshold, still passes (counting only jumps whose
// nearer end is within R_p closes that, and was flown: fewer UTM-30LX flights entered every
// room, their trees running out of frontiers; modules/exploration/README.md).
//
// For motion the safe region is eroded by the vehicle's clearance rho (Freda and Oriolo account
// for the robot's size the same way): every sector holds kRaysPerSector evenly spaced rays, and a
// ray's clear distance is how far a disc of radius rho can travel along it before touching any
// return of the scan (r_i cos(phi) - sqrt(rho^2 - r_i^2 sin^2(phi)) for a return at angle phi
// off the ray and less than rho to its side), at most the sector's radius and R_p - rho.
// Waypoints are drawn along rays, within their clear distance; frontier removal uses the
// perceived radius.
//
// Beam classes: a return within R_p is an obstacle; kNoReturn or a return beyond R_p is free;
// kTooNear is an obstacle at zero range; kDropout and kDeflected say nothing, so a sector that
// holds one is not obstacle-free but its radius comes from its other beams (a sector of only
// such beams has radius zero).
#include <array>
#include <cmath>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/static_vector.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/exploration/params.hpp"
#include "kestrel/exploration/work_units.hpp"

namespace kestrel::exploration {

enum class FrontierKind : uint8_t { kMid, kLeft, kRight };
const char* to_string(FrontierKind k);

// A frontier of one scan, in the body frame of the scan.
struct LocalFrontier {
  uint8_t sector = 0;
  FrontierKind kind = FrontierKind::kMid;
  float angle_rad = 0;  // body frame
  float range_m = 0;
};

class SectorScan {
 public:
  // Sectors of `scan` with params.sector_count sectors (the count is capped by the beam count).
  // kInvalidArgument for bad params or a scan without beams or angles; the object is then empty.
  Status build(const LaserScan& scan, const SrtParams& params);

  // The same in slices, for a caller with a time budget per cycle: begin() checks the input
  // and classifies the beams into sectors (radii, obstacle-free flags); advance() builds the
  // direction tables when the geometry changed, erodes the rays beam by beam and, last, rounds
  // them and finds the frontiers, stopping once it has used `budget` work units (it finishes
  // the item it is on, so it may overrun by one beam's rays). It returns the units used.
  // Every call must get the scan begin() got. ready() once the result equals build()'s.
  Status begin(const LaserScan& scan, const SrtParams& params);
  uint32_t advance(const LaserScan& scan, uint32_t budget);
  bool ready() const { return stage_ == Stage::kReady; }

  uint16_t count() const { return count_; }
  // Sector s spans body angles [start + s * width, start + (s + 1) * width), width > 0.
  float start_rad() const { return start_rad_; }
  float width_rad() const { return width_rad_; }
  float mid_angle(uint16_t s) const { return start_rad_ + (static_cast<float>(s) + 0.5f) * width_rad_; }
  uint16_t radius_mm(uint16_t s) const { return radius_mm_[s]; }
  static constexpr uint16_t kRaysPerSector = 4;
  // Ray j (0 <= j < kRaysPerSector) of sector s and its clear distance.
  float ray_angle(uint16_t s, uint16_t j) const {
    return start_rad_ + (static_cast<float>(s) + (static_cast<float>(j) + 0.5f) / kRaysPerSector) * width_rad_;
  }
  uint16_t clear_mm(uint16_t s, uint16_t j) const { return clear_mm_[s * kRaysPerSector + j]; }
  bool obstacle_free(uint16_t s) const { return free_[s]; }
  const IVector<LocalFrontier>& frontiers() const { return frontiers_; }

  // Direction of beam i of the scan last begun, from the sectors' clockwise edge start_rad():
  // cosine and sine, valid once ready() (tabled once per laser geometry).
  float beam_cos(std::size_t i) const { return beam_cos_[beam_slot(i)]; }
  float beam_sin(std::size_t i) const { return beam_sin_[beam_slot(i)]; }
  // Whether those tables hold the beams of `scan` (a scan of the same geometry).
  bool beam_table_fits(const LaserScan& scan) const {
    return ready() && beam_table_size_ == scan.beam_count && beam_table_step_ == std::fabs(scan.angle_step_rad) &&
           ccw_ == (scan.angle_step_rad > 0.0f);
  }
  // Angle of the clockwise edge of `scan`'s field of view (start_rad() for the scan begun).
  static float start_of(const LaserScan& scan);

 private:
  enum class Stage : uint8_t { kEmpty, kRayTable, kBeamTable, kErode, kFinish, kReady };
  std::size_t beam_slot(std::size_t i) const { return ccw_ ? i : beams_ - 1 - i; }
  // One beam's erosion of the rays; returns its work units (0 for a beam too far to erode).
  uint32_t erode_beam(const LaserScan& scan, std::size_t i);
  void finish();

  std::array<uint16_t, kMaxSectors> radius_mm_{};
  std::array<uint16_t, kMaxSectors * kRaysPerSector> clear_mm_{};
  std::array<bool, kMaxSectors> free_{};
  std::array<bool, kMaxSectors> beam_jump_{};  // holds one end of a jump between neighbouring beams
  bool needs_beam_jump_ = true;
  StaticVector<LocalFrontier, kMaxLocalFrontiers> frontiers_;
  float start_rad_ = 0;
  float width_rad_ = 0;
  uint16_t count_ = 0;

  // The erosion in progress.
  Stage stage_ = Stage::kEmpty;
  std::array<float, kMaxSectors * kRaysPerSector> clear_{};  // m
  float rho_ = 0, cap_ = 0, rp_m_ = 0;
  int32_t jump_mm_ = 1;
  std::size_t beams_ = 0;
  std::size_t cursor_ = 0;  // next table entry or beam
  bool ccw_ = true;
  // Direction tables, kept while the geometry stays: ray k of the sectors at (k + 1/2) of a
  // ray width, and beam slot k at (k + 1/2) of a beam step, from start_rad_.
  std::array<float, kMaxSectors * kRaysPerSector> ray_cos_{}, ray_sin_{};
  std::array<float, kMaxBeams> beam_cos_{}, beam_sin_{};
  float ray_table_width_ = 0;  // 0: no table
  uint16_t ray_table_count_ = 0;
  float beam_table_step_ = 0;  // 0: no table
  std::size_t beam_table_size_ = 0;
};

}  // namespace kestrel::exploration
