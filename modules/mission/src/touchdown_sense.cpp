#include "kestrel/mission/touchdown_sense.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::mission {

void TouchdownSense::reset() { *this = TouchdownSense{}; }

void TouchdownSense::observe(TimeUs now, const AltimeterSample* newest, float landed_height_m, float max_age_s) {
  if (newest != nullptr && (!counted_any_ || newest->stamp > counted_stamp_)) {
    counted_any_ = true;
    counted_stamp_ = newest->stamp;
    const bool usable = std::isfinite(newest->height_m) && newest->height_m >= kMinHeightM &&
                        newest->height_m <= kMaxHeightM;
    if (usable) {
      take(*newest, landed_height_m);
    } else {
      in_run_ = low_run_ = false;  // it ends a run of low readings
    }
  }
  // A reading stamped ahead of now (clocks a little apart) is as recent as one stamped now.
  age_s_ = seen_ ? std::max(0.0f, static_cast<float>((now - last_stamp_).seconds())) : 0.0f;
  recent_ = seen_ && age_s_ <= max_age_s;
}

void TouchdownSense::take(const AltimeterSample& r, float landed_height_m) {
  const double gap_s = (r.stamp - last_stamp_).seconds();
  const bool continues = in_run_ && gap_s <= static_cast<double>(kMaxGapS);
  const bool stays_low = low_run_ && gap_s <= static_cast<double>(kLowGapS);
  seen_ = true;
  last_stamp_ = r.stamp;
  last_height_m_ = r.height_m;
  low_ = r.height_m < landed_height_m;
  if (!low_) {
    in_run_ = low_run_ = false;
    down_ = false;
    return;
  }
  if (!stays_low) low_since_ = r.stamp;
  low_run_ = true;
  if (!continues || !still_.takes(r.height_m)) {
    still_since_ = r.stamp;  // the run starts again at this reading
    still_.clear();
  }
  still_.add(r.height_m);
  in_run_ = true;
  down_ = down_ || (r.stamp - still_since_).seconds() >= static_cast<double>(kStillS) ||
          (r.stamp - low_since_).seconds() >= static_cast<double>(kLowS);
}

std::optional<bool> TouchdownSense::on_ground() const {
  if (down_) return true;
  if (recent_) return false;  // over the height, or low and not yet still: not down yet
  return std::nullopt;
}

std::optional<float> TouchdownSense::floor_under(float estimated_height_m, float vertical_speed_mps) const {
  if (!recent_ || low_ || !std::isfinite(estimated_height_m) || !std::isfinite(vertical_speed_mps))
    return std::nullopt;
  return estimated_height_m - vertical_speed_mps * age_s_ - last_height_m_;
}

}  // namespace kestrel::mission
