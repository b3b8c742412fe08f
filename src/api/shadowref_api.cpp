// The public interface (include/shadowref/shadowref.h) over the scene loader, the technique
// registry and the frame renderer. Nothing here renders or loads by itself: every byte comes from
// the same functions the command line calls, so a frame from the library is the CLI's frame.
#include "shadowref/shadowref.h"

#include <cmath>
#include <exception>
#include <filesystem>
#include <limits>
#include <optional>

#include "api/scene_impl.h"
#include "image/image_writer.h"
#include "image/output_metadata.h"
#include "scene/animation.h"
#include "scene/checked_arithmetic.h"
#include "scene/scene.h"
#include "scene/scene_error.h"
#include "scene/scene_loader.h"
#include "shadow/draw_tag.h"
#include "shadow/frame_renderer.h"
#include "shadow/scene_view.h"
#include "shadow/soft_lights.h"
#include "shadow/technique.h"
#include "shadow/technique_registry.h"

namespace shadowref::api {

// What writeImage needs beyond the Frame's copies: the renderer's own framebuffer (depth codes,
// not decoded floats) and the settings the metadata names.
struct FrameData {
  FrameResult result;
  std::vector<std::string> lightNames;  // the scene's, for the visibility channels
  OutputMetadata metadata;
};

namespace {

// Runs a load, turning every failure into Error with the loader's "file:line:col: message" (or,
// for a failure with no place, "name: message").
template <typename Load>
Scene::Impl loadOrThrow(const std::string& name, Load load) {
  try {
    shadowref::Scene scene = load();
    techniqueOf(scene.shadow);  // an unknown shadow.method is an error at its place, as in `check`
    return Scene::Impl{std::move(scene), name, {}};
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

// The eye-space distance of every pixel: the window depth d mapped back through the third and
// fourth rows of the projection the frame was drawn with (z_ndc = 2d - 1 for the depth range
// [0, 1] [GL 2.1, §2.11.1]). With clip z = a·z_e + b and clip w = c·z_e + e (w_e = 1),
// z_ndc = (a·z_e + b) / (c·z_e + e), so z_e = (b - z_ndc·e) / (z_ndc·c - a); the camera looks
// down -z, so the distance is -z_e. Shadow volumes draw through the infinite projection
// ([Kuhn 2016, §3.3]), where depth 1 is infinitely far.
std::vector<double> eyeDepths(const shadowref::Scene& scene, const ShadowTechnique& sceneTechnique,
                              const std::string& method, const Framebuffer& fb) {
  const ShadowTechnique* technique = method.empty() ? &sceneTechnique : findTechnique(method);
  const SceneView view = makeCameraView(scene, technique && technique->countsInStencil);
  const double a = view.projection[2][2], b = view.projection[3][2];
  const double c = view.projection[2][3], e = view.projection[3][3];
  std::vector<double> eye(fb.depthCodes().size());
  for (size_t i = 0; i < eye.size(); ++i) {
    const double ndc = 2.0 * fb.depthCodec().decode(fb.depthCodes()[i]) - 1.0;
    const double denominator = ndc * c - a;
    eye[i] = denominator == 0.0 ? std::numeric_limits<double>::infinity() : -(b - ndc * e) / denominator;
  }
  return eye;
}

// The buffers a frame keeps per light are bounded before anything is rendered, with the limits
// of `render --dump stencil` and `--dump visibility`: 2^27 stencil counts (one byte each) and
// 2^26 visibility values (floats, counted and copied: about 1 GiB at most).
constexpr uint64_t kMaxKeptStencilCounts = uint64_t(1) << 27;
constexpr uint64_t kMaxVisibilityValues = uint64_t(1) << 26;

void checkKeptBuffers(const shadowref::Scene& s, const RenderOptions& options) {
  const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);  // within the scene's limits
  const std::string image = std::to_string(s.width) + "x" + std::to_string(s.height);
  if (options.stencilPerLight) {
    uint64_t lights = 0;
    for (const Light& light : s.lights) lights += expandSoftLight(light).size();
    const std::optional<uint64_t> counts = checkedMul(pixels, lights);
    if (!counts || *counts > kMaxKeptStencilCounts)
      throw Error("stencil per light: " + std::to_string(lights) + " lights x " + image +
                  " counts is more than the limit of 2^27; keep none (stencilPerLight = false), or render fewer "
                  "lights or a smaller image");
  }
  if (options.visibility) {
    const std::optional<uint64_t> values = checkedMul(pixels, uint64_t(s.lights.size()));
    if (!values || *values > kMaxVisibilityValues)
      throw Error("visibility: " + std::to_string(s.lights.size()) + " lights x " + image +
                  " values is more than the limit of 2^26; keep none (visibility = false), or render fewer lights "
                  "or a smaller image");
  }
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
  auto impl = std::make_unique<Impl>(loadOrThrow(path, [&] { return loadScene(path, options); }));
  impl->overrides = overrides;
  return Scene(std::move(impl));
}

Scene Scene::fromString(const std::string& yaml, const std::string& name, const std::vector<std::string>& overrides) {
  LoadOptions options;
  options.overrides = overrides;
  auto impl = std::make_unique<Impl>(loadOrThrow(name, [&] { return loadSceneFromString(yaml, name, options); }));
  impl->overrides = overrides;
  return Scene(std::move(impl));
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
  checkKeptBuffers(s, options);
  frameOptions.keepStencil = options.stencilPerLight;
  frameOptions.keepVisibility = options.visibility;
  frameOptions.keepShadowMaps = options.shadowMaps;
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
  FrameResult result = [&] {
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
    frame.eyeDepth = eyeDepths(s, techniqueOf(s.shadow), options.method, fb);
  }
  if (fb.hasStencil()) frame.stencil.assign(fb.stencil().begin(), fb.stencil().end());
  if (fb.hasAccum()) frame.accumulation = rgba(fb.accum());
  for (const PixelVector<uint8_t>& counts : result.stencilPerLight) frame.stencilPerLight.emplace_back(counts.begin(), counts.end());
  frame.lightNames = result.stencilLightNames;
  frame.history = std::move(history.records);
  frame.visibility = result.visibility;
  std::vector<std::string> sceneLights;
  for (const Light& light : s.lights) sceneLights.push_back(light.name);
  if (!frame.visibility.empty()) frame.visibilityNames = sceneLights;
  for (size_t i = 0; i < result.shadowMaps.size(); ++i) {
    const DepthTexture& map = result.shadowMaps[i];
    frame.shadowMaps.push_back({result.shadowMapNames[i], map.width, map.height, map.values()});
  }
  const RasterStats& st = result.stats;
  frame.statistics = {{"draw_calls", st.drawCalls},
                      {"triangles_in", st.trianglesIn},
                      {"triangles_clipped", st.trianglesClipped},
                      {"triangles_culled", st.trianglesCulled},
                      {"triangles_rasterized", st.trianglesRasterized},
                      {"fragments", st.fragments},
                      {"stencil_failed", st.stencilFailed},
                      {"depth_failed", st.depthFailed},
                      {"stencil_writes", st.stencilWrites},
                      {"color_writes", st.colorWrites}};
  for (const PassTiming& t : result.timings) frame.passMilliseconds.emplace_back(t.pass, t.milliseconds);
  frame.warnings = result.warnings;
  OutputMetadata metadata;
  metadata.software = "shadowref " + version();
  metadata.content = "frame";
  metadata.method = options.method.empty() ? s.shadow.method : options.method;
  metadata.scene = scene.impl().name;
  metadata.overrides = scene.impl().overrides;
  metadata.threads = frame.threads;
  metadata.pipeline = name(frameOptions.observer ? PipelineKind::Reference : frameOptions.pipeline);
  auto data = std::make_shared<FrameData>(FrameData{std::move(result), std::move(sceneLights), std::move(metadata)});
  frame.data = std::move(data);
  return frame;
}

void writeImage(const Frame& frame, const std::string& path) {
  if (!frame.data) throw Error(path + ": the frame holds no image (it was not made by render)");
  const FrameResult& result = frame.data->result;
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png" && ext != ".exr") throw Error(path + ": unknown image extension '" + ext + "' (.png or .exr)");
  // The channels `render -o x.exr --dump stencil --dump visibility` writes, as far as the frame kept them.
  OutputMetadata metadata = frame.data->metadata;
  if (ext == ".png") return shadowref::writeImage(result.framebuffer, path, metadata);
  ExrExtras extras = perLightStencilChannels(result.stencilPerLight, result.stencilLightNames);
  for (size_t i = 0; i < result.visibility.size(); ++i) {
    const std::string channel = "visibility.L" + std::to_string(i);
    extras.channels.push_back(NamedChannel::floatChannel(channel, result.visibility[i]));
    metadata.extra.emplace_back("shadowref:" + channel, frame.data->lightNames[i]);
  }
  writeExr(result.framebuffer, path, extras, metadata);
}

}  // namespace shadowref::api
