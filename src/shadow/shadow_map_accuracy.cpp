#include "shadow/shadow_map_accuracy.h"

#include <stdexcept>

namespace shadowref {

ShadowMapErrors countShadowErrors(const LightShadow& shadow, const std::vector<glm::dvec3>& points,
                                  const std::vector<uint8_t>& visible, const std::vector<uint8_t>& mask) {
  if (visible.size() != points.size() || mask.size() != points.size())
    throw std::invalid_argument("countShadowErrors: points, visible and mask differ in length");
  ShadowMapErrors e;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!mask[i]) continue;
    ++e.points;
    const bool shadowed = shadow.factor(points[i]) < 1.0;
    if (shadowed && visible[i]) ++e.falseShadow;
    if (!shadowed && !visible[i]) ++e.missedShadow;
  }
  return e;
}

}  // namespace shadowref
