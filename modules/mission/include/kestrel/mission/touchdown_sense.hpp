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
//  - on the ground: the last kLowReadings readings were all under it, and none over it since,
//    recent or not (a laser's deflected beams read nothing nearer than its minimum range: the
//    UTM-30LX's 0.1 m is more than its 0.08 m mount height, so on the ground it falls silent);
//  - none (nullopt): no reading, a stale one over the height, or a low one not yet confirmed;
//    the caller then goes by the estimate.
// A reading counts once (by its stamp; one not newer than the last is ignored), and only a
// usable one: finite, its height in [0, kMaxHeightM]. Recent: now - stamp <= max_age_s.
#include <cstdint>
#include <optional>

#include "kestrel/core/messages.hpp"

namespace kestrel::mission {

class TouchdownSense {
 public:
  // One reading under the landed height may be the edge of something the vehicle passes over.
  static constexpr uint8_t kLowReadings = 2;
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
  bool seen_ = false;      // a usable reading since reset()
  TimeUs last_stamp_;      // of the newest usable reading
  float last_height_m_ = 0;
  bool recent_ = false;    // the newest usable reading, at the last observe()
  bool low_ = false;       // ... lay under the landed height
  uint8_t low_run_ = 0;    // readings under it in a row, saturating
};

}  // namespace kestrel::mission
