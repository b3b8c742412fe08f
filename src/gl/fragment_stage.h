// The fragment stage ([GL 2.1, §3.5.1, §3.5.5, §3.11]): what a covered pixel (coverage.h) carries
// into the per-fragment operations — its window depth at the pixel centre, its varyings
// interpolated perspective-correctly, and the colour the shader makes of them. The fast executor
// (exec/fragment_processor.cpp) calls these functions for its one-fragment path and computes the
// same operations in the same order in its span loops, so these definitions own the bits.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "gl/fragment_shader.h"
#include "gl/render_state.h"
#include "gl/triangle_setup.h"

namespace shadowref {

// Window depth at the centre of pixel (x, y): the triangle's depth plane (planeDepthAt, through the
// unsnapped vertices), plus the polygon offset of its setup ([GL 2.1, §3.5.5]), then with depth
// clamp (ARB_depth_clamp) clamped to the depth range. The clamp to [0, 1] is the depth codec's,
// when the depth is converted to the buffer's format (DepthCodec::encode).
double fragmentDepth(const TriangleSetup& t, int x, int y, const RenderState& state);

// The first `count` varyings at a pixel whose unbiased edge values are e0, e1, e2
// (E_i = lambda_i * area2): weights lambda_i / w_i, normalised by their sum, so area2 cancels
// ([GL 2.1, §3.5.1, eq. 3.6]). Clipped vertices carry their varyings interpolated linearly in clip
// space (clipper.cpp), which is the same perspective-correct interpolation.
void interpolateVaryings(const TriangleSetup& t, int64_t e0, int64_t e1, int64_t e2, int count, double* out);

// The shader's colour for the fragment at (x, y) with window depth `depth` (the depth as the
// buffer holds it: decoded from its code) and edge values e0, e1, e2.
glm::dvec4 shadeFragment(const FragmentShader& shader, const TriangleSetup& t, int x, int y, double depth, int64_t e0,
                         int64_t e1, int64_t e2);

}  // namespace shadowref
