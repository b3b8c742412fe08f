// The shadow-map texture unit's lookups four points at a time (DepthCompareSampler::sampleDivided
// for a batch, declared in gl/depth_compare_sampler.h): vector lanes of the scalar definition in
// gl/depth_compare_sampler.cpp, the same bits for every point. Kept in the executor so that the
// reference stays scalar; the per-pixel shaders of a shadow-map pass call it for their batches.
#include "gl/depth_compare_sampler.h"

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "exec/clamp_unit.h"
#include "exec/compare_dispatch.h"

namespace shadowref {

namespace {

using v4d = double __attribute__((vector_size(32)));
using v4f = float __attribute__((vector_size(16)));
using v4i = int32_t __attribute__((vector_size(16)));
using v4l = int64_t __attribute__((vector_size(32)));

// nearestTexel for four coordinates: floor, NaN and negatives to 0, at most size - 1. The
// results are whole numbers in [0, size - 1], so the conversion to int is exact.
v4i nearestTexels(v4d coordinate, int size) {
  v4d t = coordinate * double(size);
#if defined(__AVX__)
  t = _mm256_floor_pd(t);  // floor is exact: the same bits as std::floor lane by lane
#else
  for (int lane = 0; lane < 4; ++lane) t[lane] = std::floor(t[lane]);
#endif
  const v4d last = v4d{} + double(size - 1);
  const v4d clamped = t >= 0.0 ? (last < t ? last : t) : v4d{};
  return __builtin_convertvector(clamped, v4i);
}

// compareTexel's comparison with the function fixed, as lane masks (all ones where it passes).
template <CompareFunc F>
v4l compare(v4f r, v4f d) {
  using v4m = int32_t __attribute__((vector_size(16)));
  v4m m;
  if constexpr (F == CompareFunc::Never) m = v4m{};
  else if constexpr (F == CompareFunc::Less) m = r < d;
  else if constexpr (F == CompareFunc::Equal) m = r == d;
  else if constexpr (F == CompareFunc::LEqual) m = r <= d;
  else if constexpr (F == CompareFunc::Greater) m = r > d;
  else if constexpr (F == CompareFunc::NotEqual) m = r != d;
  else if constexpr (F == CompareFunc::GEqual) m = r >= d;
  else m = v4m{} - 1;
  return __builtin_convertvector(m, v4l);
}

}  // namespace

void DepthCompareSampler::sampleDivided(const double* s, const double* t, const double* r, int count, double* out) const {
  // The texels first, for every point, with a request for each one's line: a large map is far
  // beyond the caches, and the lookups then wait for their lines together, not one after another.
  constexpr int kMaxPoints = 64;
  int64_t texel[kMaxPoints];
  const int whole = count / 4 * 4;
  if (whole > kMaxPoints) {  // more than a batch: in batches
    for (int k = 0; k < count; k += kMaxPoints) sampleDivided(s + k, t + k, r + k, std::min(kMaxPoints, count - k), out + k);
    return;
  }
  const uint32_t* bits = texture->bits.data();
  for (int k = 0; k < whole; k += 4) {
    v4d sv, tv;
    std::memcpy(&sv, s + k, sizeof sv);
    std::memcpy(&tv, t + k, sizeof tv);
    const v4i x = nearestTexels(sv, texture->width), y = nearestTexels(tv, texture->height);
    for (int lane = 0; lane < 4; ++lane) {
      texel[k + lane] = int64_t(y[lane]) * texture->width + x[lane];
      __builtin_prefetch(bits + texel[k + lane]);
    }
  }
  auto run = [&](auto f) {
    constexpr CompareFunc F = decltype(f)::value;
    int k = 0;
    for (; k < whole; k += 4) {
      v4d rv;
      std::memcpy(&rv, r + k, sizeof rv);
      // r clamped to [0, 1] as std::clamp does it (NaN passes through), then compared in float.
      const v4f rf = __builtin_convertvector(clampUnit(rv), v4f);
      v4f d;
      for (int lane = 0; lane < 4; ++lane) d[lane] = std::bit_cast<float>(bits[texel[k + lane]]);
      const v4d result = compare<F>(rf, d) ? v4d{} + 1.0 : v4d{} + failValue;
      std::memcpy(out + k, &result, sizeof result);
    }
    for (; k < count; ++k) out[k] = sampleDivided(s[k], t[k], r[k]);
  };
  withCompare(func, run);
}

}  // namespace shadowref
