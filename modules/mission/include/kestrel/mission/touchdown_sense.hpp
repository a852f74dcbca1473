#pragma once
// Touchdown by the altimeter's word. The estimate's height is the altimeter's readings over the
// floor the filter believes is under the vehicle (NavFilter::floor_m); a floor step taken wrongly
// leaves it off by a desk's height. Landing by the estimate alone, the mission then cut the motors
// 0.66 m above the floor (iarc-arena, UTM-30LX seed 25, before the height runs' time to stay), or
// never landed on the furniture it came down on. The altimeter reads the height over whatever is
// under the vehicle, which is where it touches down.
//
// Its verdict, from the readings since reset():
//  - airborne: the newest reading is recent and at or over the landed height;
//  - on the ground: readings under it have stayed within kStillM of one another for kStillS
//    (the vehicle stopped: the filter's vertical velocity does not see the stop at once, the
//    impact being too short for its IMU, and its height runs on under the floor until its
//    readings re-lock it), and none over it since, recent or not (a laser's deflected beams read
//    nothing nearer than its minimum range: the UTM-30LX's 0.1 m is more than its 0.08 m mount
//    height, so on the ground it falls silent);
//  - none (nullopt): no reading, a stale one over the height, or low ones not yet still long
//    enough; the caller then goes by the estimate.
// A reading counts once (by its stamp; one not newer than the last is ignored), and only a
// usable one: finite, its height in [kMinHeightM, kMaxHeightM] (on the floor the noise reads a
// few millimetres under it). Recent: now - stamp <= max_age_s.
#include <cstdint>
#include <optional>

#include "kestrel/core/messages.hpp"

namespace kestrel::mission {

class TouchdownSense {
 public:
  // Still: descending at the landing's 0.3 m/s, readings 0.1 s apart move 0.03 m. kStillS is
  // two readings of a 10 Hz altimeter (the URG-04LX's), give or take their jitter.
  static constexpr float kStillM = 0.02f;
  static constexpr float kStillS = 0.09f;
  static constexpr float kMinHeightM = -0.5f;
  static constexpr float kMaxHeightM = 20.0f;

  void reset();
  // Each guidance step: the newest reading (nullptr: none), the height under which the vehicle
  // is down, and how old a reading may be to count as the present.
  void observe(TimeUs now, const AltimeterSample* newest, float landed_height_m, float max_age_s);

  std::optional<bool> on_ground() const;
  // The floor under the vehicle in the estimate's frame (height minus the newest reading), while
  // that reading is recent.
  std::optional<float> floor_under(float estimated_height_m) const;

 private:
  void take(const AltimeterSample& r, float landed_height_m);

  bool seen_ = false;      // a usable reading since reset()
  TimeUs last_stamp_;      // of the newest usable reading
  float last_height_m_ = 0;
  bool recent_ = false;    // the newest usable reading, at the last observe()
  bool low_ = false;       // ... lay under the landed height
  // The run of low readings within kStillM of one another that ends with the newest: its first
  // stamp and its lowest and highest heights.
  TimeUs still_since_;
  float still_min_m_ = 0;
  float still_max_m_ = 0;
  bool down_ = false;      // that run has lasted kStillS
};

}  // namespace kestrel::mission
