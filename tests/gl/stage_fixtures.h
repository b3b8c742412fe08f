// Set-up triangles given in window coordinates, for the tests of the reference pipeline's stages
// (coverage, fragment stage, per-fragment operations): the stage under test gets exactly the
// triangle the test describes, without clipping or a viewport transform in between.
#pragma once

#include "gl/render_state.h"
#include "gl/triangle_setup.h"
#include "gl/vertex.h"

namespace shadowref::testing {

// A window vertex at (x, y) with window depth z and 1/w = invW, its varyings those of `source`.
inline WindowVertex windowAt(double x, double y, double z = 0.5, double invW = 1.0, const ClipVertex* source = nullptr) {
  WindowVertex v;
  v.fx = x;
  v.fy = y;
  v.x = int64_t(x * double(kSubpixelOne));  // the tests use exact multiples of 1/256
  v.y = int64_t(y * double(kSubpixelOne));
  v.z = z;
  v.invW = invW;
  v.source = source;
  return v;
}

// The setup of window triangle (a, b, c) in `state` (a Float32 depth codec); requires it to have area.
inline TriangleSetup setupOf(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c,
                             const RenderState& state = {}, Facing facing = FrontFacing) {
  TriangleSetup t;
  const bool made = setupTriangle(a, b, c, facing, state, DepthCodec{}, t);
  if (!made) t.area2 = 0;
  return t;
}

}  // namespace shadowref::testing
