// Per-light visibility: for every pixel and every light of the scene, how much of that light
// reaches the surface the pixel shows — 1 lit, 0 in shadow, a fraction between for percentage-
// closer filtering and for soft shadows. Each method defines it through its own data, so that
// two methods can be compared shadow against shadow rather than colour against colour
// (docs/outputs.md, "Visibility"):
//   - none: 1 everywhere (nothing casts a shadow);
//   - stencil shadow volumes (zpass, zfail, auto): 1 where the stencil count is 0 after that
//     light's volume pass ([Kuhn 2016, §3.1]), else 0; a soft light's value is the fraction of
//     its lights ([Kuhn 2016, §3.6]) whose count is 0;
//   - shadow maps (shadowmap, tsm): the depth comparison of the camera pass's lookup with a
//     compare-fail value of 0 — 1 or 0, the fraction of the k × k comparisons that pass with PCF
//     ([Hempe 2004, §3.1, §5.1.2]); with soft lights the mean over the accumulation frames
//     ([Hempe 2004, §4.2.2]).
// A pixel that shows no surface (the background) is 1. Values in framebuffer order.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gl/framebuffer.h"
#include "gl/pipeline.h"
#include "scene/scene.h"
#include "shadow/scene_passes.h"

namespace shadowref {

struct LightShadow;

// The sums a frame's passes add to, one per scene light: `lit[l][pixel]` counts the samples that
// see the light (a whole number, exact in float up to 2^24), `samples[l]` how many were taken per
// pixel. visibility = lit / samples, taken once at the end, so the value does not depend on the
// order of the additions.
class VisibilityCounts {
 public:
  VisibilityCounts(size_t lights, size_t pixels);
  // Adds one sample of light l: 1 where the stencil count is 0.
  void addStencil(size_t light, const PixelVector<uint8_t>& stencil);
  // Adds `weight` samples of light l: `fraction[pixel] · weight` of them see it (the PCF fraction
  // of k² comparisons, weight = k²; the fraction is a multiple of 1/weight).
  void addFractions(size_t light, const std::vector<float>& fraction, int weight);
  // Every pixel sees every light: no method's data says otherwise (`none`).
  void addLit(size_t light);
  // lit / samples per light (1 for a light that got no sample), in framebuffer order.
  std::vector<std::vector<float>> finish() const;

 private:
  std::vector<std::vector<float>> lit_;
  std::vector<uint32_t> samples_;
};

// The shadow-map visibility of up to four lights at once: one extra pass drawing the camera
// pass's instances (the same clip vertices, states and depth test, so every pixel shows the same
// surface) into a framebuffer of its own, with a shader that writes the lookups' results, with a
// compare-fail value of 0, into R, G, B, A. Returns one vector per light (framebuffer order), the
// background 1. `pipeline` is the frame's: the pass is drawn by one like it.
std::vector<std::vector<float>> shadowMapVisibility(const Pipeline& pipeline, const RenderState& cameraState,
                                                    int width, int height, DepthFormat depthFormat,
                                                    std::span<const PreparedInstance> prepared,
                                                    std::span<const LightShadow* const> shadows);

}  // namespace shadowref
