#pragma once
// Q-format fixed point with saturating arithmetic, for hot loops on the FPU-less Verdex.
// Fixed<F> stores round(x * 2^F) in a 32-bit integer; products use a 64-bit intermediate and
// round to nearest (ties away from zero); every operation saturates at the representable range
// instead of wrapping, so an overflow degrades a value rather than flipping its sign.
#include <cmath>
#include <cstdint>
#include <limits>

namespace kestrel {

namespace fixed_detail {
constexpr int32_t saturate(int64_t v) {
  if (v > std::numeric_limits<int32_t>::max()) return std::numeric_limits<int32_t>::max();
  if (v < std::numeric_limits<int32_t>::min()) return std::numeric_limits<int32_t>::min();
  return static_cast<int32_t>(v);
}
// Divides by 2^shift rounding to nearest, ties away from zero.
constexpr int64_t round_shift(int64_t v, int shift) {
  if (shift <= 0) return v;
  const int64_t half = int64_t{1} << (shift - 1);
  return v >= 0 ? (v + half) >> shift : -((-v + half) >> shift);
}
}  // namespace fixed_detail

template <int F>
class Fixed {
  static_assert(F > 0 && F < 31, "Fixed<F>: F fractional bits in 1..30");

 public:
  static constexpr int kFracBits = F;
  static constexpr int32_t kOne = int32_t{1} << F;

  constexpr Fixed() = default;
  static constexpr Fixed from_raw(int32_t raw) { Fixed f; f.raw_ = raw; return f; }
  static constexpr Fixed from_int(int32_t v) { return from_raw(fixed_detail::saturate(int64_t{v} << F)); }
  // NaN maps to zero; out-of-range values saturate.
  static Fixed from_double(double v) {
    if (std::isnan(v)) return Fixed{};
    const double scaled = std::round(v * static_cast<double>(kOne));
    if (scaled >= static_cast<double>(std::numeric_limits<int32_t>::max())) return max();
    if (scaled <= static_cast<double>(std::numeric_limits<int32_t>::min())) return min();
    return from_raw(static_cast<int32_t>(scaled));
  }
  static constexpr Fixed max() { return from_raw(std::numeric_limits<int32_t>::max()); }
  static constexpr Fixed min() { return from_raw(std::numeric_limits<int32_t>::min()); }

  constexpr int32_t raw() const { return raw_; }
  constexpr double to_double() const { return static_cast<double>(raw_) / static_cast<double>(kOne); }
  constexpr float to_float() const { return static_cast<float>(raw_) / static_cast<float>(kOne); }
  // Rounds to the nearest integer, ties away from zero.
  constexpr int32_t round_to_int() const { return static_cast<int32_t>(fixed_detail::round_shift(raw_, F)); }

  friend constexpr Fixed operator+(Fixed a, Fixed b) {
    return from_raw(fixed_detail::saturate(int64_t{a.raw_} + b.raw_));
  }
  friend constexpr Fixed operator-(Fixed a, Fixed b) {
    return from_raw(fixed_detail::saturate(int64_t{a.raw_} - b.raw_));
  }
  friend constexpr Fixed operator*(Fixed a, Fixed b) {
    return from_raw(fixed_detail::saturate(fixed_detail::round_shift(int64_t{a.raw_} * b.raw_, F)));
  }
  // Division by zero saturates towards the sign of the dividend (zero / zero is zero).
  friend constexpr Fixed operator/(Fixed a, Fixed b) {
    if (b.raw_ == 0) return a.raw_ > 0 ? max() : (a.raw_ < 0 ? min() : Fixed{});
    const int64_t num = int64_t{a.raw_} * (int64_t{1} << F);
    const int64_t den = b.raw_;
    // Round to nearest, ties away from zero.
    const int64_t q = ((num < 0) == (den < 0)) ? (num + den / 2) / den : (num - den / 2) / den;
    return from_raw(fixed_detail::saturate(q));
  }
  constexpr Fixed operator-() const { return from_raw(fixed_detail::saturate(-int64_t{raw_})); }
  Fixed& operator+=(Fixed b) { return *this = *this + b; }
  Fixed& operator-=(Fixed b) { return *this = *this - b; }
  Fixed& operator*=(Fixed b) { return *this = *this * b; }
  friend constexpr auto operator<=>(Fixed, Fixed) = default;

 private:
  int32_t raw_ = 0;
};

using Q16 = Fixed<16>;  // 16.16: ±32768 with 1.5e-5 resolution
using Q24 = Fixed<24>;  // 8.24: ±128 with 6e-8 resolution (gains, unit vectors)

}  // namespace kestrel
