// Teaching view of TSM ([Hempe 2004, §4.1]): the trapezoid drawn over the
// plain (unwarped) light view, so one sees which part of the light's view the warped map spends
// its texels on.
#pragma once

#include "gl/depth_compare_sampler.h"
#include "shadow/trapezoid.h"

namespace shadowref {

// Draws the trapezoid's four sides (light post-projective x-y, [−1, 1]² = the whole map) into
// the depth map as lines of depth `value` (0: black in a grey dump), and a small cross at the
// focus point. Texels outside the map are skipped.
void drawTrapezoidOutline(DepthTexture& map, const Trapezoid& trapezoid, float value = 0.0f);

}  // namespace shadowref
