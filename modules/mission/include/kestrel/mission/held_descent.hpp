#pragma once
// Touchdown on something the altimeter does not see: a landing held up. The altimeter reads the
// floor under one spot; resting on a rim or a step with that spot over the lower floor, it says
// airborne for as long as the motors run (TouchdownSense), and the estimate, holding the rim's
// height, never comes under the landed height either. The mission's descent would wait for
// ever, the motors spinning over whatever holds the vehicle. A desk under a UTM-30LX, whose
// deflected beams fall silent 0.02 m up, with the estimate's height right, is the same.
//
// What tells it: the height set-point well under the estimated height while that height stays
// still. A vehicle flying on a live estimate does not stay so: 0.3 m over its set-point the
// controller asks for about 5 m/s^2 downwards (the default LQR's 0.86 of thrust per metre, as
// kestrel-sysid prints it; the simulated vehicle's 19.6 m/s^2 per unit of thrust). Only
// something under it, a snag, or an estimate that no longer follows the vehicle holds it
// there, as a land detector's "no vertical movement while the thrust asks for descent".
// Against the last two: the estimate must be a new one each step (a state that stops advancing
// says nothing of the vehicle), and the altimeter, while it reads, must read the same height
// too (in the air, under a frozen estimate, its readings move; on a rim they do not).
//
// held(): for kHeldS of steps, every one with the set-point at least kGapM under the estimated
// height, the vertical speed under kStillSpeedMps, and the heights (and the readings, while
// there are any) within kStillM of one another. A step that breaks any of it, or that gives no
// finite value, starts the wait again.
#include <optional>

#include "kestrel/core/time.hpp"
#include "kestrel/mission/mission_step.hpp"
#include "kestrel/mission/still_band.hpp"

namespace kestrel::mission {

class HeldDescent {
 public:
  // The landing ramp aims 0.2 m under the floor, so a vehicle resting on the floor it believes
  // in stops with its set-point 0.2 m under it: that is touchdown's business (TouchdownSense,
  // or the estimate's height), not a vehicle held up.
  static constexpr float kGapM = 0.3f;
  // Still: the filter's height of a vehicle at rest wanders by millimetres; descending at the
  // landing's 0.3 m/s it moves 0.03 m in a tenth of a second.
  static constexpr float kStillM = 0.03f;
  static constexpr float kStillSpeedMps = 0.1f;
  static constexpr float kHeldS = 1.0f;

  void reset() { *this = HeldDescent{}; }
  // Each landing step with an estimate believed: the step's time (`dt_s`, counted for at most
  // kMaxStepS so that a stalled loop cannot make a second of two steps), the
  // estimate's stamp, height and vertical speed, the height set-point of this step, and the
  // altimeter's newest reading while it is recent (nullopt: none).
  void observe(float dt_s, TimeUs estimate_stamp, float height_m, float vertical_speed_mps, float setpoint_z_m,
               std::optional<float> reading_m);
  // A step with no estimate believed: it says nothing of what the vehicle did.
  void interrupt() { in_run_ = false; }
  bool held() const { return in_run_ && run_ >= Duration::from_s(kHeldS); }

 private:
  bool in_run_ = false;
  Duration run_;                          // the steps' time since the run's first step
  std::optional<TimeUs> newest_stamp_;    // of the estimates observed
  StillBand heights_{kStillM};
  StillBand readings_{kStillM};
};

}  // namespace kestrel::mission
