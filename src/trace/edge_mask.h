// The pixels near a primitive edge, where GL leaves the implementation freedom: which of two
// triangles owns a pixel centre exactly on (or within rounding of) their shared edge — the
// fill-rule tie — and how clipped vertices are rounded. A difference there between two
// implementations is explained by the fill rule, not by the per-fragment operations
// (docs/conformance.md).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "gl/render_state.h"

namespace shadowref::trace {

class EdgeMask {
 public:
  EdgeMask(int width, int height) : width_(width), height_(height), mask_(size_t(width) * size_t(height), false) {}

  // Marks every pixel whose centre lies within `distance` pixels of an edge of the triangle
  // (clip-space corners), after clipping it in double precision against |x|, |y| <= 4w (so
  // window coordinates stay finite; edges out there mark nothing), w > 0 and, unless depth
  // clamp, the near and far planes, and projecting it with its viewport.
  void addTriangle(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c, const Viewport& viewport,
                   bool depthClamp, double distance = 1.0);

  // One flag per pixel, bottom row first.
  const std::vector<bool>& mask() const { return mask_; }
  bool at(size_t i) const { return mask_[i]; }

 private:
  int width_, height_;
  std::vector<bool> mask_;
};

}  // namespace shadowref::trace
