// The public interface (include/shadowref/shadowref.h) over the scene loader, the technique
// registry and the frame renderer. Nothing here renders or loads by itself: every byte comes from
// the same functions the command line calls, so a frame from the library is the CLI's frame.
#include "shadowref/shadowref.h"

#include <exception>

#include "scene/animation.h"
#include "scene/scene.h"
#include "scene/scene_error.h"
#include "scene/scene_loader.h"
#include "shadow/draw_tag.h"
#include "shadow/frame_renderer.h"
#include "shadow/technique.h"
#include "shadow/technique_registry.h"

namespace shadowref::api {

struct Scene::Impl {
  shadowref::Scene scene;
};

namespace {

// Runs a load, turning every failure into Error with the loader's "file:line:col: message" (or,
// for a failure with no place, "name: message").
template <typename Load>
Scene::Impl loadOrThrow(const std::string& name, Load load) {
  try {
    shadowref::Scene scene = load();
    techniqueOf(scene.shadow);  // an unknown shadow.method is an error at its place, as in `check`
    return Scene::Impl{std::move(scene)};
  } catch (const SceneError& e) {
    throw Error(e.what());
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(name + ": " + e.what());
  }
}

class HistoryRecorder final : public FragmentObserver {
 public:
  explicit HistoryRecorder(const std::vector<Instance>& instances) : instances_(instances) {}
  void onFragment(const FragmentEvent& e) override {
    FragmentRecord r;
    r.draw = e.drawIndex;
    r.what = describeDrawTag(e.drawTag, instances_);
    r.front = e.facing == FrontFacing;
    r.depth = e.depth;
    r.storedDepth = e.storedDepth;
    r.stencilPassed = e.stencilPassed;
    r.depthPassed = e.depthPassed;
    r.stencilBefore = e.stencilBefore;
    r.stencilAfter = e.stencilAfter;
    for (int k = 0; k < 4; ++k) {
      r.colorBefore[k] = e.colorBefore[k];
      r.colorAfter[k] = e.colorAfter[k];
    }
    records.push_back(std::move(r));
  }
  std::vector<FragmentRecord> records;

 private:
  const std::vector<Instance>& instances_;
};

std::vector<float> rgba(const PixelVector<glm::vec4>& pixels) {
  std::vector<float> values;
  values.reserve(pixels.size() * 4);
  for (const glm::vec4& p : pixels)
    for (int k = 0; k < 4; ++k) values.push_back(p[k]);
  return values;
}

}  // namespace

std::string version() { return SHADOWREF_API_VERSION; }

std::vector<std::string> methods() {
  std::vector<std::string> names;
  for (const ShadowTechnique* t : techniques()) names.emplace_back(t->name);
  return names;
}

Scene::Scene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;
Scene::~Scene() = default;

Scene Scene::fromFile(const std::string& path, const std::vector<std::string>& overrides) {
  LoadOptions options;
  options.overrides = overrides;
  return Scene(std::make_unique<Impl>(loadOrThrow(path, [&] { return loadScene(path, options); })));
}

Scene Scene::fromString(const std::string& yaml, const std::string& name, const std::vector<std::string>& overrides) {
  LoadOptions options;
  options.overrides = overrides;
  return Scene(std::make_unique<Impl>(loadOrThrow(name, [&] { return loadSceneFromString(yaml, name, options); })));
}

int Scene::width() const { return impl_->scene.width; }
int Scene::height() const { return impl_->scene.height; }
std::string Scene::method() const { return impl_->scene.shadow.method; }
bool Scene::animated() const { return impl_->scene.animation != nullptr; }
double Scene::fps() const { return impl_->scene.animation ? impl_->scene.animation->fps : 24.0; }
Scene Scene::at(double seconds) const {
  return Scene(std::make_unique<Impl>(loadOrThrow(impl_->scene.sourceFile, [&] { return sceneAt(impl_->scene, seconds); })));
}

Frame render(const Scene& scene, const RenderOptions& options) {
  const shadowref::Scene& s = scene.impl().scene;
  FrameOptions frameOptions;
  frameOptions.method = options.method;
  if (!options.method.empty() && !findTechnique(options.method))
    throw Error("method: " + unknownTechniqueMessage(options.method));
  frameOptions.pipeline = options.pipeline == Pipeline::Reference ? PipelineKind::Reference : PipelineKind::Fast;
  frameOptions.threads = options.threads;
  frameOptions.keepStencil = options.stencilPerLight;
  const std::vector<Instance> instances = s.instances();
  HistoryRecorder history(instances);
  if (options.historyX >= 0 || options.historyY >= 0) {
    if (options.historyX < 0 || options.historyY < 0 || options.historyX >= s.width || options.historyY >= s.height)
      throw Error("pixel history: (" + std::to_string(options.historyX) + ", " + std::to_string(options.historyY) +
                  ") is outside the " + std::to_string(s.width) + "x" + std::to_string(s.height) + " image");
    frameOptions.watchX = options.historyX;
    frameOptions.watchY = options.historyY;
    frameOptions.observer = &history;
    frameOptions.pipeline = PipelineKind::Reference;  // the history's events are the reference's
  }
  const FrameResult result = [&] {
    try {
      return renderFrame(s, frameOptions);
    } catch (const SceneError& e) {
      throw Error(e.what());
    }
  }();
  const Framebuffer& fb = result.framebuffer;
  Frame frame;
  frame.width = fb.width();
  frame.height = fb.height();
  frame.threads = pipelineThreads(frameOptions.pipeline, frameOptions.threads);
  if (fb.hasColor()) frame.color = rgba(fb.color());
  if (fb.hasDepth()) {
    frame.depth.resize(fb.depthCodes().size());
    for (size_t i = 0; i < frame.depth.size(); ++i) frame.depth[i] = float(fb.depthCodec().decode(fb.depthCodes()[i]));
  }
  if (fb.hasStencil()) frame.stencil.assign(fb.stencil().begin(), fb.stencil().end());
  if (fb.hasAccum()) frame.accumulation = rgba(fb.accum());
  for (const PixelVector<uint8_t>& counts : result.stencilPerLight) frame.stencilPerLight.emplace_back(counts.begin(), counts.end());
  frame.lightNames = result.stencilLightNames;
  frame.history = std::move(history.records);
  return frame;
}

}  // namespace shadowref::api
