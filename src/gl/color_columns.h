// Batch shaders work in columns — one array per channel, four fragments to a vector — and hand
// back one RGBA per fragment. Turning four fragments' columns into their four colours is a 4x4
// transpose: eight shuffles and four stores instead of sixteen scalar moves. Moves only: every bit
// (-0.0, NaN) arrives as it was.
#pragma once

#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>

namespace shadowref {

using ColorLanes = double __attribute__((vector_size(32)));

// out[i] = (r[i], g[i], b[i], a[i]) for the first n (at most 4) lanes.
inline void storeColorLanes(ColorLanes r, ColorLanes g, ColorLanes b, ColorLanes a, int n, glm::dvec4* out) {
  static_assert(sizeof(glm::dvec4) == sizeof(ColorLanes));
  if (n == 4) {
    using Index = int64_t __attribute__((vector_size(32)));
    // The same lane selection in GCC's and clang's spelling (clang builds the fuzz targets).
#if defined(__clang__)
#define SHADOWREF_SHUFFLE(x, y, i0, i1, i2, i3) __builtin_shufflevector(x, y, i0, i1, i2, i3)
#else
#define SHADOWREF_SHUFFLE(x, y, i0, i1, i2, i3) __builtin_shuffle(x, y, Index{i0, i1, i2, i3})
#endif
    const ColorLanes rg02 = SHADOWREF_SHUFFLE(r, g, 0, 4, 2, 6);  // r0 g0 r2 g2
    const ColorLanes rg13 = SHADOWREF_SHUFFLE(r, g, 1, 5, 3, 7);  // r1 g1 r3 g3
    const ColorLanes ba02 = SHADOWREF_SHUFFLE(b, a, 0, 4, 2, 6);
    const ColorLanes ba13 = SHADOWREF_SHUFFLE(b, a, 1, 5, 3, 7);
    const ColorLanes p0 = SHADOWREF_SHUFFLE(rg02, ba02, 0, 1, 4, 5), p1 = SHADOWREF_SHUFFLE(rg13, ba13, 0, 1, 4, 5),
                     p2 = SHADOWREF_SHUFFLE(rg02, ba02, 2, 3, 6, 7), p3 = SHADOWREF_SHUFFLE(rg13, ba13, 2, 3, 6, 7);
#undef SHADOWREF_SHUFFLE
    // One store each (an array of the four, copied at once, went through the stack).
    std::memcpy(&out[0], &p0, sizeof p0);
    std::memcpy(&out[1], &p1, sizeof p1);
    std::memcpy(&out[2], &p2, sizeof p2);
    std::memcpy(&out[3], &p3, sizeof p3);
    return;
  }
  for (int i = 0; i < n; ++i) out[i] = {r[i], g[i], b[i], a[i]};
}

// out[k] = (r[k], g[k], b[k], alpha) for k < count.
inline void storeColorColumns(const double* r, const double* g, const double* b, double alpha, int count,
                              glm::dvec4* out) {
  const ColorLanes a = {alpha, alpha, alpha, alpha};
  int k = 0;
  for (; k + 4 <= count; k += 4) {
    ColorLanes lanes[3];
    std::memcpy(&lanes[0], r + k, sizeof lanes[0]);
    std::memcpy(&lanes[1], g + k, sizeof lanes[1]);
    std::memcpy(&lanes[2], b + k, sizeof lanes[2]);
    storeColorLanes(lanes[0], lanes[1], lanes[2], a, 4, out + k);
  }
  for (; k < count; ++k) out[k] = {r[k], g[k], b[k], alpha};
}

}  // namespace shadowref
