#include "extremes/depth_code.h"

#include <vector>

#include "gl/pipeline.h"

namespace shadowref::extremes {

uint32_t depthCode(const glm::dmat4& projection, double distance, DepthFormat format) {
  Framebuffer fb(1, 1, format);
  const auto pipeline = makePipeline(PipelineKind::Fast, fb);
  RenderState state;
  state.viewport = Viewport{0, 0, 1, 1, 0.0, 1.0};
  state.clipFar = false;  // the far plane itself (z_w = 1) is a depth we want to read
  state.depthTest = true;
  state.depthFunc = CompareFunc::Always;
  // A square facing the camera, wider than the frustum at that distance for any fov below 170°.
  const double h = 20.0 * distance;
  std::vector<ClipVertex> quad(6);
  const glm::dvec2 corners[6] = {{-h, -h}, {h, -h}, {h, h}, {-h, -h}, {h, h}, {-h, h}};
  for (int i = 0; i < 6; ++i) quad[i].position = projection * glm::dvec4(corners[i], -distance, 1.0);
  DrawCall call;
  call.state = &state;
  call.vertices = quad;
  pipeline->draw(call);
  return pipeline->framebuffer().depthCodes()[0];
}

}  // namespace shadowref::extremes
