#pragma once
// SRT-Star perception, paper 002 section IV after Freda and Oriolo (ICRA 2005): the scan is
// divided into equal angular sectors. A sector's radius is its nearest return (at most the
// perception range R_p): the circular sector of that radius is obstacle-free, and the union of
// the sectors is the star-shaped Local Safe Region of the waypoint. Each sector has a left, a
// mid and a right point (Fig. 3): the mid-point is a frontier when the whole sector is
// obstacle-free (no return within R_p); the left or right point is a frontier when the sector
// reaches much farther than its neighbour on that side (a range discontinuity: a doorway, the
// end of a wall).
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
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/static_vector.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/exploration/params.hpp"

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

 private:
  void erode(const LaserScan& scan, const SrtParams& params, uint16_t rp_mm);

  std::array<uint16_t, kMaxSectors> radius_mm_{};
  std::array<uint16_t, kMaxSectors * kRaysPerSector> clear_mm_{};
  std::array<bool, kMaxSectors> free_{};
  StaticVector<LocalFrontier, kMaxLocalFrontiers> frontiers_;
  float start_rad_ = 0;
  float width_rad_ = 0;
  uint16_t count_ = 0;
};

}  // namespace kestrel::exploration
