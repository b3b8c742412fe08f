// What the primitive stages consume: homogeneous clip-space positions plus varyings.
#pragma once

#include <array>
#include <new>
#include <vector>

#include <glm/glm.hpp>

#include "memory/construct_later.h"

namespace shadowref {

// Varyings are interpolated perspective-correctly across a triangle. Double precision: they
// carry world positions for lighting and shadow-map lookups, where float would be the error.
inline constexpr int kMaxVaryings = 16;

struct ClipVertex {
  glm::dvec4 position{0.0};  // clip space; w = 0 (a point at infinity) is legal
  std::array<double, kMaxVaryings> varyings{};
};

// Vertices filled after allocation, range by range (prepareInstances, the Gouraud passes' lit copies).
using ClipVertexBuffer = std::vector<ClipVertex, ConstructLaterAllocator<ClipVertex>>;

// Constructs the vertex at `slot` of a ClipVertexBuffer as a copy of `v`.
inline ClipVertex& placeVertex(ClipVertex& slot, const ClipVertex& v) {
  return *::new (static_cast<void*>(&slot)) ClipVertex(v);
}

}  // namespace shadowref
