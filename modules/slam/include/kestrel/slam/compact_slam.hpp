#pragma once
// The compact SLAM of paper 004 (a modified CoreSLAM) as level 3 of paper 000 Figure 4: it
// keeps one map of everything the laser has seen, finds where each scan it is given fits that
// map best, starting from the filter's pose at the scan's time, and hands back that pose as a
// correction for NavFilter::apply_correction. The scan matcher's local map forgets a wall five
// key scans after it passes out of reach; this map does not, so a match that has slid along a
// wall (a corridor, a room wider than the URG-04LX's reach) is pulled back onto walls seen
// earlier.
//
// Paper 004's modification: a beam with no return clears nothing (CoreSLAM cleared its whole
// ray), which kept its map clean where the laser's critical angle is exceeded. Here a beam
// without a return never becomes a point at all (ScanPoints).
//
// A correction is handed back only when the scan fits the map well at the new pose (its mean
// map value under max_fit_level: its returns on drawn walls) and clearly better than at the
// filter's pose (by min_gain_level): along a corridor whose ends are out of reach the fit is
// flat, and the search's anchor (SearchAnchor) holds it at the filter's pose. A scan is drawn
// where it fits best, as CoreSLAM draws it, whether or not the filter is corrected (drawn at
// the filter's pose, a slow drift below the correction threshold would bend the map with it),
// but only once the sensor has moved draw_every_m or turned draw_every_rad since the last scan
// drawn: drawn ten times a second, the walls took the pose of the last second, the map followed
// the filter instead of holding it, and two copies of a wall made the search snap between them.
// draw_min_curvature (off by default) draws only where the map's walls pin the fit both ways;
// flown, it starved the SLAM of corrections (modules/exploration/EXPERIMENTS.md).
//
// No heap: the map is the caller's (1 MiB, allocated once); everything else is inside.
#include <cstdint>

#include "kestrel/core/prng.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/scan_matching/scan_points.hpp"
#include "kestrel/slam/scan_fit.hpp"
#include "kestrel/slam/slam_map.hpp"
#include "kestrel/slam/slam_params.hpp"

namespace kestrel::slam {

namespace slam_flag {
inline constexpr uint32_t kStarted = 1u << 0;       // the first scan: the map starts at its pose
inline constexpr uint32_t kDrawn = 1u << 1;         // the scan was drawn into the map
inline constexpr uint32_t kMatched = 1u << 2;       // the search ran
inline constexpr uint32_t kCorrected = 1u << 3;     // `pose` is a correction for the filter
inline constexpr uint32_t kWarmingUp = 1u << 4;     // too early to correct: drawn at the prior
inline constexpr uint32_t kTooFewPoints = 1u << 5;  // neither matched nor drawn
inline constexpr uint32_t kNotFinite = 1u << 6;     // the prior is not finite: ignored
inline constexpr uint32_t kNoFit = 1u << 7;         // best fit above max_fit_level
inline constexpr uint32_t kNoGain = 1u << 8;        // not min_gain_level better than the prior
inline constexpr uint32_t kTooFar = 1u << 9;        // the correction exceeds its limits
inline constexpr uint32_t kUnpinned = 1u << 10;     // due to be drawn, but the map does not pin
                                                    // the fit both ways (draw_min_curvature)
}  // namespace slam_flag

struct SlamResult {
  Pose2 pose;               // the correction when kCorrected; otherwise the prior (the scan
                            // is drawn at the best fit unless kTooFar)
  Pose2 fit;                // the search's best pose after supported_move, whether handed back
                            // or refused (kMatched); otherwise the prior
  float level = 0;          // the best fit's mean map value (0 wall .. 255 free)
  float prior_level = 0;    // the prior's
  uint16_t points = 0;      // returns used
  uint32_t flags = 0;
  bool corrected() const { return (flags & slam_flag::kCorrected) != 0; }
};

// Written by process() only (level 3); read them once it is idle, or at the end of a run.
struct SlamCounters {
  uint32_t scans = 0;           // with enough points: started, warmed up or matched
  uint32_t corrections = 0;     // handed back (kCorrected)
  uint32_t no_fit = 0;          // matched, refused: kNoFit, kNoGain or kTooFar
  uint32_t no_gain = 0;
  uint32_t too_far = 0;
  uint32_t too_few_points = 0;  // neither matched nor drawn
  uint32_t drawn = 0;           // drawn into the map (kDrawn), the first scan included
  uint32_t unpinned = 0;        // due to be drawn and not, the map not pinning them (kUnpinned)
};

class CompactSlam {
 public:
  explicit CompactSlam(SlamMap& map) : map_(map) {}

  // Checks and takes the parameters and forgets the map: the next scan starts it again.
  Status configure(const SlamParams& p);
  // One scan: its returns in the sensor frame (deskewed to its stamp) and the filter's pose of
  // the sensor at that stamp, in the world frame.
  SlamResult process(const scan_matching::ScanPoints& points, const Pose2& prior);

  const SlamMap& map() const { return map_; }
  // The newest scan's returns as process() thinned them (diagnostics: its fit elsewhere,
  // mean_level()).
  const MapScan& last_scan() const { return scan_; }
  const SlamParams& params() const { return params_; }
  const SlamCounters& counters() const { return counters_; }
  bool started() const { return started_; }

 private:
  void draw(const Pose2& pose);
  bool due_to_draw(const Pose2& pose) const;
  bool within_limits(const Pose2& prior, const Pose2& pose) const;

  SlamMap& map_;
  SlamParams params_;
  SlamCounters counters_;
  MapScan scan_;
  Prng prng_{1};
  Pose2 last_drawn_;
  bool started_ = false;
};

}  // namespace kestrel::slam
