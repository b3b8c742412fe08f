#include "shadow/frame_renderer.h"

#include <chrono>
#include <memory>
#include <stdexcept>

#include "gl/clear.h"
#include "gl/pipeline.h"
#include "shadow/scene_passes.h"
#include "shadow/scene_view.h"
#include "shadow/technique_registry.h"
#include "shadow/visibility.h"

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
  if (options.keepVisibility) {
    VisibilityCounts counts(scene.lights.size(), pipeline.framebuffer().pixelCount());
    for (size_t l = 0; l < scene.lights.size(); ++l) counts.addLit(l);
    result.visibility = counts.finish();
  }
}

}  // namespace

std::string numberedPass(int& counter, const std::string& what) {
  const std::string number = std::to_string(++counter);
  return (number.size() < 2 ? "0" : "") + number + "-" + what;
}

FrameResult renderFrame(const Scene& scene, const FrameOptions& options) {
  const TechniqueList among = options.techniques.empty() ? techniques() : options.techniques;
  const ShadowTechnique* technique = nullptr;
  if (options.method.empty()) {
    technique = &techniqueOf(scene.shadow, among);
  } else {
    technique = findTechnique(options.method, among);
    if (!technique) throw std::invalid_argument("shadow method " + unknownTechniqueMessage(options.method, among));
  }
  FrameResult result{Framebuffer(scene.width, scene.height, scene.depthFormat), {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};
  // The pixel history always runs on the reference: its events are the definition.
  const PipelineKind kind = options.observer ? PipelineKind::Reference : options.pipeline;
  const std::unique_ptr<Pipeline> pipeline = options.pipelines && !options.observer
                                                 ? options.pipelines->make(result.framebuffer)
                                                 : makePipeline(kind, result.framebuffer, options.threads);
  if (!pipeline) throw std::runtime_error(std::string("the ") + name(kind) + " pipeline is not available in this build");
  if (options.observer) pipeline->watchPixel(options.watchX, options.watchY, options.observer);
  technique->render(scene, options, result, *pipeline);
  pipeline->endPass();  // before the result leaves: the framebuffer is complete
  if (options.keepVisibility && result.visibility.size() != scene.lights.size())
    throw std::runtime_error("the shadow method " + std::string(technique->name) + " computes no per-light visibility");
  result.stats += pipeline->stats();
  return result;
}

// The technique of this file (technique_registry.cpp lists it).
extern const ShadowTechnique kUnshadowedTechnique{
    .name = "none",
    .summary = "no shadows: every light in one lit pass",
    .settings = {},
    .countsInStencil = false,
    .render = renderUnshadowed,
    .describe = nullptr,
};

}  // namespace shadowref
