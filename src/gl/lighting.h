// The Phong illumination model ([Kuhn 2016, §2.3]), as OpenGL's fixed-function lighting computes
// it:
//   colour = emission + ambient_global * ka
//          + sum over lights: att * spot * (kd * Id * max(N.L, 0) + ks * Is * max(R.V, 0)^n)
// with the Blinn-Phong variant using max(N.H, 0)^n, H the half vector of L and V. Lighting is
// evaluated in world space. Two shaders use it: Gouraud (per vertex, colour interpolated) and
// per-pixel (position and normal interpolated, lighting per fragment).
#pragma once

#include <limits>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "gl/fragment_shader.h"

namespace shadowref {

struct PhongLight {
  glm::dvec4 position{0.0, 0.0, 1.0, 0.0};  // w = 1 point/spot; w = 0 directional: towards the light
  glm::dvec3 diffuse{1.0}, specular{1.0};
  glm::dvec3 spotDirection{0.0, 0.0, -1.0};
  double spotCosCutoff = -1.0;  // -1: not a spot light (cutoff 180 degrees)
  double spotExponent = 0.0;
  glm::dvec3 attenuation{1.0, 0.0, 0.0};  // constant, linear, quadratic
};

struct PhongMaterial {
  glm::dvec3 ambient{0.2}, diffuse{0.8}, specular{0.0}, emission{0.0};
  double shininess = 0.0;
  bool blinn = false;
};

// The ambient part: emission + global ambient * ka.
glm::dvec3 ambientTerm(const PhongMaterial& m, const glm::dvec3& globalAmbient);

// One light's diffuse and specular contribution at world position p with unit normal n, seen
// from `eye`. Surfaces facing away from the light (N.L <= 0) get nothing, specular included.
glm::dvec3 lightContribution(const PhongLight& light, const PhongMaterial& m, const glm::dvec3& p,
                             const glm::dvec3& n, const glm::dvec3& eye);

// A light and a material with everything that does not depend on the point worked out once: the
// light's position divided by w, its normalised direction or spot axis, kd * Id and ks * Is. The
// per-point arithmetic left is lightContribution's, operation for operation, so the result has
// the same bits; shaders make these once per draw instead of once per fragment.
struct LightTerms {
  bool directional = false, spot = false, specular = false, blinn = false;
  glm::dvec3 direction{0.0};   // directional: unit vector towards the light
  glm::dvec3 point{0.0};       // point and spot: the light's position
  glm::dvec3 attenuation{1.0, 0.0, 0.0};
  glm::dvec3 spotAxis{0.0};    // normalised spot direction
  double spotCosCutoff = -1.0, spotExponent = 0.0;
  glm::dvec3 diffuse{0.0}, specularColor{0.0};  // kd * Id, ks * Is
  double shininess = 0.0;
};

LightTerms lightTerms(const PhongLight& light, const PhongMaterial& m);
glm::dvec3 lightContribution(const LightTerms& light, const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& eye);
// lightContribution for every fragment of a batch of per-pixel shading (varyings in the
// kVaryingPosition/kVaryingNormal layout, normal as fragmentNormal makes it), in columns: fragment
// k's colour is (r[k], g[k], b[k]). The same bits, computed several fragments at a time.
void lightContributions(const FragmentBatch& batch, const LightTerms& light, const glm::dvec3& eye, double* r,
                        double* g, double* b);

// What a shader adds up: optionally the ambient term, plus the listed lights.
struct LightingSetup {
  PhongMaterial material;
  glm::dvec3 globalAmbient{0.0};
  bool includeAmbient = true;
  std::vector<PhongLight> lights;
  glm::dvec3 eye{0.0};
};

glm::dvec3 shadePoint(const LightingSetup& setup, const glm::dvec3& p, const glm::dvec3& n);

// Varying layout shared by the lighting shaders: world position (0..2), world normal (3..5).
inline constexpr int kVaryingPosition = 0;
inline constexpr int kVaryingNormal = 3;
// Gouraud: RGB colour computed per vertex (0..2).
inline constexpr int kVaryingColor = 0;

// Per-pixel Phong: interpolated position and normal, normal renormalised, lighting per fragment.
// A fragment of a back-facing polygon is lit with the normal flipped (two-sided lighting), so
// the inside of a closed room is lit correctly.
class PerPixelLightingShader final : public FragmentShader {
 public:
  explicit PerPixelLightingShader(const LightingSetup& setup);
  int varyingCount() const override { return 6; }
  glm::dvec4 shade(const FragmentInput& in) const override;
  void shadeBatch(const FragmentBatch& batch, glm::dvec4* out) const override;
  bool describe(ShaderDescription& out) const override;

 private:
  glm::dvec3 litColor(const FragmentInput& in) const;
  LightingSetup setup_;  // what it was made from, for describe()
  glm::dvec3 base_;  // the ambient term, or 0
  std::vector<LightTerms> terms_;
  glm::dvec3 eye_;
};

// The interpolated normal of a per-pixel shader, renormalised, flipped for a back face.
glm::dvec3 fragmentNormal(const FragmentInput& in);

// Gouraud: the colour was computed per vertex (gouraudVertexColor) and is only interpolated.
class GouraudShader final : public FragmentShader {
 public:
  int varyingCount() const override { return 3; }
  glm::dvec4 shade(const FragmentInput& in) const override {
    return {in.varyings[kVaryingColor], in.varyings[kVaryingColor + 1], in.varyings[kVaryingColor + 2], 1.0};
  }
  void shadeBatch(const FragmentBatch& batch, glm::dvec4* out) const override;
  bool describe(ShaderDescription& out) const override;
};

glm::dvec3 gouraudVertexColor(const LightingSetup& setup, const glm::dvec3& p, const glm::dvec3& n);

}  // namespace shadowref
