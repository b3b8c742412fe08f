#include "gl/fragment_stage.h"

#include <algorithm>

namespace shadowref {

double fragmentDepth(const TriangleSetup& t, int x, int y, const RenderState& state) {
  double z = planeDepthAt(t, x, y) + t.depthOffset;
  if (state.depthClamp) {
    const Viewport& vp = state.viewport;
    z = std::clamp(z, std::min(vp.nearVal, vp.farVal), std::max(vp.nearVal, vp.farVal));
  }
  return z;  // the depth codec clamps to [0, 1] when it converts
}

void interpolateVaryings(const TriangleSetup& t, int64_t e0, int64_t e1, int64_t e2, int count, double* out) {
  if (count == 0) return;  // a shader that reads none: the vertices' varyings are not touched
  const double b0 = double(e0) * t.v[0].invW;
  const double b1 = double(e1) * t.v[1].invW;
  const double b2 = double(e2) * t.v[2].invW;
  const double inv = 1.0 / (b0 + b1 + b2);
  const double* a0 = t.v[0].source->varyings.data();
  const double* a1 = t.v[1].source->varyings.data();
  const double* a2 = t.v[2].source->varyings.data();
  for (int k = 0; k < count; ++k) out[k] = (b0 * a0[k] + b1 * a1[k] + b2 * a2[k]) * inv;
}

glm::dvec4 shadeFragment(const FragmentShader& shader, const TriangleSetup& t, int x, int y, double depth, int64_t e0,
                         int64_t e1, int64_t e2) {
  double varyings[kMaxVaryings];
  interpolateVaryings(t, e0, e1, e2, shader.varyingCount(), varyings);
  FragmentInput in;
  in.x = x;
  in.y = y;
  in.depth = depth;
  in.facing = t.facing;
  in.varyings = varyings;
  for (int i = 0; i < 3; ++i) in.triangle[i] = t.v[i].source;
  return shader.shade(in);
}

}  // namespace shadowref
