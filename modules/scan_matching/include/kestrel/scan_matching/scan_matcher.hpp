#pragma once
// The high-speed correlative scan matcher of paper 000, section 5.1: each scan is aligned by
// exhaustive (or provably equivalent branch-and-bound) search against a likelihood map drawn
// from the contours of the last k key scans (5.1.1, 5.1.2), in a window centred on a
// constant-velocity prediction and sized from the vehicle's maximum acceleration and the time
// since the last scan; the pose comes with a covariance read off the pose likelihood (5.1.3).
// A scan joins the local map only when too few of its points fit it, so a hovering vehicle
// keeps its map and does not drift.
//
// Steps per scan: validate -> points -> predict and size the window -> search -> covariance
// and sub-cell refinement -> overlap test (maybe submit a key scan) -> output.
#include <array>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/scan_matching/correlative_search.hpp"
#include "kestrel/scan_matching/covariance_estimator.hpp"
#include "kestrel/scan_matching/local_map.hpp"

namespace kestrel::scan_matching {

// Bits of PoseMeasurement2::flags set by the scan matcher.
namespace match_flag {
inline constexpr uint32_t kRejected = 1u << 0;       // no pose: see the reason bits below
inline constexpr uint32_t kTooFewPoints = 1u << 1;   // all no-return, all max range, one beam...
inline constexpr uint32_t kTimeBackwards = 1u << 2;  // stamp older than the previous scan's
inline constexpr uint32_t kBadGeometry = 1u << 3;    // non-finite or zero angles, bad beam count
inline constexpr uint32_t kNoMap = 1u << 4;          // no local map published yet (async mode)
inline constexpr uint32_t kLost = 1u << 5;           // best score too low: pose is the prediction
inline constexpr uint32_t kDegenerate = 1u << 6;     // long thin translation ellipse (corridor)
inline constexpr uint32_t kKeyScan = 1u << 7;        // the scan was submitted to the local map
inline constexpr uint32_t kFirstScan = 1u << 8;      // started the map; pose is the initial pose
inline constexpr uint32_t kWindowClamped = 1u << 9;  // the window hit its static capacity
inline constexpr uint32_t kMapRestarted = 1u << 10;  // lost too long: the map restarts here
}  // namespace match_flag

struct ScanMatch {
  PoseMeasurement2 measurement;  // stamp of the scan, pose, 3x3 covariance, flags
  float score = 0;               // mean cell value under the points / kCellMax, 0..1
  float overlap = 0;             // fraction of points on the map's likely cells
  GridPose grid;                 // the raw grid optimum
  float major_axis_rad = 0;      // translation ellipse orientation
  float axis_ratio = 1;
  uint16_t points = 0;
  bool ok() const { return (measurement.flags & match_flag::kRejected) == 0; }
};

// A pose the caller's filter predicts for the scan's stamp, and how far off it may be.
struct PosePrior {
  Pose2 pose;
  float position_std_m = -1;  // 1 sigma; negative: unknown (window from max acceleration)
  float heading_std_rad = -1;
  // The vehicle's velocity (world frame) and yaw rate at the stamp, held over the laser's
  // sweep to move each beam's point to where the sensor was at the stamp (ScanMatcher::deskew).
  // Zero: the scan is taken as instantaneous.
  float vx_mps = 0, vy_mps = 0, yaw_rate_radps = 0;
};

class ScanMatcher {
 public:
  // Maps are allocated by the caller, once. synchronous: the local map is rebuilt inline
  // (replay, tests); otherwise the caller runs local_map().rebuild() in a background task.
  ScanMatcher(const Params& p, LikelihoodMap& a, LikelihoodMap& b, bool synchronous = true);

  Status configure(const Params& p, const Pose2& initial = {});
  // `prior`, when given, is the vehicle's pose at the scan's stamp as the caller's filter
  // predicts it: the search is centred there instead of on the matcher's own constant-velocity
  // prediction, which lets a match that was lost recover as soon as the scan fits again.
  // With its uncertainty, the window covers Params::prior_sigmas of it (within the window's
  // limits) instead of what maximum acceleration allows since the last scan: the filter has
  // already carried the motion, so what is left to search is the filter's own error.
  ScanMatch process(const LaserScan& scan, const PosePrior* prior = nullptr);

  LocalMap& local_map() { return local_; }
  // The newest scan's returns in the sensor frame, deskewed to its stamp when a prior was given.
  const ScanPoints& scan_points() const { return key_.points; }
  const Params& params() const { return params_; }
  CorrelativeSearch& search() { return search_; }

 private:
  bool to_points(const LaserScan& scan);
  void deskew(const LaserScan& scan, const PosePrior& prior);
  float laser_reach_m(const LaserScan& scan) const;
  void remember_key(const Pose2& pose, bool restart);
  float distance_to_nearest_key(const Pose2& p) const;
  void update_beam_table(const LaserScan& scan);

  Params params_;
  bool synchronous_;
  LocalMap local_;
  CorrelativeSearch search_;
  CovarianceEstimator cov_;
  KeyScan key_;  // the scan being matched (points in sensor frame) and its pose
  // Beam directions of the laser's geometry, computed when it changes (sin and cos per beam
  // per scan would dominate the Verdex's software floating point).
  std::array<float, kMaxBeams> beam_cos_{}, beam_sin_{};
  float table_first_rad_ = 0, table_step_rad_ = 0;
  uint16_t table_beams_ = 0;
  std::array<int32_t, 2 * 64 + 1> curve_{};
  Pose2 initial_;
  Pose2 last_pose_, prev_pose_;
  TimeUs last_stamp_, prev_stamp_;
  TimeUs last_fit_stamp_;  // newest scan that fitted the map, started it or restarted it
  TimeUs last_key_stamp_;  // newest scan submitted as a key scan
  bool last_key_at_corridor_match_ = false;  // the newest key scan's match was degenerate and truncated
  // Where the key scans submitted since the map (re)started were taken, newest first; the
  // radius is set per scan from the laser's reach.
  static_assert(kMaxKeyframes <= kMaxSeenDiscs, "every key scan has its disc");
  SeenDiscs key_discs_;
  int accepted_ = 0;
  bool started_ = false;
};

// The vehicle configuration: both map buffers in one object the caller allocates once at
// start-up. 2000 x 2000 cells of the vehicle's 1 cm cover 20 m centred on the newest key scan
// (the vehicle stays within 5 m of it), close to the most the contours' int16 sub-cell
// coordinates allow (2047): near the middle of a 15 m room its far walls, and a corridor's end
// walls within 10 m, lie inside the map, where with 10 m (1024 cells) the match said nothing
// along the room or the corridor and the filter carried that axis on the IMU (modules/
// exploration/EXPERIMENTS.md, *The local map is 20 m wide*). With the max-pooled pyramids and
// segment lists both buffers take about 10.2 MiB (we read DESIGN.md's "SLAM map <= 1 MiB" as the
// compact SLAM's map, not this one: same file). The search scores the points the map holds, so
// a UTM-30LX scan costs more than on the 10 m map; a 4 m URG-04LX costs the same.
template <int Dim, std::size_t MaxSegments>
struct ScanMatcherStorage {
  LikelihoodMapStorage<Dim, MaxSegments> map_a, map_b;
};
inline constexpr int kOnboardMapDim = 2000;
inline constexpr std::size_t kOnboardMaxSegments = 4 * kMaxBeams;
using OnboardMapStorage = ScanMatcherStorage<kOnboardMapDim, kOnboardMaxSegments>;

}  // namespace kestrel::scan_matching
