// Clamps to [0, 1] on four doubles at once, in two instructions where the CPU has them: the colour
// clamp of blending and of every colour write, and the depth encoder's.
#pragma once

#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace shadowref {

using ClampLanes = double __attribute__((vector_size(32)));

#if defined(__SSE2__) && !defined(__AVX__)
namespace detail {
// f on each half of the four lanes: SSE2's instructions take two doubles.
template <class Fn>
inline ClampLanes byHalves(ClampLanes v, Fn f) {
  __m128d half[2];
  std::memcpy(half, &v, sizeof half);
  for (__m128d& h : half) h = f(h);
  ClampLanes out;
  std::memcpy(&out, half, sizeof out);
  return out;
}
}  // namespace detail
#endif

// c < 0 ? 0 : (1 < c ? 1 : c) per lane, as std::clamp: NaN and -0.0 pass through unchanged.
// x86's MAXPD(a, b) is a > b ? a : b and MINPD(a, b) is a < b ? a : b, each the second operand
// when unordered, so MAX(0, c) is c < 0 ? 0 : c and MIN(1, x) is 1 < x ? 1 : x, exactly.
inline ClampLanes clampUnit(ClampLanes c) {
#if defined(__AVX__)
  return __m256d(_mm256_min_pd(_mm256_set1_pd(1.0), _mm256_max_pd(_mm256_setzero_pd(), __m256d(c))));
#elif defined(__SSE2__)
  return detail::byHalves(c, [](__m128d h) { return _mm_min_pd(_mm_set1_pd(1.0), _mm_max_pd(_mm_setzero_pd(), h)); });
#else
  const ClampLanes low = c < 0.0 ? ClampLanes{} : c;
  return 1.0 < low ? ClampLanes{} + 1.0 : low;
#endif
}

// z > 0 ? min(z, 1) : 0 per lane, as DepthCodec::encode clamps: NaN and -0.0 become +0.0.
// MAXPD(z, 0) is z > 0 ? z : 0 (0 when unordered), then MIN(1, x) as above.
inline ClampLanes clampUnitOrZero(ClampLanes z) {
#if defined(__AVX__)
  return __m256d(_mm256_min_pd(_mm256_set1_pd(1.0), _mm256_max_pd(__m256d(z), _mm256_setzero_pd())));
#elif defined(__SSE2__)
  return detail::byHalves(z, [](__m128d h) { return _mm_min_pd(_mm_set1_pd(1.0), _mm_max_pd(h, _mm_setzero_pd())); });
#else
  return z > 0.0 ? (1.0 < z ? ClampLanes{} + 1.0 : z) : ClampLanes{};
#endif
}

// Eight doubles: the span loops' eight depths with AVX-512, clamped after their conversion to
// float (below).
using ClampLanes8 = double __attribute__((vector_size(64)));

// clampUnitOrZero after the conversion to float, on eight floats: float(clampUnitOrZero(z)) has
// the bits of clampUnitOrZeroFloat(float(z)) for every double z — the rounding to float keeps the
// order against 0 and 1 (a z above 1 rounds to 1 or more, a positive z to +0 or more, NaN stays
// NaN) — and eight floats are one AVX register where eight doubles are two halves.
using ClampFloats8 = float __attribute__((vector_size(32)));
inline ClampFloats8 clampUnitOrZeroFloat(ClampFloats8 f) {
#if defined(__AVX__)
  return __m256(_mm256_min_ps(_mm256_set1_ps(1.0f), _mm256_max_ps(__m256(f), _mm256_setzero_ps())));
#else
  using Mask = int32_t __attribute__((vector_size(32)));
  const Mask positive = f > 0.0f, above = 1.0f < f;
  return positive ? (above ? ClampFloats8{} + 1.0f : f) : ClampFloats8{};
#endif
}

}  // namespace shadowref
