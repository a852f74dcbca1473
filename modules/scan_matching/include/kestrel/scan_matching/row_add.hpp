#pragma once
// The inner loops of image addition (paper 000, section 5.1.2): rows of 8-bit map cells added
// into rows of 16-bit scores. Each has a plain scalar form and a lane form that must agree
// with it bit for bit (tested): NEON widening adds on ARM targets that have NEON (Overo's
// Cortex-A8), SSE2 on the x86-64 host (the compiler does not keep the accumulators of the
// portable form in registers). Integer addition has
// no rounding and the sums stay below 2^16 (kCellMax * kMaxBeams), so the only way the forms
// can differ is a bug.
#include <cstdint>

#if defined(__ARM_NEON)
#include <arm_neon.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace kestrel::scan_matching {

// Lanes per group: 8 where the target has 128-bit integer SIMD, 1 (plain scalar) on targets
// without, such as the Verdex's XScale, where padding rows would only add work.
#if defined(__ARM_NEON) || defined(__SSE2__)
inline constexpr int kRowLanes = 8;
#else
inline constexpr int kRowLanes = 1;
#endif
// Widest score row whose accumulators stay in registers for a whole pass over the points.
inline constexpr int kMaxRegisterGroups = 4;

inline void add_row_scalar(uint16_t* dst, const uint8_t* src, int n) {
  for (int i = 0; i < n; ++i) dst[i] = static_cast<uint16_t>(dst[i] + src[i]);
}

// dst[0, n) += src[0, n), n a multiple of kRowLanes.
inline void add_row_lanes(uint16_t* dst, const uint8_t* src, int n) {
#if defined(__ARM_NEON)
  for (int i = 0; i < n; i += 8) vst1q_u16(dst + i, vaddw_u8(vld1q_u16(dst + i), vld1_u8(src + i)));
#else
  for (int i = 0; i < n; i += kRowLanes) {
    for (int j = 0; j < kRowLanes; ++j) dst[i + j] = static_cast<uint16_t>(dst[i + j] + src[i + j]);
  }
#endif
}

// dst[0, 8G) += sum over i of rows[offsets[i]] [0, 8G): one score row from every point at
// once, the accumulators held in registers instead of re-read and re-written per point.
template <int G>
inline void sum_rows_lanes(uint16_t* dst, const uint8_t* rows, const int32_t* offsets, int n) {
  static_assert(G >= 1 && G <= kMaxRegisterGroups);
#if defined(__ARM_NEON)
  uint16x8_t acc[G];
  for (int g = 0; g < G; ++g) acc[g] = vdupq_n_u16(0);
  for (int i = 0; i < n; ++i) {
    const uint8_t* s = rows + offsets[i];
    for (int g = 0; g < G; ++g) acc[g] = vaddw_u8(acc[g], vld1_u8(s + 8 * g));
  }
  for (int g = 0; g < G; ++g) vst1q_u16(dst + 8 * g, vaddq_u16(vld1q_u16(dst + 8 * g), acc[g]));
#elif defined(__SSE2__)
  const __m128i zero = _mm_setzero_si128();
  __m128i acc[G];
  for (int g = 0; g < G; ++g) acc[g] = zero;
  for (int i = 0; i < n; ++i) {
    const uint8_t* s = rows + offsets[i];
    for (int g = 0; g < G; ++g) {
      const __m128i cells = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(s + 8 * g));
      acc[g] = _mm_add_epi16(acc[g], _mm_unpacklo_epi8(cells, zero));
    }
  }
  for (int g = 0; g < G; ++g) {
    __m128i* out = reinterpret_cast<__m128i*>(dst + 8 * g);
    _mm_storeu_si128(out, _mm_add_epi16(_mm_loadu_si128(out), acc[g]));
  }
#else
  uint16_t acc[8 * G] = {};
  for (int i = 0; i < n; ++i) {
    const uint8_t* s = rows + offsets[i];
    for (int j = 0; j < 8 * G; ++j) acc[j] = static_cast<uint16_t>(acc[j] + s[j]);
  }
  for (int j = 0; j < 8 * G; ++j) dst[j] = static_cast<uint16_t>(dst[j] + acc[j]);
#endif
}

#if defined(__ARM_NEON) || defined(__SSE2__)
// dst rows r < R (dst_stride apart), 8 lanes each, += the 8 cells at rows + offsets[i] + r * d
// summed over i: a block of at most 8 x 8 scores with one accumulator per row in registers,
// so each point's offset is read once for all R rows (branch and bound's leaf blocks, the
// small slices of the covariance curve).
template <int R>
inline void sum_block_lanes(uint16_t* dst, int dst_stride, const uint8_t* rows, int d, const int32_t* offsets, int n) {
  static_assert(R >= 1 && R <= 8);
#if defined(__ARM_NEON)
  uint16x8_t acc[R];
  for (int r = 0; r < R; ++r) acc[r] = vdupq_n_u16(0);
  for (int i = 0; i < n; ++i) {
    const uint8_t* s = rows + offsets[i];
    for (int r = 0; r < R; ++r) acc[r] = vaddw_u8(acc[r], vld1_u8(s + r * d));
  }
  for (int r = 0; r < R; ++r) {
    uint16_t* out = dst + r * dst_stride;
    vst1q_u16(out, vaddq_u16(vld1q_u16(out), acc[r]));
  }
#else  // SSE2
  const __m128i zero = _mm_setzero_si128();
  __m128i acc[R];
  for (int r = 0; r < R; ++r) acc[r] = zero;
  for (int i = 0; i < n; ++i) {
    const uint8_t* s = rows + offsets[i];
    for (int r = 0; r < R; ++r) {
      const __m128i cells = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(s + r * d));
      acc[r] = _mm_add_epi16(acc[r], _mm_unpacklo_epi8(cells, zero));
    }
  }
  for (int r = 0; r < R; ++r) {
    __m128i* out = reinterpret_cast<__m128i*>(dst + r * dst_stride);
    _mm_storeu_si128(out, _mm_add_epi16(_mm_loadu_si128(out), acc[r]));
  }
#endif
}
#endif  // NEON or SSE2

// The scalar reference of sum_rows_lanes, any width.
inline void sum_rows_scalar(uint16_t* dst, const uint8_t* rows, const int32_t* offsets, int n, int width) {
  for (int i = 0; i < n; ++i) add_row_scalar(dst, rows + offsets[i], width);
}

}  // namespace kestrel::scan_matching
