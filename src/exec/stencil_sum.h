// The sum that ends a counting flush by runs of triangles (counting_flush.cpp): each thread but the
// first counted into a stencil of its own, and those counts are added to the framebuffer's stencil
// modulo 256 — the shadow volumes' wrapping ops — and zeroed for the next flush.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace shadowref {

// stencil[i] += counts[i] (modulo 256), then counts[i] = 0, for i in [0, n): 32 bytes a step. GCC
// left the plain loop scalar (two byte pointers, which may alias each other), about eight
// instructions a pixel; as 32-byte vectors the same work takes a few instructions per 32 pixels.
inline void addAndZeroCounts(uint8_t* stencil, uint8_t* counts, size_t n) {
  using Bytes = uint8_t __attribute__((vector_size(32)));
  size_t i = 0;
  for (; i + sizeof(Bytes) <= n; i += sizeof(Bytes)) {
    Bytes sum, add;
    std::memcpy(&sum, stencil + i, sizeof sum);
    std::memcpy(&add, counts + i, sizeof add);
    sum += add;
    std::memcpy(stencil + i, &sum, sizeof sum);
    std::memset(counts + i, 0, sizeof add);
  }
  for (; i < n; ++i) {
    stencil[i] = uint8_t(stencil[i] + counts[i]);
    counts[i] = 0;
  }
}

}  // namespace shadowref
