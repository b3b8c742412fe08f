#include "sweep/shadow_error.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "shadow/frame_renderer.h"
#include "shadow/soft_lights.h"
#include "oracle/oracle.h"
#include "sweep/soft_reference.h"

namespace shadowref::sweep {

const char* name(Reference reference) {
  switch (reference) {
    case Reference::HardLight: return "point";
    case Reference::AreaSquare: return "square";
    case Reference::AreaSphere: return "sphere";
  }
  return "?";
}

namespace {

using Plane = std::vector<float>;  // one value per pixel, framebuffer layout (row 0 at the bottom)

Plane brightness(const Framebuffer& fb) {
  Plane out(fb.color().size());
  for (size_t i = 0; i < out.size(); ++i) {
    const glm::vec4& c = fb.color()[i];
    out[i] = (c.r + c.g + c.b) / 3.0f;
  }
  return out;
}

Plane renderBrightness(const Scene& scene, std::string_view method, int threads) {
  FrameOptions options;
  options.method = method;
  options.threads = threads;
  return brightness(renderFrame(scene, options).framebuffer);
}

// The unshadowed frame with only light `only` switched on (-1: none, the ambient-only frame).
Plane unshadowedWith(const Scene& scene, int only, int threads) {
  Scene copy = scene;
  for (size_t i = 0; i < copy.lights.size(); ++i)
    if (static_cast<int>(i) != only) copy.lights[i].color = glm::dvec3(0.0);
  return renderBrightness(copy, "none", threads);
}

bool isVolumeMethod(std::string_view m) {
  return m == "zpass" || m == "zfail" || m == "auto";
}

// Shadow volumes: a pixel sees an (expanded) light where its stencil count is 0; a soft light's
// visibility is the share of its lights that see it (each carries colour / count,
// [Kuhn 2016, §3.6]).
std::vector<Plane> volumeVisibility(const Scene& scene, std::string_view method, int threads) {
  FrameOptions options;
  options.method = method;
  options.threads = threads;
  options.keepStencil = true;
  const FrameResult frame = renderFrame(scene, options);
  std::vector<Plane> out;
  size_t expanded = 0;
  for (const Light& light : scene.lights) {
    const size_t count = expandSoftLight(light).size();
    Plane v(frame.framebuffer.stencil().size(), 0.0f);
    for (size_t k = expanded; k < expanded + count; ++k) {
      if (k >= frame.stencilPerLight.size()) throw std::runtime_error("fewer stencil buffers than lights");
      const auto& s = frame.stencilPerLight[k];
      for (size_t i = 0; i < v.size(); ++i) v[i] += s[i] == 0 ? 1.0f : 0.0f;
    }
    for (float& x : v) x /= float(count);
    out.push_back(std::move(v));
    expanded += count;
  }
  return out;
}

// Shadow maps: with the compare-fail value set to 0 a shadowed fragment is black, and the frame is
// (ambient + light) · visibility (shadow_map_renderer.cpp), so visibility = frame / unshadowed.
// PCF and the accumulated area light give the fractions in between. One light only.
Plane mapVisibility(const Scene& scene, std::string_view method, const Plane& unshadowed, int threads) {
  if (scene.lights.size() != 1) throw std::runtime_error("shadow-map error needs a scene with one light");
  Scene copy = scene;
  copy.shadow.compareFail = 0.0;
  const Plane lit = renderBrightness(copy, method, threads);
  Plane v(lit.size(), 0.0f);
  for (size_t i = 0; i < v.size(); ++i)
    v[i] = unshadowed[i] > 0.0f ? std::clamp(lit[i] / unshadowed[i], 0.0f, 1.0f) : 0.0f;
  return v;
}

// The soft reference costs samples x pixels shadow rays; configurations that share the scene,
// camera, light and reference shape share it.
const std::vector<float>& cachedAreaLightVisibility(const Scene& scene, const Light& light,
                                                    const ErrorSettings& settings,
                                                    const oracle::OracleImage& primary, int threads) {
  static std::map<std::string, std::vector<float>> cache;
  std::ostringstream key;
  key.precision(17);
  key << scene.sourceFile << ' ' << scene.width << 'x' << scene.height << ' ' << scene.camera.eye.x << ' '
      << scene.camera.eye.y << ' ' << scene.camera.eye.z << ' ' << scene.camera.target.x << ' ' << scene.camera.target.y
      << ' ' << scene.camera.target.z << ' ' << light.position.x << ' ' << light.position.y << ' ' << light.position.z
      << ' ' << name(settings.reference) << ' ' << settings.softSpacing << ' ' << settings.referenceSamples << ' '
      << scene.instances().size();
  auto it = cache.find(key.str());
  if (it == cache.end()) {
    const std::vector<glm::dvec3> samples =
        areaLightSamples(settings.reference, light.position, settings.softSpacing, settings.referenceSamples);
    it = cache.emplace(key.str(), areaLightVisibility(scene, light, samples, primary, threads)).first;
  }
  return it->second;
}

}  // namespace

ShadowError measureShadowError(const Scene& scene, std::string_view method, const ErrorSettings& settings) {
  const int threads = settings.threads > 0 ? settings.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const size_t lights = scene.lights.size();
  const Plane ambientOnly = unshadowedWith(scene, -1, threads);
  std::vector<Plane> unshadowed;
  for (size_t i = 0; i < lights; ++i) unshadowed.push_back(unshadowedWith(scene, static_cast<int>(i), threads));

  std::vector<Plane> rendered;
  if (method == "none") rendered.assign(lights, Plane(ambientOnly.size(), 1.0f));
  else if (isVolumeMethod(method)) rendered = volumeVisibility(scene, method, threads);
  else rendered.push_back(mapVisibility(scene, method, unshadowed[0], threads));

  oracle::OracleOptions oracleOptions;
  oracleOptions.forceInfiniteProjection = settings.forceInfiniteOracle;
  oracleOptions.threads = threads;
  double absSum = 0.0;
  long wrong = 0, wrongCore = 0, core = 0, shadowed = 0, pixels = 0;
  for (size_t l = 0; l < lights; ++l) {
    Light hard = scene.lights[l];
    hard.soft = SoftShape::None;
    const oracle::OracleImage truth = oracle::castOracle(scene, hard, oracleOptions);
    std::vector<float> reference(truth.lit.begin(), truth.lit.end());
    if (settings.reference != Reference::HardLight) {
      if (lights != 1) throw std::runtime_error("soft reference needs a scene with one light");
      reference = cachedAreaLightVisibility(scene, hard, settings, truth, threads);
    }
    for (size_t i = 0; i < reference.size(); ++i) {
      if (!truth.hitMask[i] || unshadowed[l][i] - ambientOnly[i] <= kContributionThreshold) continue;
      const float v = rendered[l][i], r = reference[i];
      ++pixels;
      absSum += std::fabs(v - r);
      const bool disagree = (v >= 0.5f) != (r >= 0.5f);
      wrong += disagree;
      shadowed += r < 0.5f;
      if (!truth.nearEdge[i]) {
        ++core;
        wrongCore += disagree;
      }
    }
  }
  ShadowError e;
  e.pixels = pixels;
  if (pixels > 0) {
    e.mae = absSum / double(pixels);
    e.wrong = double(wrong) / double(pixels);
    e.shadowed = double(shadowed) / double(pixels);
  }
  if (core > 0) e.wrongCore = double(wrongCore) / double(core);
  return e;
}

}  // namespace shadowref::sweep
