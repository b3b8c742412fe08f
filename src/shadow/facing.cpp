#include "shadow/facing.h"

namespace shadowref {

bool facesLight(const glm::dvec3& normal, const glm::dvec3& vertex, const glm::dvec4& light) {
  const glm::dvec3 towardsLight = glm::dvec3(light) - light.w * vertex;
  return glm::dot(normal, towardsLight) > 0.0;
}

void computeFacing(const Mesh& mesh, const glm::dvec4& light, std::vector<uint8_t>& facing) {
  const size_t count = mesh.weldedTriangles.size();
  facing.resize(count);
  for (size_t t = 0; t < count; ++t) {
    const glm::dvec3& a = mesh.weldedPositions[mesh.weldedTriangles[t].x];
    facing[t] = facesLight(mesh.faceNormals[t], a, light) ? 1 : 0;
  }
}

glm::dvec4 lightInObjectSpace(const glm::dmat4& world, const glm::dvec4& worldLight) {
  glm::dvec4 l = glm::inverse(world) * worldLight;
  // A projective world matrix would leave w != 0, 1; scene transforms are affine, so only the
  // rounding of inverse() can disturb w. Snap it back so L.w stays exactly 1 or 0.
  l.w = worldLight.w;
  return l;
}

}  // namespace shadowref
