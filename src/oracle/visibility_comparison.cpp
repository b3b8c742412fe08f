#include "oracle/visibility_comparison.h"

#include <cmath>
#include <stdexcept>

namespace shadowref::oracle {

std::vector<uint8_t> comparedPixels(const OracleImage& o, const Light& light) {
  std::vector<uint8_t> mask = o.hitMask;
  if (light.type != LightType::Spot) return mask;
  const double cosCutoff = std::cos(light.spotCutoffDegrees * M_PI / 180.0);
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i] && glm::dot(glm::normalize(o.hitPoint[i] - light.position), glm::normalize(light.direction)) < cosCutoff)
      mask[i] = 0;
  return mask;
}

VisibilityComparison compareVisibility(const OracleImage& o, const std::vector<uint8_t>& mask,
                                       const std::function<bool(size_t)>& renderedLit, bool paleNearEdges) {
  const size_t w = size_t(o.width), h = size_t(o.height);
  if (mask.size() != w * h || o.lit.size() != w * h || o.nearEdge.size() != w * h)
    throw std::invalid_argument("compareVisibility: the mask and the oracle image differ in size");
  VisibilityComparison c;
  VisibilityCounts& n = c.counts;
  c.errorMap.assign(w * h * 3, 0);
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) {
      const size_t i = o.index(x, y);
      if (!mask[i]) continue;
      ++n.compared;
      const bool tracedLit = o.lit[i] != 0;
      uint8_t* px = &c.errorMap[((h - 1 - size_t(y)) * w + size_t(x)) * 3];
      if (renderedLit(i) == tracedLit) {
        ++n.agree;
        px[0] = px[1] = px[2] = tracedLit ? 200 : 90;
        continue;
      }
      const bool edge = o.nearEdge[i] != 0;
      ++(edge ? n.nearEdge : n.elsewhere);
      const bool pale = paleNearEdges && edge;
      if (tracedLit) {
        ++n.falseShadow;
        px[0] = 255, px[1] = pale ? 160 : 0, px[2] = pale ? 160 : 0;
      } else {
        ++n.missedShadow;
        px[0] = pale ? 150 : 0, px[1] = pale ? 180 : 64, px[2] = 255;
      }
    }
  return c;
}

}  // namespace shadowref::oracle
