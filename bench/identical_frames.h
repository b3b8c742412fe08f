// Whether two frames' buffers are byte for byte the same: colour, depth, stencil and accumulation.
// What the benchmarks check before they time anything at several thread counts.
#pragma once

#include <cstring>

#include "gl/framebuffer.h"

namespace shadowref::bench {

template <class T>
bool sameBytes(const PixelVector<T>& a, const PixelVector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

inline bool identicalFrames(const Framebuffer& a, const Framebuffer& b) {
  return sameBytes(a.color(), b.color()) && sameBytes(a.depthCodes(), b.depthCodes()) &&
         sameBytes(a.stencil(), b.stencil()) && sameBytes(a.accum(), b.accum());
}

}  // namespace shadowref::bench
