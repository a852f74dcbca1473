#pragma once
// Angle arithmetic. Angles are radians; wrapped angles lie in [-pi, pi).
#include <cmath>
#include <numbers>

namespace kestrel {

template <class T>
constexpr T kPi = std::numbers::pi_v<T>;

template <class T>
constexpr T deg_to_rad(T deg) { return deg * (kPi<T> / T(180)); }
template <class T>
constexpr T rad_to_deg(T rad) { return rad * (T(180) / kPi<T>); }

// Wraps any finite angle into [-pi, pi). Non-finite input is returned unchanged, so that the
// caller's finiteness check still sees it.
template <class T>
T wrap_angle(T a) {
  if (!std::isfinite(a)) return a;
  if (a >= -kPi<T> && a < kPi<T>) return a;
  T w = std::fmod(a + kPi<T>, T(2) * kPi<T>);
  if (w < T(0)) w += T(2) * kPi<T>;
  w -= kPi<T>;
  // fmod can round onto the open end of the interval.
  return w >= kPi<T> ? -kPi<T> : w;
}

// The signed smallest rotation taking b to a.
template <class T>
T angle_diff(T a, T b) { return wrap_angle(a - b); }

}  // namespace kestrel
