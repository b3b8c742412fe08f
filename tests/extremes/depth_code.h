// Depth codes as the pipeline stores them, for the precision measurements of the extremes suite.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "gl/framebuffer.h"

namespace shadowref::extremes {

// The depth code the rasterizer stores for a surface facing the camera at eye distance `distance`
// under `projection` (a 1 x 1 framebuffer, one quad through the whole pipeline: clip, setup,
// depth plane, encode). The code's unsigned order is the depth order (framebuffer.h), so the
// difference of two codes counts the distinct depths the buffer can hold between them.
uint32_t depthCode(const glm::dmat4& projection, double distance, DepthFormat format);

// Codes between two distances: how many distinct depths the buffer resolves in [near, far).
inline uint64_t codesBetween(const glm::dmat4& projection, double d0, double d1, DepthFormat format) {
  return uint64_t(depthCode(projection, d1, format)) - uint64_t(depthCode(projection, d0, format));
}

}  // namespace shadowref::extremes
