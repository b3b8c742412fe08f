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

// Per pixel, the largest depth difference (in 24-bit codes) that a GL clipping in float at the
// near plane can make, for the pixels of triangles that plane cuts. Mesa's clipper (gallium's
// draw module, both softpipe and llvmpipe) interpolates the new vertex's clip coordinates in
// float and divides by its w: the absolute error of the interpolation, about one float rounding
// of the edge's largest coordinate, is divided by the new vertex's w, which is small when the
// near plane is close to the eye and the edge long. The vertex moves off the triangle's plane, so
// the depth plane of the cut triangle tilts (docs/conformance.md §Near-plane cuts). Under polygon
// offset, Mesa also computes the slope term per piece of the cut polygon from those float
// vertices; the bound then includes the whole slope term.
class NearCutBound {
 public:
  NearCutBound(int width, int height) : width_(width), height_(height), codes_(size_t(width) * size_t(height), 0.0) {}

  // A triangle's clip-space corners as drawn with `state` (its viewport, depth clamp and polygon
  // offset). Nothing happens unless the near plane cuts it (a corner on each side of z = -w,
  // depth clamp off). Otherwise every pixel whose centre lies inside the cut triangle gets at
  // least its bound: max over the new vertices v of
  //   (|delta z_v| + |dz/dx| |delta x_v| + |dz/dy| |delta y_v|) (2^24 - 1),
  // with the window errors of v from a clip-coordinate error e = 2^-22 max|coordinate of the
  // edge| (x, y: e (1 + |x/w|) / w scaled by half the viewport, z: e (1 + |z/w|) / w scaled by
  // half the depth range), plus |factor| max(|dz/dx|, |dz/dy|) (2^24 - 1) under polygon offset.
  void addTriangle(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c, const RenderState& state);

  // Codes per pixel, bottom row first; 0 where no cut triangle lies.
  double at(size_t i) const { return codes_[i]; }

 private:
  int width_, height_;
  std::vector<double> codes_;
};

}  // namespace shadowref::trace
