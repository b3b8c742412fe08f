// What the primitive stages consume: homogeneous clip-space positions plus varyings.
#pragma once

#include <array>
#include <glm/glm.hpp>

namespace shadowref {

// Varyings are interpolated perspective-correctly across a triangle. Double precision: they
// carry world positions for lighting and shadow-map lookups, where float would be the error.
inline constexpr int kMaxVaryings = 16;

struct ClipVertex {
  glm::dvec4 position{0.0};  // clip space; w = 0 (a point at infinity) is legal
  std::array<double, kMaxVaryings> varyings{};
};

}  // namespace shadowref
