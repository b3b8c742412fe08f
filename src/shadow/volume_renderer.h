// Stencil shadow volumes ([Crow 1977], counted in the stencil buffer as in [Heidmann 1991]), the
// whole frame ([Kuhn 2016, §3.1, §4.2]; [SV slides]; [DSS article]):
//   1. ambient pass filling the depth buffer (P_inf, depth LESS);
//   2. per light (soft lights expanded): clear stencil, draw every shadow caster's volume into the
//      stencil buffer only, counting z-pass, z-fail or chosen per object (auto);
//   3. lit pass where stencil == 0, depth LEQUAL, added with ONE/ONE, so lights add up
//   ([DSS article]).
// Or the compositing of the [SV slides]: the fully lit scene first, then per light the ambient-only
// scene redrawn where stencil != 0.
#pragma once

#include "gl/pipeline.h"
#include "scene/scene.h"
#include "shadow/frame_renderer.h"
#include "shadow/scene_view.h"

namespace shadowref {

// The state every pass of renderShadowVolumes starts from: the camera's viewport under P_inf,
// without far clipping (the volumes reach infinity, [Kuhn 2016, §3.3]), back faces culled, depth
// LESS.
RenderState volumeBaseState(const SceneView& view);

// How the casters' volumes are counted: every one z-pass, every one z-fail, or each as McGuire's
// test chooses (the technique `auto`).
enum class VolumeCounting : uint8_t { ZPass, ZFail, PerCaster };

void renderShadowVolumes(const Scene& scene, VolumeCounting method, const FrameOptions& options, FrameResult& result,
                         Pipeline& pipeline);

}  // namespace shadowref
