#include "shadow/frame_renderer.h"

#include <chrono>
#include <memory>
#include <stdexcept>

#include "gl/clear.h"
#include "gl/pipeline.h"
#include "shadow/scene_passes.h"
#include "shadow/scene_view.h"
#include "shadow/shadow_method.h"
#include "shadow/shadow_map_renderer.h"
#include "shadow/volume_renderer.h"

namespace shadowref {

namespace {

class PassClock {
 public:
  explicit PassClock(FrameResult& result) : result_(result) {}
  template <class Fn>
  void run(const std::string& pass, Fn&& fn) {
    const auto start = std::chrono::steady_clock::now();
    fn();
    const auto end = std::chrono::steady_clock::now();
    result_.timings.push_back({pass, std::chrono::duration<double, std::milli>(end - start).count()});
  }

 private:
  FrameResult& result_;
};

// No shadows: every light in one pass, with the ambient term.
void renderUnshadowed(const Scene& scene, const FrameOptions& options, FrameResult& result, Pipeline& pipeline) {
  const SceneView view = makeCameraView(scene);
  const std::vector<Instance> instances = scene.instances();
  const std::vector<PreparedInstance> prepared = prepareInstances(instances, view, &pipeline);
  RenderState state;
  state.viewport = view.viewport;
  state.clipFar = !view.infinite;
  state.depthTest = true;
  state.depthFunc = CompareFunc::Less;
  state.cull = CullMode::Back;
  PassClock clock(result);
  clock.run("lit", [&] {
    // The clear and the lit draws are one pass (drawLit ends it).
    pipeline.clear({.state = state, .color = glm::vec4(glm::vec3(scene.background), 1.0f), .depth = 1.0});
    drawLit(pipeline, state, scene, view, prepared, scene.lights, true);
  });
  if (options.onPass) options.onPass("01-lit", pipeline.framebuffer());
}

}  // namespace

std::string numberedPass(int& counter, const std::string& what) {
  const std::string number = std::to_string(++counter);
  return (number.size() < 2 ? "0" : "") + number + "-" + what;
}

FrameResult renderFrame(const Scene& scene, const FrameOptions& options) {
  const ShadowMethod method = options.method.value_or(scene.shadow.method);
  FrameResult result{Framebuffer(scene.width, scene.height, scene.depthFormat), {}, {}, {}, {}, {}, {}, {}};
  const std::unique_ptr<Pipeline> pipeline = makePipeline(options.pipeline, result.framebuffer, options.threads);
  if (!pipeline)
    throw std::runtime_error(std::string("the ") + name(options.pipeline) + " pipeline is not available in this build");
  if (options.observer) pipeline->watchPixel(options.watchX, options.watchY, options.observer);
  switch (method) {
    case ShadowMethod::None: renderUnshadowed(scene, options, result, *pipeline); break;
    case ShadowMethod::ZPass:
    case ShadowMethod::ZFail:
    case ShadowMethod::Auto: renderShadowVolumes(scene, method, options, result, *pipeline); break;
    case ShadowMethod::ShadowMap:
    case ShadowMethod::Trapezoidal: renderShadowMaps(scene, method, options, result, *pipeline); break;
    default:
      throw std::runtime_error(std::string("shadow method '") + name(method) + "' is not available in this build");
  }
  pipeline->endPass();  // before the result leaves: the framebuffer is complete
  result.stats += pipeline->stats();
  return result;
}

}  // namespace shadowref
