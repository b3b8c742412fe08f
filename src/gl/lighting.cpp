#include "gl/lighting.h"

#include <algorithm>
#include <cmath>

#include "gl/lighting_pow.h"

namespace shadowref {

glm::dvec3 ambientTerm(const PhongMaterial& m, const glm::dvec3& globalAmbient) {
  return m.emission + globalAmbient * m.ambient;
}

LightTerms lightTerms(const PhongLight& light, const PhongMaterial& m) {
  LightTerms t;
  t.directional = light.position.w == 0.0;
  if (t.directional) {
    t.direction = glm::normalize(glm::dvec3(light.position));
  } else {
    t.point = glm::dvec3(light.position) / light.position.w;
    t.attenuation = light.attenuation;
    t.spot = light.spotCosCutoff > -1.0;
    if (t.spot) t.spotAxis = glm::normalize(light.spotDirection);
    t.spotCosCutoff = light.spotCosCutoff;
    t.spotExponent = light.spotExponent;
  }
  t.diffuse = m.diffuse * light.diffuse;
  t.specular = m.specular != glm::dvec3(0.0);
  t.specularColor = m.specular * light.specular;
  t.shininess = m.shininess;
  t.blinn = m.blinn;
  return t;
}

glm::dvec3 lightContribution(const LightTerms& light, const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& eye) {
  glm::dvec3 l;
  double attenuation = 1.0;
  if (light.directional) {
    l = light.direction;
  } else {
    const glm::dvec3 toLight = light.point - p;
    const double d = glm::length(toLight);
    if (d == 0.0) return glm::dvec3(0.0);
    l = toLight / d;
    attenuation = 1.0 / (light.attenuation.x + light.attenuation.y * d + light.attenuation.z * d * d);
    if (light.spot) {
      const double cosAngle = glm::dot(-l, light.spotAxis);
      if (cosAngle < light.spotCosCutoff) return glm::dvec3(0.0);
      attenuation *= lightingPow(std::max(cosAngle, 0.0), light.spotExponent);
    }
  }
  const double nDotL = glm::dot(n, l);
  if (nDotL <= 0.0) return glm::dvec3(0.0);
  glm::dvec3 color = light.diffuse * nDotL;
  if (light.specular) {
    const glm::dvec3 v = glm::normalize(eye - p);
    double s;
    if (light.blinn) {
      s = std::max(glm::dot(n, glm::normalize(l + v)), 0.0);
    } else {
      const glm::dvec3 r = 2.0 * nDotL * n - l;  // reflection of L about N
      s = std::max(glm::dot(r, v), 0.0);
    }
    color += light.specularColor * lightingPow(s, light.shininess);  // 1 for shininess 0
  }
  return attenuation * color;
}

glm::dvec3 lightContribution(const PhongLight& light, const PhongMaterial& m, const glm::dvec3& p,
                             const glm::dvec3& n, const glm::dvec3& eye) {
  return lightContribution(lightTerms(light, m), p, n, eye);
}

glm::dvec3 shadePoint(const LightingSetup& setup, const glm::dvec3& p, const glm::dvec3& n) {
  glm::dvec3 c = setup.includeAmbient ? ambientTerm(setup.material, setup.globalAmbient) : glm::dvec3(0.0);
  for (const PhongLight& light : setup.lights) c += lightContribution(light, setup.material, p, n, setup.eye);
  return c;
}

PerPixelLightingShader::PerPixelLightingShader(const LightingSetup& setup)
    : setup_(setup), base_(setup.includeAmbient ? ambientTerm(setup.material, setup.globalAmbient) : glm::dvec3(0.0)), eye_(setup.eye) {
  for (const PhongLight& light : setup.lights) terms_.push_back(lightTerms(light, setup.material));
}

glm::dvec3 fragmentNormal(const FragmentInput& in) {
  const double* v = in.varyings;
  glm::dvec3 n(v[kVaryingNormal], v[kVaryingNormal + 1], v[kVaryingNormal + 2]);
  const double len = glm::length(n);
  n = len > 0.0 ? n / len : n;
  return in.facing == BackFacing ? -n : n;
}

// shadePoint with the terms made once.
glm::dvec3 PerPixelLightingShader::litColor(const FragmentInput& in) const {
  const double* v = in.varyings;
  const glm::dvec3 p(v[kVaryingPosition], v[kVaryingPosition + 1], v[kVaryingPosition + 2]);
  const glm::dvec3 n = fragmentNormal(in);
  glm::dvec3 c = base_;
  for (const LightTerms& light : terms_) c += lightContribution(light, p, n, eye_);
  return c;
}

glm::dvec4 PerPixelLightingShader::shade(const FragmentInput& in) const { return glm::dvec4(litColor(in), 1.0); }

glm::dvec3 gouraudVertexColor(const LightingSetup& setup, const glm::dvec3& p, const glm::dvec3& n) {
  return shadePoint(setup, p, n);
}

}  // namespace shadowref
