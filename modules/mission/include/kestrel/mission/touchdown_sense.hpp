#pragma once
// Touchdown by the altimeter's word. The estimate's height is the altimeter's readings over the
// floor the filter believes is under the vehicle (NavFilter::floor_m); a floor step taken wrongly
// leaves it off by a desk's height. Landing by the estimate alone, the mission then cut the motors
// 0.66 m above the floor (iarc-arena, UTM-30LX seed 25, before the height runs' time to stay), or
// never landed on the furniture it came down on. The altimeter reads the height over whatever is
// under the vehicle, which is where it touches down.
//
// Its verdict, from the readings since reset():
//  - not down: the newest reading is recent, and over the landed height or low but neither
//    still yet nor low for kLowS;
//  - on the ground: readings under it, each within kMaxGapS of the one before, have stayed within
//    kStillM of one another for kStillS (the vehicle stopped: the filter's vertical velocity does
//    not see the stop at once, the impact being too short for its IMU, and its height runs on
//    under the floor until its readings re-lock it), and none over it since, recent or not (a
//    laser's deflected beams read nothing nearer than its minimum range: silence after the
//    vehicle was read still on the floor is the floor); or low readings, each within kLowGapS
//    of the one before, none over it, for kLowS, still or not (silence after them is the floor
//    too): a vehicle the landing ramp drives under the floor does not stay that near it for so
//    long unless it stands on it, and one rocking on its legs while a starved loop (session
//    61's TSan run: 72 ms to match a 25 ms scan) corrects it late never reads still;
//  - none (nullopt): no reading, or the newest stale: the caller then goes by the estimate. The
//    UTM-30LX, whose 0.1 m minimum range is more than its 0.08 m mount height, falls silent while
//    still descending: its landings are the estimate's.
// A reading counts once (by its stamp; one not newer than the last is ignored), and only a
// usable one: finite, its height in [kMinHeightM, kMaxHeightM]; one that is not ends a run of low
// readings. Recent: now - stamp <= max_age_s.
#include <optional>

#include "kestrel/core/messages.hpp"
#include "kestrel/mission/still_band.hpp"

namespace kestrel::mission {

class TouchdownSense {
 public:
  // Still: descending at the landing's 0.3 m/s, readings 0.1 s apart move 0.03 m. kStillS is
  // two readings of a 10 Hz altimeter (the URG-04LX's), give or take their jitter; a longer gap
  // between two readings says nothing of what the vehicle did in it.
  static constexpr float kStillM = 0.02f;
  static constexpr float kStillS = 0.09f;
  static constexpr float kMaxGapS = 0.15f;
  static constexpr float kLowS = 2.0f;
  static constexpr float kLowGapS = 0.5f;
  // On the floor a reading is the mount's height less its calibration, a few millimetres either
  // side of zero; one further under the floor than this is not a height.
  static constexpr float kMinHeightM = -0.1f;
  static constexpr float kMaxHeightM = 20.0f;

  void reset();
  // Each guidance step: the newest reading (nullptr: none), the height under which the vehicle
  // is down, and how old a reading may be to count as the present.
  void observe(TimeUs now, const AltimeterSample* newest, float landed_height_m, float max_age_s);

  std::optional<bool> on_ground() const;
  // The newest usable reading while it is recent: nullopt otherwise.
  std::optional<float> recent_height() const {
    return recent_ ? std::optional<float>(last_height_m_) : std::nullopt;
  }
  // The floor under the vehicle in the estimate's frame while the newest reading is recent and
  // says airborne: the estimated height carried back to the reading's stamp at the estimated
  // vertical speed, less the reading.
  std::optional<float> floor_under(float estimated_height_m, float vertical_speed_mps) const;

 private:
  void take(const AltimeterSample& r, float landed_height_m);

  bool counted_any_ = false;  // a reading since reset(), usable or not
  TimeUs counted_stamp_;      // of the newest such
  bool seen_ = false;         // a usable reading since reset()
  TimeUs last_stamp_;         // of the newest usable reading
  float last_height_m_ = 0;
  float age_s_ = 0;        // now - last_stamp_ at the last observe()
  bool recent_ = false;    // the newest usable reading, at the last observe()
  bool low_ = false;       // ... lay under the landed height
  // The run of low readings within kStillM of one another that ends with the newest: whether
  // there is one, its first stamp and its heights.
  bool in_run_ = false;
  TimeUs still_since_;
  StillBand still_{kStillM};
  bool low_run_ = false;   // the run of low readings, still or not, that ends with the newest
  TimeUs low_since_;
  bool down_ = false;      // a still run has lasted kStillS or a low run kLowS, none over since
};

}  // namespace kestrel::mission
