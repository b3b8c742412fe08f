// Teaching view of TSM ([Hempe 2004, §4.1]): the trapezoid drawn over the
// plain (unwarped) light view, so one sees which part of the light's view the warped map spends
// its texels on.
#pragma once

#include <functional>

#include "gl/depth_compare_sampler.h"
#include "shadow/trapezoid.h"

namespace shadowref {

// The texels of a width x height map that the line from a to b (map x-y, [−1, 1]² = the whole map)
// passes through, sampled at half-texel steps (dense enough to leave no gaps, at most
// 4 (width + height) steps); texels outside the map are skipped, a texel may come twice. The
// trapezoid outline below and the teaching views' outlines (views/depth_view.h) draw with it.
void forEachLineTexel(int width, int height, const glm::dvec2& a, const glm::dvec2& b,
                      const std::function<void(int x, int y)>& texel);

// Draws the trapezoid's four sides (light post-projective x-y, [−1, 1]² = the whole map) into
// the depth map as lines of depth `value` (0: black in a grey dump), and a small cross at the
// focus point. Texels outside the map are skipped.
void drawTrapezoidOutline(DepthTexture& map, const Trapezoid& trapezoid, float value = 0.0f);

}  // namespace shadowref
