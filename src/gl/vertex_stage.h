// Object space -> clip space. Every pass that draws the same vertex (the scene pass, a shadow
// volume's front cap) must go through this one function with the same matrices: equal inputs then
// give bit-equal clip coordinates and bit-equal depths: z-fail counts the front cap
// only if it fails the depth test LESS against the scene's own depth there.
#pragma once

#include <glm/glm.hpp>

namespace shadowref {

struct VertexTransform {
  glm::dmat4 modelView{1.0};
  glm::dmat4 projection{1.0};

  glm::dvec4 toClip(const glm::dvec4& objectPosition) const { return projection * (modelView * objectPosition); }
};

}  // namespace shadowref
