#pragma once
// How well a scan fits the compact SLAM's map at a pose, and CoreSLAM's Monte Carlo search for
// the pose where it fits best (Steux and El Hamzaoui's tinySLAM, which paper 004 modified).
//
// The fit is the mean map value under the scan's returns placed at the pose: 0 when every
// return lies on a wall drawn by earlier scans, 255 when every one lies in cleared space.
// Returns on unknown cells count as kUnknown, as in CoreSLAM. Left out of the mean instead, they
// let a scan slide until its awkward returns fall where the map knows nothing: in an 8 x 6 m
// room flown with the URG-04LX, the map took a 13 cm shift that never went away (3 cm counted). The
// search draws candidates around the best pose so far, keeps any that fits better, and halves
// its spread whenever a run of candidates brings nothing: a random descent that needs no
// gradient and whose cost is fixed by the number of candidates. Points and poses are in map
// sub-cells and the rotation in Q12, so the per-point work is integer.
#include <array>
#include <cstdint>

#include "kestrel/core/prng.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/scan_matching/scan_points.hpp"
#include "kestrel/slam/slam_map.hpp"

namespace kestrel::slam {

inline constexpr std::size_t kMaxScanPoints = scan_matching::kMaxPoints;

// A scan's returns in the sensor frame, in sub-cells of the map, thinned to a budget.
struct MapScan {
  std::array<SubPoint, kMaxScanPoints> point{};
  uint16_t count = 0;
};

// Takes every k-th return so that at most max_points remain, in sub-cells of cell_m; returns
// beyond the map's own span are dropped (they could only sample unknown cells).
void thin_to_map_scan(const scan_matching::ScanPoints& in, float cell_m, uint16_t max_points, MapScan& out);

// Where the scan's returns land in the map with the sensor at `pose`.
class ScanPlacement {
 public:
  ScanPlacement(const SlamMap& map, const Pose2& pose);
  SubPoint sensor() const { return origin_; }
  SubPoint place(SubPoint p) const {
    constexpr int kQ = 12;
    return {origin_.x + static_cast<int32_t>((int64_t{cos_q12_} * p.x - int64_t{sin_q12_} * p.y) >> kQ),
            origin_.y + static_cast<int32_t>((int64_t{sin_q12_} * p.x + int64_t{cos_q12_} * p.y) >> kQ)};
  }

 private:
  SubPoint origin_;
  int32_t cos_q12_ = 0, sin_q12_ = 0;
};

// Mean map value under the scan at `pose`, in 1/256 of a level (0 .. 65280); lower fits better.
uint32_t mean_level(const SlamMap& map, const MapScan& scan, const Pose2& pose);

// The share of the scan's returns at `pose` that land on cells the map has drawn or cleared.
float known_share(const SlamMap& map, const MapScan& scan, const Pose2& pose);

struct SearchSpread {
  float xy_m = 0.08f;
  float theta_rad = 0.03f;
};

// What a candidate pays for its distance from the start, in levels per m^2 and per rad^2, on
// top of its mean level. Where the map cannot tell poses apart (along a corridor whose ends are
// out of reach) the level is flat and a plain descent wanders with the map's noise; the anchor
// holds it at the start there, and elsewhere moves the optimum by a negligible amount (a wall's
// level rises by about 10 levels per centimetre).
struct SearchAnchor {
  float per_m2 = 0;
  float per_rad2 = 0;
};

struct FitResult {
  Pose2 pose;                // the best pose found
  uint32_t level = 0;        // its mean level (1/256)
  uint32_t cost = 0;         // its level plus the anchor's charge (1/256)
  uint32_t prior_level = 0;  // the starting pose's (no charge there)
};

// `iterations` candidates around the best so far, starting at `start`; the spread halves after
// each run of iterations / 5 candidates without improvement. Deterministic for a given prng.
FitResult monte_carlo_search(const SlamMap& map, const MapScan& scan, const Pose2& start, SearchSpread spread,
                             SearchAnchor anchor, uint32_t iterations, Prng& prng);

// How sharply the scan's fit rises as its pose moves from `at`, in levels per m^2, measured
// over one step `h_m` along x, y and the diagonal: the curvature along its two
// eigen-directions, the first at first_rad, the second across it. Where one is low the map
// cannot place the scan along that direction (the axis of a corridor whose ends are out of
// reach).
struct FitCurvature {
  float first_rad = 0;
  float first = 0;
  float second = 0;
  float least() const { return first < second ? first : second; }
};
FitCurvature fit_curvature(const SlamMap& map, const MapScan& scan, const Pose2& at, float h_m);

// The part of a search's move from `start` to `best` that the map supports, given the fit's
// curvature at `best`: along an eigen-direction where it is below `min_curvature` the move's
// component is undone: there the search follows the map's noise, or the pull of the unknown
// cells ahead of the drawn walls, which took a filter that held still 0.7 m back along a
// synthetic corridor.
Pose2 supported_move(const FitCurvature& at_best, const Pose2& start, const Pose2& best, float min_curvature);

}  // namespace kestrel::slam
