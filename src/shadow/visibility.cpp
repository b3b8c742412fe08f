#include "shadow/visibility.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "gl/clear.h"
#include "gl/lighting.h"
#include "shadow/draw_tag.h"
#include "shadow/light_shadow.h"

namespace shadowref {

VisibilityCounts::VisibilityCounts(size_t lights, size_t pixels)
    : lit_(lights, std::vector<float>(pixels, 0.0f)), samples_(lights, 0) {}

void VisibilityCounts::addStencil(size_t light, const PixelVector<uint8_t>& stencil) {
  std::vector<float>& lit = lit_.at(light);
  for (size_t i = 0; i < lit.size(); ++i) lit[i] += stencil[i] == 0 ? 1.0f : 0.0f;
  ++samples_[light];
}

void VisibilityCounts::addFractions(size_t light, const std::vector<float>& fraction, int weight) {
  std::vector<float>& lit = lit_.at(light);
  // fraction = passes / weight, rounded to float: passes ≤ 225 is recovered exactly by rounding.
  for (size_t i = 0; i < lit.size(); ++i) lit[i] += float(std::nearbyint(double(fraction[i]) * double(weight)));
  samples_[light] += uint32_t(weight);
}

void VisibilityCounts::addLit(size_t light) {
  for (float& v : lit_.at(light)) v += 1.0f;
  ++samples_[light];
}

std::vector<std::vector<float>> VisibilityCounts::finish() const {
  std::vector<std::vector<float>> out(lit_.size());
  for (size_t l = 0; l < lit_.size(); ++l) {
    out[l].resize(lit_[l].size(), 1.0f);
    if (samples_[l] == 0) continue;
    const double n = double(samples_[l]);
    for (size_t i = 0; i < lit_[l].size(); ++i) out[l][i] = float(double(lit_[l][i]) / n);
  }
  return out;
}

namespace {

// LightShadow::factor with a compare-fail value of 0: copies of the light's lookups (they point
// at the light's textures, which outlive the pass), and the same choice of lookup — the cube face
// for a point light, 1 behind a trapezoidal spot light's unwarped view.
class VisibilityLookup {
 public:
  explicit VisibilityLookup(const LightShadow& shadow) : shadow_(&shadow), lookup_(shadow.lookup), cube_(shadow.cubeLookup) {
    lookup_.sampler.failValue = 0.0;
    for (ShadowLookup& face : cube_.faces) face.sampler.failValue = 0.0;
  }

  double at(const glm::dvec3& p, const glm::dvec4& receiverPlane) const {
    if (shadow_->cube) return cube_.factor(p, receiverPlane);
    const LightView& v = shadow_->views[0];
    if (shadow_->trapezoidal && !((v.projection * (v.view * glm::dvec4(p, 1.0))).w > 0.0)) return 1.0;
    return lookup_.factor(p, receiverPlane);
  }

 private:
  const LightShadow* shadow_;
  ShadowLookup lookup_;
  CubeShadowLookup cube_;
};

// Writes up to four lights' visibility at the fragment's world position into R, G, B, A (1 for
// the unused channels).
class VisibilityShader final : public FragmentShader {
 public:
  explicit VisibilityShader(std::span<const LightShadow* const> shadows) {
    for (const LightShadow* s : shadows) lookups_.emplace_back(*s);
  }
  int varyingCount() const override { return kVaryingPosition + 3; }
  glm::dvec4 shade(const FragmentInput& in) const override {
    const glm::dvec3 p(in.varyings[kVaryingPosition], in.varyings[kVaryingPosition + 1], in.varyings[kVaryingPosition + 2]);
    glm::dvec4 out(1.0);
    const glm::dvec4 plane = receiverPlaneOf(in.triangle);
    for (size_t i = 0; i < lookups_.size(); ++i) out[int(i)] = lookups_[i].at(p, plane);
    return out;
  }

 private:
  std::vector<VisibilityLookup> lookups_;
};

}  // namespace

std::vector<std::vector<float>> shadowMapVisibility(const Pipeline& pipeline, const RenderState& cameraState, int width,
                                                    int height, DepthFormat depthFormat,
                                                    std::span<const PreparedInstance> prepared,
                                                    std::span<const LightShadow* const> shadows) {
  std::vector<std::vector<float>> out;
  for (size_t first = 0; first < shadows.size(); first += 4) {
    const std::span<const LightShadow* const> four = shadows.subspan(first, std::min<size_t>(4, shadows.size() - first));
    Framebuffer fb(width, height, depthFormat);
    {
      const std::unique_ptr<Pipeline> pass = pipeline.forFramebuffer(fb);
      const VisibilityShader shader(four);
      const PassStates states(cameraState);
      pass->clear({.state = cameraState, .color = glm::vec4(1.0f), .depth = 1.0});
      for (const PreparedInstance& p : prepared) {
        DrawCall call;
        call.state = &states.of(*p.instance);
        call.vertices = p.vertices;
        call.indices = p.indices;
        call.shader = &shader;
        call.tag = drawTag(DrawKind::Lit, p.index);
        pass->draw(call);
      }
      pass->endPass();
    }
    for (size_t i = 0; i < four.size(); ++i) {
      std::vector<float>& v = out.emplace_back(fb.pixelCount());
      for (size_t k = 0; k < v.size(); ++k) v[k] = fb.color()[k][int(i)];
    }
  }
  return out;
}

}  // namespace shadowref
