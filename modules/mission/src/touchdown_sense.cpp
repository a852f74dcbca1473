#include "kestrel/mission/touchdown_sense.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::mission {

void TouchdownSense::reset() { *this = TouchdownSense{}; }

void TouchdownSense::observe(TimeUs now, const AltimeterSample* newest, float landed_height_m, float max_age_s) {
  const bool usable = newest != nullptr && std::isfinite(newest->height_m) && newest->height_m >= kMinHeightM &&
                      newest->height_m <= kMaxHeightM;
  if (usable && (!seen_ || newest->stamp > last_stamp_)) take(*newest, landed_height_m);
  // A reading stamped ahead of now (clocks a little apart) is as recent as one stamped now.
  recent_ = seen_ && (now - last_stamp_).seconds() <= static_cast<double>(max_age_s);
}

void TouchdownSense::take(const AltimeterSample& r, float landed_height_m) {
  const bool was_low = seen_ && low_;
  seen_ = true;
  last_stamp_ = r.stamp;
  last_height_m_ = r.height_m;
  low_ = r.height_m < landed_height_m;
  if (!low_) {
    down_ = false;
    return;
  }
  const float lo = std::min(still_min_m_, r.height_m);
  const float hi = std::max(still_max_m_, r.height_m);
  if (!was_low || hi - lo > kStillM) {
    still_since_ = r.stamp;  // the run starts again at this reading
    still_min_m_ = still_max_m_ = r.height_m;
  } else {
    still_min_m_ = lo;
    still_max_m_ = hi;
  }
  down_ = down_ || (r.stamp - still_since_).seconds() >= static_cast<double>(kStillS);
}

std::optional<bool> TouchdownSense::on_ground() const {
  if (down_) return true;
  if (seen_ && recent_ && !low_) return false;
  return std::nullopt;
}

std::optional<float> TouchdownSense::floor_under(float estimated_height_m) const {
  if (!recent_ || !std::isfinite(estimated_height_m)) return std::nullopt;
  return estimated_height_m - last_height_m_;
}

}  // namespace kestrel::mission
