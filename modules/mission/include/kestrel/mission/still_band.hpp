#pragma once
// A run of heights that stays within a width of one another: how the landing tells a vehicle
// at rest (TouchdownSense's readings, HeldDescent's estimated heights) from one still moving.
#include <algorithm>

namespace kestrel::mission {

class StillBand {
 public:
  explicit constexpr StillBand(float width_m) : width_m_(width_m) {}

  // Whether v joins the run and keeps it within the width (an empty band takes anything).
  constexpr bool takes(float v) const { return !any_ || std::max(hi_, v) - std::min(lo_, v) <= width_m_; }
  constexpr void add(float v) {
    lo_ = any_ ? std::min(lo_, v) : v;
    hi_ = any_ ? std::max(hi_, v) : v;
    any_ = true;
  }
  constexpr void clear() { any_ = false; }

 private:
  float width_m_;
  float lo_ = 0;
  float hi_ = 0;
  bool any_ = false;
};

}  // namespace kestrel::mission
