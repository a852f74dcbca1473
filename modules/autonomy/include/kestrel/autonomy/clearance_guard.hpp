#pragma once
// Clearance over what the altimeter finds under the vehicle: what AutonomyStack does to the
// mission's altitude set-point exploring and flying home (not on a waypoint's height, which is
// the operator's and must be arrived at), on its own so that it can be tested without the loop.
//
// Why: the laser sees only its own plane (paper 000 section 3.3), so furniture whose top lies
// between the body's underside and that plane is invisible until the vehicle is over it, when
// the altimeter reads its top and the filter places the floor there (EkfParams'
// altitude_relock_s: a floor step). At 1.0 m over gt-building's 0.9 m box a level body clears
// the top by 4 cm, which a pitch of a few degrees and a centimetre of height error use up: the
// simulated flights touched it with the rim behind them, after the altimeter had found it.
// So a floor that comes within min_clearance_m of the set-point raises the set-point to keep
// that clearance (by at most max_rise_m: nothing sees the ceiling), and keeps it raised hold_s
// after the floor falls again, because the body is wider than the altimeter's spot and its rim
// is still over the box when the spot has left it.
//
// The filter places the floor only when a run of readings is decided (altitude_relock_s, 0.4 s
// or more); meanwhile it refuses the readings, and its height, on the IMU alone, drifts: at the
// URG-04LX's 10 Hz, gt-building flights sank 2.5 cm in that half second over the 0.9 m box and
// touched it with the rim behind (7 of 20 flights' contacts in 150; none with the newest reading
// counted, session 59, nor with the weighed floor, session 60: modules/exploration/EXPERIMENTS.md).
// So the floor the filter is weighing (NavFilter::weighed_floor_m: a run of readings that jumped
// and agree, the floor its newest shows) counts from the run's second reading, where it lies over
// the placed one (floor_under).
//
// It acts only where a floor lies above the take-off floor (the filter places one only with its
// runs of rejected heights on: EkfParams::altitude_relock_s > 0, the default; in the simulator,
// with obstacle tops seen from above, its default too); on the take-off floor the flight altitude
// is the operator's whatever the clearance. It cannot help before the altimeter is over the
// obstacle: a body rim that meets it first is the operator's flight altitude to choose (mission
// argument altitude_m). Home, checked at the flight altitude in 3D, is not arrived at while a
// rise is held (at most hold_s after the vehicle leaves a raised floor).
//
// No heap, no exceptions: the height kept, when it was last wanted and whether it raised the
// set-point are the only state (and a count of rises, for the flight's counters).
#include <cstdint>
#include <limits>
#include <optional>

#include "kestrel/core/messages.hpp"
#include "kestrel/core/status.hpp"
#include "kestrel/core/time.hpp"

namespace kestrel::autonomy {

struct ClearanceParams {
  // The altimeter's height over what is under it, at least; 0 turns the guard off. 0.25 m:
  // over gt-building's 0.75 m desks a 1.0 m flight is not raised, over its 0.9 m box by 0.15 m.
  float min_clearance_m = 0.25f;
  float max_rise_m = 0.5f;  // above the mission's set-point, at most
  float hold_s = 2.0f;      // the height kept stands this long after it was last wanted
};

Status validate(const ClearanceParams& p);

class ClearanceGuard {
 public:
  explicit ClearanceGuard(const ClearanceParams& p = {}) : params_(p) {}

  // One guidance cycle. `floor_m` is the floor under the altimeter above the take-off floor
  // (floor_under()); `in_flight` says the set-point's height is the flight altitude
  // (false: taking off, landing, on the ground; the rise is dropped and nothing changes). The
  // set-point's height, in either mode, is raised by rise_m().
  void apply(TimeUs now, float floor_m, bool in_flight, GuidanceSetpoint& setpoint);
  float rise_m() const { return rise_m_; }
  // How many times a height was kept that raised the set-point: once per raised floor (or
  // floors within one another's hold), however many cycles a set-point already higher (the
  // mission's own, the cycle it turns home) interrupts the rise; after the hold, a height kept
  // anew that raises nothing ends it.
  uint32_t rises() const { return rises_; }

  // The floor for apply(): the filter's placed one (NavFilter::floor_m()), or the one it is
  // weighing (NavFilter::weighed_floor_m()) where that lies higher. A floor not finite is
  // passed over for the other.
  static float floor_under(float placed_floor_m, std::optional<float> weighed_floor_m);

 private:
  static constexpr float kNothingUnder = -std::numeric_limits<float>::infinity();

  ClearanceParams params_;
  float kept_above_m_ = kNothingUnder;  // the set-point's least height: a raised floor's plus the clearance
  TimeUs wanted_at_;                    // when it was last wanted
  float rise_m_ = 0.0f;                 // this cycle's
  bool raised_for_kept_ = false;        // the height kept has raised the set-point
  uint32_t rises_ = 0;
};

}  // namespace kestrel::autonomy
