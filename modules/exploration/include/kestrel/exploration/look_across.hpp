#pragma once
// Turns the heading across an axis the scan matcher cannot measure. Along a wall that is all
// the laser reaches (a 30 m hallway, a 15 m room, with the URG-04LX's 4 m), the match is
// degenerate: nothing ties the position along the wall, and an error in the filter's velocity
// along it persists and grows unseen (traced: 18 m in 50 s, hovering in place while facing
// west, the door that would have pinned it 1.6 m behind, in the laser's blind arc). Facing
// across that axis puts both directions along it inside the laser's 240 degree field (at
// +-90 degrees), so whatever lies within reach either way (a door's jamb, a room's end wall)
// comes into view. Paper 002 points the heading at the waypoint; this changes only which
// way the laser looks, never the velocity, and of the two headings across the axis takes the
// one nearer the waypoint's (kept up to 110 degrees off it), so the direction flown stays
// inside the laser's field (120 degrees either side).
// Not in the papers (modules/exploration/EXPERIMENTS.md).
#include <cstdint>

#include "kestrel/core/time.hpp"
#include "kestrel/exploration/params.hpp"

namespace kestrel::exploration {

// The newest scan match's constraint, in the navigation frame (from the autonomy stack).
struct MatchConstraint {
  TimeUs stamp;
  bool degenerate = false;  // long thin translation ellipse: the position along it is unknown
  float flat_axis_rad = 0;  // the ellipse's major axis (either sense)
  bool usable = false;      // the match measured something (not lost)
};

class LookAcross {
 public:
  // A pause in the matches longer than this starts a degenerate spell over: two matches 30 s
  // apart are no spell of 30 s.
  static constexpr int64_t kMaxGapUs = 500000;
  // Keep the side already turned to until the other is this much nearer the target: along a
  // corridor both sides are about 90 degrees off it, and each swap is a half turn.
  static constexpr float kSideHysteresisRad = 0.35f;

  // Takes parameters that validate() (Params::validate checks them).
  void configure(const LookAcrossParams& p);
  void reset();
  // The newest match; stamps that do not advance are ignored. A lost match (not usable) or a
  // degenerate one without a finite axis ends a degenerate spell and counts towards the
  // release like a clear one: it cannot tell which way to look.
  void note(const MatchConstraint& m);
  // The heading to fly: `target` unless looking across, then a heading across the flat axis:
  // the side nearer `target`, kept while within 90 degrees plus kSideHysteresisRad of it.
  float heading(float target_rad);
  bool active() const { return active_; }
  uint32_t looks() const { return looks_; }  // times it turned across, since reset

 private:
  int64_t after_us_ = 0;  // 0: off
  int64_t release_us_ = 0;
  TimeUs last_{};
  TimeUs degenerate_since_{};
  TimeUs clear_since_{};
  float axis_rad_ = 0;
  float side_ = 0;  // +1: axis + 90 degrees, -1: axis - 90 degrees, 0: none chosen yet
  bool have_last_ = false;
  bool degenerate_ = false;
  bool active_ = false;
  uint32_t looks_ = 0;
};

}  // namespace kestrel::exploration
