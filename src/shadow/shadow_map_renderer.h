// Shadow mapping [Williams 1978], the whole frame ([Hempe 2004, §3.1, §4.1, §4.2, §5]):
//   1. per light, the depth map from the light: orthographic for a directional light, perspective
//      for a spot light, six cube faces for a point light (beyond the documents); polygon offset
//      or back faces only against self-shadowing; for TSM the light's clip space warped by N_T;
//   2. the camera pass: every fragment's world position through T = bias · (N_T ·) P_light ·
//      V_light, divided by q, compared R <= D; failing fragments are modulated by the
//      compare-fail value ([Hempe 2004, §5.1.2]: GL_MODULATE with
//      GL_TEXTURE_COMPARE_FAIL_VALUE 0.4);
//   3. soft shadows ([Hempe 2004, §4.2, §5.3]): the frame rendered once per position on the edge of
//   the
//      square area light, each ACCUMed with weight 1/n, then RETURN.
#pragma once

#include <memory>
#include <vector>

#include "gl/lighting.h"
#include "gl/pipeline.h"
#include "scene/scene.h"
#include "shadow/frame_renderer.h"

namespace shadowref {

// The light's clip space as it is, or warped by the trapezoid N_T (TSM, [Hempe 2004, §4.1]).
enum class ShadowMapKind : uint8_t { Standard, Trapezoidal };

void renderShadowMaps(const Scene& scene, ShadowMapKind kind, const FrameOptions& options, FrameResult& result,
                      Pipeline& pipeline);

struct LightShadow;
// The camera pass's shaders (step 2), for a replay of a captured frame (src/trace): lit per pixel
// by `setup` and modulated by each light's shadow test, or for a Gouraud material the per-vertex
// colours of each light modulated so (at most 4 lights: std::invalid_argument beyond).
std::unique_ptr<FragmentShader> makeShadowMappedShader(const LightingSetup& setup, std::vector<const LightShadow*> shadows);
std::unique_ptr<FragmentShader> makeShadowMappedGouraudShader(std::vector<const LightShadow*> shadows);

}  // namespace shadowref
