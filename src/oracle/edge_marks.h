// Marking the pixels near projected edges (comparisons leave out pixels within one pixel of
// a volume or geometry edge, where the rasterizer's fill rule and the ray's exact answer may
// differ). Edges are homogeneous world segments (w = 0 ends allowed), clipped in clip space to the
// near plane and the guard band (camera_model.h), then every pixel whose centre lies within
// `radius` pixels of the projected segment is marked.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "oracle/camera_model.h"

namespace shadowref::oracle {

// marks: width * height of the viewport, row 0 at the bottom.
void markNearSegment(const CameraModel& camera, glm::dvec4 a, glm::dvec4 b, double radius, std::vector<uint8_t>& marks);

}  // namespace shadowref::oracle
