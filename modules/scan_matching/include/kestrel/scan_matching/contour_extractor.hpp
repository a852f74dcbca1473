#pragma once
// Contour extraction, paper 000 section 5.1.1. The environment's shape is modelled as polyline
// contours. Every return starts as a one-point contour; candidate joins between the endpoints
// of nearby points (up to join_beam_window apart in scan order) are scored by their length and
// kept in a MinHeap; the shortest join is taken first, provided both points are still contour
// endpoints and lie on different contours (no loops, no branches). Because nearby points are
// joined first and a join may skip over points in between, a partially transparent surface
// (a railing whose posts alternate with returns from the wall behind) stays one contour while
// the wall behind forms its own. Joins longer than a few beam spacings at the points' range
// are refused: depth discontinuities never become surfaces.
#include <array>
#include <cstdint>

#include "kestrel/core/min_heap.hpp"
#include "kestrel/scan_matching/params.hpp"
#include "kestrel/scan_matching/scan_points.hpp"

namespace kestrel::scan_matching {

inline constexpr std::size_t kMaxJoinWindow = 8;

// The result: segments between point indices. A point with no segment is a one-point contour
// (drawn as a dot).
struct Contours {
  std::array<uint16_t, kMaxPoints> seg_a{};
  std::array<uint16_t, kMaxPoints> seg_b{};
  std::array<uint8_t, kMaxPoints> degree{};     // 0: isolated point, 1: endpoint, 2: interior
  std::array<uint16_t, kMaxPoints> contour{};   // contour id of each point (its root point)
  uint16_t segment_count = 0;
  uint16_t point_count = 0;
  uint16_t contour_count = 0;
};

class ContourExtractor {
 public:
  explicit ContourExtractor(const Params& p) : params_(p) {}
  void set_params(const Params& p) { params_ = p; }
  void extract(const ScanPoints& pts, Contours& out);

 private:
  uint16_t find(uint16_t i);
  bool may_join(const ScanPoints& pts, uint16_t i, uint16_t j, int32_t& key_01mm) const;

  Params params_;
  MinHeap<int32_t, kMaxPoints * kMaxJoinWindow> heap_;
  std::array<uint16_t, kMaxPoints> parent_{};
};

}  // namespace kestrel::scan_matching
