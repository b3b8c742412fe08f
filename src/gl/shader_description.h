// A fragment shader as data: what a capture (src/trace) writes for each shader a draw uses, and
// from which a replay makes the same shader again. Only the shaders whose every parameter is plain
// data here describe themselves (FragmentShader::describe); a shader that does not cannot be
// captured.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/depth_compare_sampler.h"
#include "gl/lighting.h"

namespace shadowref {

enum class ShaderKind : uint8_t {
  Constant = 1,             // ConstantColorShader: `color`
  ColorVarying = 2,         // ColorVaryingShader: varyings 0..3 as RGBA
  Gouraud = 3,              // GouraudShader: varyings 0..2 as RGB, alpha 1
  PerPixelLighting = 4,     // PerPixelLightingShader(`setup`)
  ShadowMapped = 5,         // the shadow-mapped camera pass, lit per pixel: `setup` and `shadows`
  ShadowMappedGouraud = 6,  // the shadow-mapped camera pass of a Gouraud material: `shadows`
};

// One depth map's lookup: the texture matrix T, the depth-compare sampler and its filter.
struct ShadowMapDescription {
  glm::dmat4 textureMatrix{1.0};
  const DepthTexture* texture = nullptr;
  CompareFunc func = CompareFunc::LEqual;
  double failValue = 0.4;
  int pcf = 1;
  double constantBias = 0.0;
  bool outsideLit = false;
  // The taps follow the receiver's plane (ShadowLookup::receiverPlaneBias): 0 off, 1 around the
  // point (ReceiverPlaneBias::Kernel), 2 at the texels' centres (Texel).
  uint8_t receiverPlaneBias = 0;
};

// One light's shadow test: one map, or six cube faces chosen by the direction from the light;
// trapezoidal: a point behind the unwarped light view (w <= 0) is lit.
struct LightShadowDescription {
  bool cube = false;
  glm::dvec3 lightPosition{0.0};
  std::vector<ShadowMapDescription> maps;  // 1, or 6 when cube
  bool trapezoidal = false;
  glm::dmat4 lightView{1.0}, lightProjection{1.0};
};

struct ShaderDescription {
  ShaderKind kind = ShaderKind::Constant;
  glm::dvec4 color{0.0};
  LightingSetup setup;
  std::vector<LightShadowDescription> shadows;
};

}  // namespace shadowref
