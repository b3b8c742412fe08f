// How right a shadow map is: its shadow test at surface points
// against the true light visibility there (a shadow ray per pixel, src/oracle).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "shadow/light_shadow.h"

namespace shadowref {

struct ShadowMapErrors {
  size_t points = 0;        // points compared (pixels with a hit)
  size_t falseShadow = 0;   // shadowed by the map (factor < 1), visible from the light
  size_t missedShadow = 0;  // lit by the map (factor 1), hidden from the light

  size_t wrong() const { return falseShadow + missedShadow; }
  double wrongFraction() const { return points ? double(wrong()) / double(points) : 0.0; }
};

// Compares the map's verdict at points[i] with visible[i] (1: the light sees it) wherever
// mask[i] is set; all three have the same length. planes[i]: the receiver plane at points[i]
// (LightShadow::factor), same length too, or empty for none.
ShadowMapErrors countShadowErrors(const LightShadow& shadow, const std::vector<glm::dvec3>& points,
                                  const std::vector<uint8_t>& visible, const std::vector<uint8_t>& mask,
                                  const std::vector<glm::dvec4>& planes = {});

}  // namespace shadowref
