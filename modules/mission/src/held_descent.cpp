#include "kestrel/mission/held_descent.hpp"

#include <algorithm>
#include <cmath>

namespace kestrel::mission {

void HeldDescent::observe(float dt_s, TimeUs estimate_stamp, float height_m, float vertical_speed_mps,
                          float setpoint_z_m, std::optional<float> reading_m) {
  const bool fresh = !newest_stamp_ || estimate_stamp > *newest_stamp_;
  if (fresh) newest_stamp_ = estimate_stamp;
  const bool finite = std::isfinite(dt_s) && std::isfinite(height_m) && std::isfinite(vertical_speed_mps) &&
                      std::isfinite(setpoint_z_m) && (!reading_m || std::isfinite(*reading_m));
  if (!fresh || !finite || height_m - setpoint_z_m < kGapM || std::fabs(vertical_speed_mps) >= kStillSpeedMps) {
    in_run_ = false;
    return;
  }
  if (!in_run_ || !heights_.takes(height_m) || (reading_m && !readings_.takes(*reading_m))) {
    in_run_ = true;  // the run starts again at this step
    run_ = Duration{};
    heights_.clear();
    readings_.clear();
  } else {
    run_ = run_ + Duration::from_s(std::clamp(dt_s, 0.0f, kMaxStepS));
  }
  heights_.add(height_m);
  if (reading_m) readings_.add(*reading_m);
}

}  // namespace kestrel::mission
