#include "shadow/shadow_map_accuracy.h"

#include <stdexcept>

namespace shadowref {

ShadowMapErrors countShadowErrors(const LightShadow& shadow, const std::vector<glm::dvec3>& points,
                                  const std::vector<uint8_t>& visible, const std::vector<uint8_t>& mask,
                                  const std::vector<glm::dvec4>& planes) {
  if (visible.size() != points.size() || mask.size() != points.size() || (!planes.empty() && planes.size() != points.size()))
    throw std::invalid_argument("countShadowErrors: points, visible, mask and planes differ in length");
  ShadowMapErrors e;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!mask[i]) continue;
    ++e.points;
    const bool shadowed = shadow.factor(points[i], planes.empty() ? glm::dvec4(0.0) : planes[i]) < 1.0;
    if (shadowed && visible[i]) ++e.falseShadow;
    if (!shadowed && !visible[i]) ++e.missedShadow;
  }
  return e;
}

}  // namespace shadowref
