#include "kestrel/mission/touchdown_sense.hpp"

#include <cmath>

namespace kestrel::mission {

void TouchdownSense::reset() { *this = TouchdownSense{}; }

void TouchdownSense::observe(TimeUs now, const AltimeterSample* newest, float landed_height_m, float max_age_s) {
  const bool usable = newest != nullptr && std::isfinite(newest->height_m) && newest->height_m >= 0.0f &&
                      newest->height_m <= kMaxHeightM;
  if (usable && (!seen_ || newest->stamp > last_stamp_)) {
    seen_ = true;
    last_stamp_ = newest->stamp;
    last_height_m_ = newest->height_m;
    low_ = newest->height_m < landed_height_m;
    if (!low_) {
      low_run_ = 0;
    } else if (low_run_ < UINT8_MAX) {
      ++low_run_;
    }
  }
  // A reading stamped ahead of now (clocks a little apart) is as recent as one stamped now.
  recent_ = seen_ && (now - last_stamp_).seconds() <= static_cast<double>(max_age_s);
}

std::optional<bool> TouchdownSense::on_ground() const {
  if (!seen_) return std::nullopt;
  if (low_run_ >= kLowReadings) return true;
  if (recent_ && !low_) return false;
  return std::nullopt;
}

std::optional<float> TouchdownSense::floor_under(float estimated_height_m) const {
  if (!recent_ || !std::isfinite(estimated_height_m)) return std::nullopt;
  return estimated_height_m - last_height_m_;
}

}  // namespace kestrel::mission
