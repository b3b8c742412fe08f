// One shadow-map lookup spelled out for the pixel history: the steps of ShadowLookup::factor
// ([Hempe 2004, §3.1, §5.1.4]) for one world position, each value as the lookup computed it —
// strq = T · p, the bias, the division, the nearest texel, its stored depth D, the compared
// r/q (clamped to [0, 1], in float as the texture stores it) and the result.
#pragma once

#include <glm/glm.hpp>

#include "shadow/light_shadow.h"

namespace shadowref {

struct ShadowLookupTrace {
  int face = -1;                    // a point light's cube face (CubeFace), -1 for one map
  glm::dvec4 strq{0.0};             // T · (p, 1), with the constant bias applied to r
  double s = 0.0, t = 0.0, r = 0.0; // s/q, t/q, r/q
  int texelX = 0, texelY = 0;       // the nearest texel (the centre of a PCF kernel)
  int mapWidth = 0, mapHeight = 0;
  float stored = 0.0f;              // D, the depth the texel holds
  float compared = 0.0f;            // r/q clamped to [0, 1] in float: what is compared with D
  bool passed = false;              // compared LEQUAL (the sampler's function) D at the nearest texel
  int pcf = 1;                      // k of k x k PCF; the result is then the kernel's mean
  bool behindLight = false;         // q <= 0 (or behind a spot light's unwarped view): lit, 1
  bool outsideMap = false;          // s/q or t/q outside [0, 1] with a map fitted to the casters: lit, 1
  double result = 1.0;              // LightShadow::factor(p): 1 lit, the compare-fail value shadowed
};

// `receiverPlane`: the world plane of the point's triangle, as LightShadow::factor takes it.
ShadowLookupTrace traceShadowLookup(const LightShadow& shadow, const glm::dvec3& worldPosition,
                                    const glm::dvec4& receiverPlane = glm::dvec4(0.0));

}  // namespace shadowref
