#include "shadow/shadow_lookup.h"

namespace shadowref {

glm::dvec4 shadowCoordinates(const glm::dmat4& T, const glm::dvec3& worldPosition) {
  return T * glm::dvec4(worldPosition, 1.0);
}

glm::dvec4 withConstantBias(const glm::dvec4& strq, double constantBias) {
  return {strq.x, strq.y, strq.z - constantBias * strq.w, strq.w};
}

double ShadowLookup::factor(const glm::dvec3& worldPosition) const {
  const glm::dvec4 strq = withConstantBias(shadowCoordinates(textureMatrix, worldPosition), constantBias);
  if (!(strq.w > 0.0)) return 1.0;
  return pcf > 1 ? sampler.samplePcf(strq, pcf) : sampler.sample(strq);
}

double CubeShadowLookup::factor(const glm::dvec3& worldPosition) const {
  const CubeFace face = cubeFaceFor(worldPosition - lightPosition);
  return faces[size_t(face)].factor(worldPosition);
}

}  // namespace shadowref
