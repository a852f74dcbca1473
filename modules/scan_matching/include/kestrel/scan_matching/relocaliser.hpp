#pragma once
// Finds the vehicle again against a few remembered scans, over a window far wider than the
// scan matcher's: where the estimate has drifted metres (up to 4.5) from the frame the scans were
// taken in, and nothing else the vehicle carries still holds that frame. The vehicle remembers
// its take-off scan and a few from its first minute near home, when the estimate had not yet
// drifted, and, flying home after a long exploration, asks where it stands relative to them
// (autonomy_stack.hpp): the compact SLAM cannot tell, its corrections are held to half a metre
// and its map near home has taken in the drift of every later pass. One scan is not enough: a
// 240 degree laser at take-off never saw the wall behind it, which is what the vehicle sees
// when it comes home facing the other way.
//
// The reference scans' contours (paper 000, 5.1.1) are drawn into a likelihood map of coarse
// cells centred on the first one, and a scan is searched against it by the correlative
// search's branch and bound (5.1.2) over +-window_m and +-window_rad around the caller's guess.
// A fix is handed back only when all of these hold:
//   - the scan fits: its mean cell over the points the map can judge is min_score or more, on
//     min_points points or more (4 m of laser seeing a wall the take-off scan did not see
//     fits nothing, and is refused);
//   - it fits clearly better than at the guess (min_gain): a flat optimum leaves the guess;
//   - it is unambiguous: at the best rotation, no translation of the window farther than
//     exclusion_m from the best scores max_second_ratio of it or more. Along a corridor, or
//     facing a plain wall, or between two alike doors, the search cannot tell which, and then
//     it does not say. The rival is found by branch and bound at that rotation
//     (CorrelativeSearch::best_outside), as wide as the search (kMaxWindowCells);
//   - it does not see through the reference's walls: placed at the best pose, at most
//     max_see_through of the scan's beams pass a wall the reference drew (a cell of
//     wall_level or more) short of their return by see_through_margin_m, or, for a beam that
//     found nothing within the laser's reach (range_code::kNoReturn), short of that reach. The
//     likelihood rewards returns on walls and is blind to rays through them: from a room beside
//     home, one metre past the corridor's wall, a scan fits the corridor 2 m away as well as
//     where it was taken, save that the room's open side, where the laser found nothing,
//     lies beyond the corridor's far wall. Without the raw scan, only returns are walked;
//   - nor puts walls where the reference saw through: placed at the best pose, at most
//     max_returns_in_free of the returns it is judged on fall in cells a reference beam
//     crossed (up to see_through_margin_m short of its return, or of the laser's reach for a
//     beam that found nothing) and no reference wall lies near (the map's kernel is zero there). The mirror of
//     the test above: in iarc-arena, a room beside home, a wall 1.5 m ahead, fits the hallway's
//     end as well as home does, save that the hallway's wall there is a glass window the
//     reference's beams passed through.
//
// No heap: the map (0.8 MiB with its pyramid) and the search are inside the object, allocated once.
#include <bitset>
#include <cstdint>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/se2.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/scan_matching/contour_extractor.hpp"
#include "kestrel/scan_matching/correlative_search.hpp"
#include "kestrel/scan_matching/likelihood_map.hpp"
#include "kestrel/scan_matching/params.hpp"
#include "kestrel/scan_matching/scan_points.hpp"

namespace kestrel::scan_matching {

// 768 cells of 4 cm: 30.7 m, so that a 4 m laser 4 m from the reference, searched +-4.5 m,
// keeps its points inside the map (2 x (4 + 4 + 4.5) m = 25 m, and the kernel's margin).
inline constexpr int kRelocaliserMapDim = 768;
inline constexpr std::size_t kMaxReferenceScans = 6;

struct RelocaliserParams {
  float resolution_m = 0.04f;    // map cell and translation step
  float sigma_m = 0.04f;         // likelihood falls to 0 at 3 sigma from a contour
  float angle_step_rad = 0.01f;  // 4 cm at 4 m
  float window_m = 4.5f;         // translation half-window around the guess
  float window_rad = 0.3f;       // rotation half-window
  float min_score = 0.35f;       // mean cell / kCellMax of the best pose
  uint16_t min_points = 60;      // points the map judges at the best pose
  float min_gain = 0.2f;         // the best scores (1 + min_gain) x the guess's, or more
  float exclusion_m = 0.5f;      // the second peak is sought beyond this from the best
  float max_second_ratio = 0.85f;
  float max_see_through = 0.05f;     // beams through a reference wall, of those judged
  float see_through_margin_m = 0.3f; // a beam is walked to this short of its return
  float wall_level = 0.75f;          // a cell this much of kCellMax is on a wall (1 sigma)
  float max_returns_in_free = 0.05f; // returns where a reference beam passed, of those judged
};

// kInvalidArgument: a value out of range, or a window the map and search cannot hold.
Status validate(const RelocaliserParams& p);

enum class RelocaliseOutcome : uint8_t {
  kFixed,        // `pose` is where the scan was taken, in the reference's frame
  kNoReference,  // add_reference() has not succeeded
  kBadInput,     // guess not finite, or too far from the reference for the map
  kNoFit,        // best pose under min_score or min_points
  kNoGain,       // best pose not min_gain better than the guess
  kAmbiguous,    // a second peak max_second_ratio as high
  kSeesThrough,  // at the best pose, beams pass through the reference's walls
  kReturnsInFree,  // at the best pose, returns lie where the reference's beams passed
};

struct Relocalisation {
  RelocaliseOutcome outcome = RelocaliseOutcome::kNoReference;
  Pose2 pose;              // the fix when kFixed, otherwise the guess
  float score = 0;         // best pose's mean cell / kCellMax
  float guess_score = 0;   // the guess's
  float second_ratio = 0;  // second peak / best
  float see_through = 0;   // beams through a reference wall at the best pose, of those judged
  float returns_in_free = 0;  // returns where a reference beam passed, at the best pose, of those judged
  uint16_t points = 0;     // points judged at the best pose
  bool fixed() const { return outcome == RelocaliseOutcome::kFixed; }
};

class Relocaliser {
 public:
  Relocaliser() : extractor_(Params{}) {}
  Relocaliser(const Relocaliser&) = delete;
  Relocaliser& operator=(const Relocaliser&) = delete;

  // `matcher` supplies the contour joins and the laser's reach (the vehicle's scan matcher's);
  // forgets the reference.
  Status configure(const RelocaliserParams& p, const Params& matcher);
  // Draws one more reference scan: its returns (sensor frame) and the sensor's pose when it was
  // taken. The first centres the map. kInvalidArgument for a pose that is not finite or (after
  // the first) more than half the map from the first, or a point that is not finite;
  // kNoData for fewer than min_points returns, kCapacityExceeded after kMaxReferenceScans.
  // `scan`, the laser scan the points came from (optional), marks the space its beams that
  // found nothing crossed as seen free too (without it, only the beams to returns).
  Status add_reference(const ScanPoints& pts, const Pose2& pose, const LaserScan* scan = nullptr);
  // Where `pts` was taken, searched around `guess` (both in the reference's frame). `scan`,
  // the laser scan the points came from (optional), lets the beams that found nothing be
  // walked for the see-through check too.
  Relocalisation locate(const ScanPoints& pts, const Pose2& guess, const LaserScan* scan = nullptr);

  bool has_reference() const { return reference_count_ > 0; }
  std::size_t reference_count() const { return reference_count_; }
  const Pose2& reference_pose() const { return reference_pose_; }
  // Whether a reference beam crossed the cell holding this world point (false off the map).
  bool seen_free(float x_m, float y_m) const;
  const RelocaliserParams& params() const { return params_; }
  const LikelihoodMap& map() const { return map_; }

 private:
  // Within half the map of the first reference: what the map and the integer walks can hold.
  bool within_map(const Pose2& pose) const;
  float second_peak_ratio(const GridPose& best);
  float see_through_fraction(const ScanPoints& pts, const LaserScan* scan, const Pose2& pose) const;
  bool passes_a_wall(const Pose2& ray, float reach_m) const;
  // The map's cells: whether (x, y) is one, its index in seen_free_, the cell of a world point.
  bool on_map(int x, int y) const;
  std::size_t cell_index(int x, int y) const;
  bool cell_of(float x_m, float y_m, int& x, int& y) const;
  void mark_seen_free(const ScanPoints& pts, const LaserScan* scan, const Pose2& pose);
  float returns_in_free_fraction(const GridPose& best);
  // Calls each beam of the scan (or, without it, each point) with its ray (where the sensor was
  // when the beam was taken, heading along the beam, world frame: the points' deskew followed)
  // and how far to walk it: see_through_margin_m short of its return, or of the laser's reach.
  template <typename Beam>
  void for_each_beam(const ScanPoints& pts, const LaserScan* scan, const Pose2& pose, Beam beam) const;

  RelocaliserParams params_;
  Params matcher_;
  LikelihoodMapStorage<kRelocaliserMapDim, kMaxPoints * kMaxReferenceScans> map_;
  // The map's cells a reference beam crossed (72 KiB): std::bitset holds them in place.
  std::bitset<static_cast<std::size_t>(kRelocaliserMapDim) * kRelocaliserMapDim> seen_free_;
  ContourExtractor extractor_;
  Contours contours_;
  CorrelativeSearch search_;
  Pose2 reference_pose_;
  std::size_t reference_count_ = 0;
};

}  // namespace kestrel::scan_matching
