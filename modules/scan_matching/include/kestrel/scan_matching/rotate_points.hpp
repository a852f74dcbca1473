#pragma once
// The scan transform of the correlative search (paper 000, section 5.1.2: "for each theta the
// scan is transformed once"), as 16 x 16 -> 32-bit integer products: points are int16 pairs in
// 1/2^F cell, cos and sin Q15 (1.0 saturates to 32767), so one rotated coordinate is one
// multiply-accumulate pair.
// Both the SIMD form (SSE2's pmaddwd on the host, NEON's widening multiply-accumulate on the
// Overo) and the scalar form (the Verdex, whose XScale has 16 x 16 multiply-accumulate but no
// fast 64-bit products) compute the same integer formula with no rounding, and must agree
// bit for bit (tested):
//   x = cx + floor((c px - s py + fx) / 2^(F + 15)),  y = cy + floor((s px + c py + fy) / 2^(F + 15))
// No overflow: |c px - s py| <= |(c, s)| |(px, py)| <= 2^15 * 2^15.5 < 1.52e9, and
// 0 <= fx < 2^(F + 15) <= 2^23, so the sum stays below 2^31.
#include <cstdint>

#if defined(__ARM_NEON)
#include <arm_neon.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace kestrel::scan_matching {

inline constexpr int kTrigBits = 15;  // cos and sin in Q15

// A cosine or sine in Q15; 1.0 saturates to 32767 (an error of 2^-15, like the rounding).
inline int16_t trig_q15(double v) {
  const double q = v * (1 << kTrigBits);
  return static_cast<int16_t>(q >= 32767.0 ? 32767 : (q <= -32767.0 ? -32767 : (q < 0 ? q - 0.5 : q + 0.5)));
}

struct RotationQ {
  int16_t c = 32767, s = 0;           // Q15
  int32_t cx = 0, cy = 0;             // centre, whole cells
  int32_t fx = 0, fy = 0;             // centre, fraction of a cell in Q(F + 15), in [0, 2^(F+15))
  int shift = kTrigBits;              // F + 15
};

// x[i], y[i] for i in [first, n) from the interleaved points pxy = {px0, py0, px1, py1, ...}.
inline void rotate_points_scalar(const int16_t* pxy, int first, int n, const RotationQ& r, int32_t* x, int32_t* y) {
  const int32_t c = r.c, s = r.s;
  for (int i = first; i < n; ++i) {
    const int32_t px = pxy[2 * i], py = pxy[2 * i + 1];
    x[i] = r.cx + ((c * px - s * py + r.fx) >> r.shift);
    y[i] = r.cy + ((s * px + c * py + r.fy) >> r.shift);
  }
}

// The same, four points per step where the target has SIMD lanes; the tail goes scalar.
inline void rotate_points(const int16_t* pxy, int n, const RotationQ& r, int32_t* x, int32_t* y) {
  int i = 0;
#if defined(__ARM_NEON)
  const int32x4_t fx = vdupq_n_s32(r.fx), fy = vdupq_n_s32(r.fy);
  const int32x4_t cx = vdupq_n_s32(r.cx), cy = vdupq_n_s32(r.cy);
  const int32x4_t down = vdupq_n_s32(-r.shift);  // a negative left shift is an arithmetic right shift
  for (; i + 4 <= n; i += 4) {
    const int16x4x2_t p = vld2_s16(pxy + 2 * i);  // p.val[0]: px, p.val[1]: py
    const int32x4_t xs = vmlsl_n_s16(vmlal_n_s16(fx, p.val[0], r.c), p.val[1], r.s);
    const int32x4_t ys = vmlal_n_s16(vmlal_n_s16(fy, p.val[0], r.s), p.val[1], r.c);
    vst1q_s32(x + i, vaddq_s32(cx, vshlq_s32(xs, down)));
    vst1q_s32(y + i, vaddq_s32(cy, vshlq_s32(ys, down)));
  }
#elif defined(__SSE2__)
  // pmaddwd: (px, py) . (c, -s) and (px, py) . (s, c), per point, in one instruction each.
  const auto pair = [](int16_t a, int16_t b) {
    return _mm_set1_epi32(static_cast<int32_t>(static_cast<uint32_t>(static_cast<uint16_t>(a)) |
                                               (static_cast<uint32_t>(static_cast<uint16_t>(b)) << 16)));
  };
  const __m128i kx = pair(r.c, static_cast<int16_t>(-r.s)), ky = pair(r.s, r.c);
  const __m128i fx = _mm_set1_epi32(r.fx), fy = _mm_set1_epi32(r.fy);
  const __m128i cx = _mm_set1_epi32(r.cx), cy = _mm_set1_epi32(r.cy);
  const __m128i down = _mm_cvtsi32_si128(r.shift);
  for (; i + 4 <= n; i += 4) {
    const __m128i p = _mm_loadu_si128(reinterpret_cast<const __m128i*>(pxy + 2 * i));
    const __m128i xs = _mm_add_epi32(_mm_madd_epi16(p, kx), fx);
    const __m128i ys = _mm_add_epi32(_mm_madd_epi16(p, ky), fy);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(x + i), _mm_add_epi32(cx, _mm_sra_epi32(xs, down)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(y + i), _mm_add_epi32(cy, _mm_sra_epi32(ys, down)));
  }
#endif
  rotate_points_scalar(pxy, i, n, r, x, y);
}

}  // namespace kestrel::scan_matching
