#include "explore/views_adapter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "scene/scene_sections.h"
#include "shadow/draw_tag.h"
#include "shadow/frame_renderer.h"
#include "shadow/scene_view.h"
#include "shadow/soft_lights.h"
#include "shadow/technique_registry.h"
#include "views/depth_view.h"
#include "views/pixel_history.h"
#include "views/stencil_counts_view.h"
#include "views/volume_colours.h"

namespace shadowref::explore {

namespace {

// 8-bit colour exactly as the PNG writer makes it: clamp to [0, 1], round(c * 255) in double with
// halves up, NaN as 0 — so that the explorer's frame is the bytes `shadowref render` writes.
uint8_t toByte(double v01) {
  if (!(v01 > 0.0)) return 0;
  if (v01 >= 1.0) return 255;
  return uint8_t(std::round(v01 * 255.0));
}

// The framebuffer's colour, top row first (the framebuffer's row 0 is the bottom).
void colourToRgba(const Framebuffer& fb, ViewImage& out) {
  out.width = fb.width();
  out.height = fb.height();
  out.rgba.assign(size_t(out.width) * size_t(out.height) * 4, 255);
  for (int y = 0; y < fb.height(); ++y) {
    const size_t row = size_t(fb.height() - 1 - y) * size_t(fb.width());
    for (int x = 0; x < fb.width(); ++x) {
      const glm::vec4 c = fb.colorAt(x, y);
      uint8_t* p = &out.rgba[(row + size_t(x)) * 4];
      p[0] = toByte(double(c.r));
      p[1] = toByte(double(c.g));
      p[2] = toByte(double(c.b));
    }
  }
}

// Values in framebuffer order (row 0 at the bottom) as grey, top row first, lo black and hi white
// (the visibility: 0 in shadow, 1 lit, as --dump visibility).
void greyToRgba(const std::vector<float>& values, int width, int height, double lo, double hi, ViewImage& out) {
  out.width = width;
  out.height = height;
  out.rgba.assign(size_t(width) * size_t(height) * 4, 255);
  out.values.assign(values.size(), 0.0f);
  const double range = hi > lo ? hi - lo : 1.0;
  for (int y = 0; y < height; ++y) {
    const size_t from = size_t(y) * size_t(width);
    const size_t to = size_t(height - 1 - y) * size_t(width);
    for (int x = 0; x < width; ++x) {
      const float v = values[from + size_t(x)];
      out.values[to + size_t(x)] = v;
      uint8_t* p = &out.rgba[(to + size_t(x)) * 4];
      const uint8_t g = toByte((double(v) - lo) / range);
      p[0] = p[1] = p[2] = g;
    }
  }
}

// A teaching view's picture (RGBA, top row first) and its legend as the page draws them: the
// swatches of a few counts, or the range of a colour bar or ramp with the colour map's 256 steps.
void copyView(const views::View& view, ViewImage& out) {
  out.width = view.picture.width;
  out.height = view.picture.height;
  out.rgba = view.picture.pixels;
  const views::ViewLegend& legend = view.legend;
  if (legend.kind == views::LegendKind::Swatches) {
    nlohmann::json entries = nlohmann::json::array();
    for (size_t i = 0; i < legend.values.size(); ++i)
      entries.push_back({{"count", legend.values[i]},
                         {"rgb", {legend.colours[i][0], legend.colours[i][1], legend.colours[i][2]}}});
    out.info["legend"] = entries;
  } else if (legend.kind == views::LegendKind::ColourBar || legend.kind == views::LegendKind::Ramp) {
    out.info["range"] = {legend.lo, legend.hi};
    nlohmann::json ramp = nlohmann::json::array();
    for (int i = 0; i < 256; ++i) {
      const views::Rgb8 c = views::viridis(double(i) / 255.0);
      ramp.push_back({c[0], c[1], c[2]});
    }
    out.info["ramp"] = ramp;
  }
}

// Values in framebuffer order (row 0 at the bottom) as the page's per-pixel values, top row first.
std::vector<float> topRowFirst(const std::vector<float>& values, int width, int height) {
  std::vector<float> out(values.size());
  for (int y = 0; y < height; ++y)
    std::copy_n(values.begin() + ptrdiff_t(y) * width, width, out.begin() + ptrdiff_t(height - 1 - y) * width);
  return out;
}

// The stencil view of `stencil` (framebuffer order), with its counts as the per-pixel values.
void stencilToView(std::span<const uint8_t> stencil, int w, int h, bool signedCounts, ViewImage& out) {
  views::StencilViewSettings settings;
  settings.signedCounts = signedCounts;
  copyView(views::stencilView(stencil, w, h, settings), out);
  std::vector<float> counts(stencil.size());
  for (size_t i = 0; i < stencil.size(); ++i) counts[i] = float(views::stencilCountOf(stencil[i], signedCounts));
  out.values = topRowFirst(counts, w, h);
  out.valueName = "count";
}

// The numbers of the lights and passes there are, for the page's choosers.
void addNames(const FrameResult& frame, const std::vector<std::string>& passes, const Scene& scene, nlohmann::json& info) {
  info["passes"] = passes;
  info["shadowMaps"] = frame.shadowMapNames;
  nlohmann::json lights = nlohmann::json::array();
  for (const Light& l : scene.lights) lights.push_back(l.name);
  info["lights"] = lights;
}

FrameOptions baseOptions(const PipelineMaker& pipelines) {
  FrameOptions options;
  options.pipelines = &pipelines;
  options.pipeline = pipelines.kind();
  options.threads = pipelines.threads();
  return options;
}

}  // namespace

bool parseView(const std::string& name, View& view) {
  static const std::pair<const char*, View> names[] = {
      {"frame", View::Frame},         {"stencil", View::Stencil}, {"volumes", View::Volumes},
      {"overlay", View::Overlay},     {"depth", View::Depth},     {"shadowmap", View::ShadowMap},
      {"visibility", View::Visibility}, {"pass", View::Pass}};
  for (const auto& [n, v] : names)
    if (name == n) {
      view = v;
      return true;
    }
  return false;
}

const char* viewName(View view) {
  switch (view) {
    case View::Frame: return "frame";
    case View::Stencil: return "stencil";
    case View::Volumes: return "volumes";
    case View::Overlay: return "overlay";
    case View::Depth: return "depth";
    case View::ShadowMap: return "shadowmap";
    case View::Visibility: return "visibility";
    case View::Pass: return "pass";
  }
  return "?";
}

ViewImage renderView(const Scene& scene, const ViewRequest& request, const PipelineMaker& pipelines) {
  FrameOptions options = baseOptions(pipelines);
  ViewImage out;
  std::vector<std::string> passes;
  const View view = request.view;
  const bool counts = techniqueOf(scene.shadow).countsInStencil;
  if (view == View::Stencil && !counts)
    throw std::runtime_error("the method '" + scene.shadow.method + "' keeps no stencil counts; choose a shadow-volume method");
  if (view == View::Volumes || view == View::Overlay) {
    if (!counts) throw std::runtime_error("the method '" + scene.shadow.method + "' draws no shadow volumes");
    options.volumeView = view == View::Volumes ? VolumeViewMode::FrontBack : VolumeViewMode::Overlay;
    if (view == View::Volumes) options.volumeColours = views::volumeColours(scene);  // as render --view volumes
  }
  options.keepStencil = view == View::Stencil;
  options.keepShadowMaps = view == View::ShadowMap;
  options.keepVisibility = view == View::Visibility;
  bool passFound = false;
  options.onPass = [&](const std::string& pass, const Framebuffer& fb) {
    const int number = int(passes.size());
    passes.push_back(pass);
    if (view != View::Pass || number != request.index) return;
    passFound = true;
    if (pass.find("stencil") != std::string::npos && fb.hasStencil()) {
      stencilToView(std::span<const uint8_t>(fb.stencil().data(), fb.stencil().size()), fb.width(), fb.height(),
                    request.signedCounts, out);
    } else if (fb.hasColor()) {
      colourToRgba(fb, out);
    }
  };
  const FrameResult frame = renderFrame(scene, options);
  switch (view) {
    case View::Frame:
    case View::Volumes:
    case View::Overlay: colourToRgba(frame.framebuffer, out); break;
    case View::Stencil: {
      if (request.index < 0 || size_t(request.index) >= frame.stencilPerLight.size())
        throw std::invalid_argument("light " + std::to_string(request.index) + ": there are " +
                                    std::to_string(frame.stencilPerLight.size()) + " stencil counts (one per light)");
      const PixelVector<uint8_t>& stencil = frame.stencilPerLight[size_t(request.index)];
      stencilToView(std::span<const uint8_t>(stencil.data(), stencil.size()), frame.framebuffer.width(),
                    frame.framebuffer.height(), request.signedCounts, out);
      out.info["light"] = frame.stencilLightNames[size_t(request.index)];
      break;
    }
    case View::Depth: {
      const Framebuffer& fb = frame.framebuffer;
      if (!fb.hasDepth()) throw std::runtime_error("this frame has no depth buffer");
      // The views module's picture (eye distance on viridis, as --dump depth) and the eye distance
      // of each pixel under the mouse (+infinity where nothing was drawn).
      const SceneView camera = makeCameraView(scene, techniqueOf(scene.shadow).drawsVolumes);
      std::vector<float> window(fb.depthCodes().size()), eye(window.size());
      for (size_t i = 0; i < window.size(); ++i) {
        const double d = fb.depthCodec().decode(fb.depthCodes()[i]);
        window[i] = float(d);
        eye[i] = d >= 1.0 ? std::numeric_limits<float>::infinity()
                          : float(views::eyeDistance(d, camera.projection, camera.viewport));
      }
      copyView(views::depthView(window, fb.width(), fb.height(), camera.projection, camera.viewport), out);
      out.values = topRowFirst(eye, fb.width(), fb.height());
      out.valueName = "eye depth";
      break;
    }
    case View::ShadowMap: {
      if (frame.shadowMaps.empty()) throw std::runtime_error("the method '" + scene.shadow.method + "' renders no shadow map");
      if (request.index < 0 || size_t(request.index) >= frame.shadowMaps.size())
        throw std::invalid_argument("map " + std::to_string(request.index) + ": there are " +
                                    std::to_string(frame.shadowMaps.size()) + " shadow maps");
      const DepthTexture& map = frame.shadowMaps[size_t(request.index)];
      const std::vector<float> depth = map.values();
      views::View picture = views::shadowMapView(depth, map.width, map.height);
      views::drawShadowMapOutline(picture, frame.shadowMapOutlines[size_t(request.index)]);
      copyView(picture, out);
      nlohmann::json outlines = nlohmann::json::array();
      for (const auto& [what, rgb] : picture.legend.outlines) outlines.push_back({{"what", what}, {"rgb", {rgb[0], rgb[1], rgb[2]}}});
      out.info["outlines"] = outlines;
      out.values = topRowFirst(depth, map.width, map.height);
      out.valueName = "stored depth";
      out.info["map"] = frame.shadowMapNames[size_t(request.index)];
      break;
    }
    case View::Visibility: {
      if (request.index < 0 || size_t(request.index) >= frame.visibility.size())
        throw std::invalid_argument("light " + std::to_string(request.index) + ": the scene has " +
                                    std::to_string(frame.visibility.size()) + " lights");
      greyToRgba(frame.visibility[size_t(request.index)], frame.framebuffer.width(), frame.framebuffer.height(), 0.0,
                 1.0, out);
      out.valueName = "visibility";
      out.info["range"] = {0.0, 1.0};
      break;
    }
    case View::Pass:
      if (!passFound)
        throw std::invalid_argument("pass " + std::to_string(request.index) + ": this frame has " +
                                    std::to_string(passes.size()) + " passes");
      out.info["pass"] = passes[size_t(request.index)];
      break;
  }
  addNames(frame, passes, scene, out.info);
  out.info["view"] = viewName(view);
  return out;
}

namespace {

nlohmann::json lookupJson(const views::HistoryLookup& l) {
  const ShadowLookupTrace& t = l.trace;
  nlohmann::json j;
  j["light"] = "L" + std::to_string(l.light);
  j["lightName"] = l.lightName;
  if (t.face >= 0) j["face"] = t.face;
  j["strq"] = {t.strq.x, t.strq.y, t.strq.z, t.strq.w};
  j["str"] = {t.s, t.t, t.r};
  j["result"] = t.result;
  if (t.behindLight) {
    j["outcome"] = "behind the light: lit";
    return j;
  }
  if (t.outsideMap) {
    j["outcome"] = "outside the map fitted to the casters: lit";
    return j;
  }
  j["texel"] = {t.texelX, t.texelY};
  j["mapSize"] = {t.mapWidth, t.mapHeight};
  j["stored"] = t.stored;
  j["compared"] = t.compared;
  j["passed"] = t.passed;
  j["pcf"] = t.pcf;
  j["outcome"] = t.passed ? "r <= D: lit" : "r > D: shadowed";
  return j;
}

}  // namespace

nlohmann::json pixelHistory(const Scene& scene, int x, int y, bool signedCounts) {
  const std::vector<Instance> instances = scene.instances();
  views::PixelHistory history(x, y);  // the history `render --pixel-history` prints
  FrameOptions options;
  options.pipeline = PipelineKind::Reference;  // the pixel history's events are the reference's
  options.keepVisibility = true;
  options.keepStencil = techniqueOf(scene.shadow).countsInStencil;
  history.attach(options);
  const FrameResult frame = renderFrame(scene, options);
  // L<i>: the lights as the passes number them, soft ones expanded (as the command line names them).
  std::vector<std::string> lightNames;
  for (const Light& light : scene.lights)
    for (const Light& l : expandSoftLight(light)) lightNames.push_back(l.name);
  const auto count = [&](uint8_t v) { return views::stencilCountOf(v, signedCounts); };
  nlohmann::json steps = nlohmann::json::array();
  nlohmann::json passes = nlohmann::json::array();
  for (const views::HistoryPass& pass : history.passes()) {
    const std::string passName = pass.name.empty() ? "(unfinished)" : pass.name;
    std::string lightName;
    if (!pass.light.empty()) {
      const size_t i = std::stoul(pass.light.substr(1));
      if (i < lightNames.size()) lightName = lightNames[i];
    }
    nlohmann::json p{{"name", passName}, {"light", pass.light}, {"lightName", lightName}, {"steps", pass.steps.size()}};
    if (pass.stencilAfter) p["stencilAfter"] = count(*pass.stencilAfter);
    passes.push_back(p);
    for (const views::HistoryStep& step : pass.steps) {
      nlohmann::json f{{"pass", passName}, {"light", pass.light}, {"lightName", lightName}};
      if (step.kind == views::HistoryStep::Kind::Clear) {
        const ClearEvent& c = step.clear;
        f["type"] = "clear";
        f["stencil"] = c.stencilAfter ? nlohmann::json{count(*c.stencilBefore), count(*c.stencilAfter)} : nlohmann::json(nullptr);
        f["depth"] = c.depthAfter ? nlohmann::json{*c.depthBefore, *c.depthAfter} : nlohmann::json(nullptr);
        f["colour"] = c.color;
        steps.push_back(std::move(f));
        continue;
      }
      const FragmentEvent& e = step.fragment;
      f["type"] = "fragment";
      f["draw"] = e.drawIndex;
      f["what"] = describeDrawTag(e.drawTag, instances);
      f["kind"] = name(drawKindOf(e.drawTag));
      f["facing"] = e.facing == FrontFacing ? "front" : "back";
      f["depth"] = e.depth;
      f["storedDepth"] = e.storedDepth;
      f["stencilTest"] = e.stencilPassed;
      f["depthTest"] = e.stencilPassed ? nlohmann::json(e.depthPassed) : nlohmann::json(nullptr);
      f["stencilBefore"] = count(e.stencilBefore);
      f["stencilAfter"] = count(e.stencilAfter);
      if (e.colorAfter != e.colorBefore) f["colour"] = {e.colorAfter.r, e.colorAfter.g, e.colorAfter.b};
      nlohmann::json lookups = nlohmann::json::array();
      for (const views::HistoryLookup& l : step.lookups) lookups.push_back(lookupJson(l));
      if (!lookups.empty()) f["lookups"] = std::move(lookups);
      steps.push_back(std::move(f));
    }
  }
  nlohmann::json out;
  out["x"] = x;
  out["y"] = y;
  out["signed"] = signedCounts;
  out["fragments"] = history.fragmentCount();
  out["steps"] = std::move(steps);
  out["passes"] = std::move(passes);
  out["lightNames"] = lightNames;
  const glm::vec4 c = frame.framebuffer.colorAt(x, y);
  out["colour"] = {toByte(double(c.r)), toByte(double(c.g)), toByte(double(c.b))};
  const size_t i = size_t(y) * size_t(frame.framebuffer.width()) + size_t(x);
  nlohmann::json visibility = nlohmann::json::object();
  for (size_t l = 0; l < frame.visibility.size(); ++l) visibility[scene.lights[l].name] = frame.visibility[l][i];
  out["visibility"] = visibility;
  nlohmann::json stencil = nlohmann::json::object();
  for (size_t l = 0; l < frame.stencilPerLight.size(); ++l)
    stencil[frame.stencilLightNames[l]] = count(frame.stencilPerLight[l][i]);
  out["stencil"] = stencil;
  return out;
}

nlohmann::json sceneSummary(const Scene& scene) {
  nlohmann::json s;
  s["source"] = scene.sourceFile;
  s["width"] = scene.width;
  s["height"] = scene.height;
  const Camera& c = scene.camera;
  s["camera"] = {{"eye", {c.eye.x, c.eye.y, c.eye.z}},
                 {"target", {c.target.x, c.target.y, c.target.z}},
                 {"up", {c.up.x, c.up.y, c.up.z}},
                 {"fov", c.fovYDegrees},
                 {"near", c.nearPlane}};
  nlohmann::json lights = nlohmann::json::array();
  for (const Light& l : scene.lights) {
    lights.push_back({{"name", l.name},
                      {"type", std::string(enumName(lightTypeNames(), l.type))},
                      {"position", {l.position.x, l.position.y, l.position.z}},
                      {"direction", {l.direction.x, l.direction.y, l.direction.z}},
                      {"soft", std::string(enumName(softShapeNames(), l.soft))}});
  }
  s["lights"] = lights;
  const ShadowSettings& sh = scene.shadow;
  s["shadow"] = {{"method", sh.method},     {"two_sided", sh.twoSidedStencil}, {"wrap", sh.wrapOps},
                 {"darken_composite", sh.darkenComposite}, {"map_size", sh.mapSize}, {"pcf", sh.pcf}};
  nlohmann::json methods = nlohmann::json::array();
  for (const ShadowTechnique* t : techniques()) {
    nlohmann::json reads = nlohmann::json::array();  // the shadow.* keys it reads: the page offers those
    for (const TechniqueSetting& setting : t->settings) reads.push_back(std::string(setting.key));
    methods.push_back({{"name", std::string(t->name)}, {"summary", std::string(t->summary)},
                       {"stencil", t->countsInStencil}, {"settings", reads}});
  }
  s["methods"] = methods;
  nlohmann::json shapes = nlohmann::json::array();
  for (const auto& [n, v] : softShapeNames()) shapes.push_back(std::string(n));
  s["softShapes"] = shapes;
  const Aabb bounds = worldBounds(scene.instances());
  s["bounds"] = {{"min", {bounds.min.x, bounds.min.y, bounds.min.z}}, {"max", {bounds.max.x, bounds.max.y, bounds.max.z}}};
  return s;
}

nlohmann::json frameStatistics(const Scene& scene, const PipelineMaker& pipelines) {
  const FrameResult frame = renderFrame(scene, baseOptions(pipelines));
  const RasterStats& st = frame.stats;
  nlohmann::json out;
  out["triangles"] = {{"in", st.trianglesIn}, {"clipped", st.trianglesClipped}, {"culled", st.trianglesCulled},
                      {"rasterized", st.trianglesRasterized}};
  out["fragments"] = {{"all", st.fragments}, {"stencilFailed", st.stencilFailed}, {"depthFailed", st.depthFailed},
                      {"stencilWrites", st.stencilWrites}, {"colourWrites", st.colorWrites}};
  out["notes"] = frame.notes;
  nlohmann::json timings = nlohmann::json::array();
  for (const PassTiming& t : frame.timings) timings.push_back({{"pass", t.pass}, {"ms", t.milliseconds}});
  out["timings"] = timings;
  out["warnings"] = frame.warnings;
  return out;
}

}  // namespace shadowref::explore
