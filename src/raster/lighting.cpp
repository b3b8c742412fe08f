#include "raster/lighting.h"

#include <algorithm>
#include <cmath>

namespace shadowref {

glm::dvec3 ambientTerm(const PhongMaterial& m, const glm::dvec3& globalAmbient) {
  return m.emission + globalAmbient * m.ambient;
}

glm::dvec3 lightContribution(const PhongLight& light, const PhongMaterial& m, const glm::dvec3& p,
                             const glm::dvec3& n, const glm::dvec3& eye) {
  glm::dvec3 l;
  double attenuation = 1.0;
  if (light.position.w == 0.0) {
    l = glm::normalize(glm::dvec3(light.position));
  } else {
    const glm::dvec3 toLight = glm::dvec3(light.position) / light.position.w - p;
    const double d = glm::length(toLight);
    if (d == 0.0) return glm::dvec3(0.0);
    l = toLight / d;
    attenuation = 1.0 / (light.attenuation.x + light.attenuation.y * d + light.attenuation.z * d * d);
    if (light.spotCosCutoff > -1.0) {
      const double cosAngle = glm::dot(-l, glm::normalize(light.spotDirection));
      if (cosAngle < light.spotCosCutoff) return glm::dvec3(0.0);
      attenuation *= std::pow(std::max(cosAngle, 0.0), light.spotExponent);
    }
  }
  const double nDotL = glm::dot(n, l);
  if (nDotL <= 0.0) return glm::dvec3(0.0);
  glm::dvec3 color = m.diffuse * light.diffuse * nDotL;
  if (m.specular != glm::dvec3(0.0)) {
    const glm::dvec3 v = glm::normalize(eye - p);
    double s;
    if (m.blinn) {
      s = std::max(glm::dot(n, glm::normalize(l + v)), 0.0);
    } else {
      const glm::dvec3 r = 2.0 * nDotL * n - l;  // reflection of L about N
      s = std::max(glm::dot(r, v), 0.0);
    }
    color += m.specular * light.specular * (m.shininess == 0.0 ? 1.0 : std::pow(s, m.shininess));
  }
  return attenuation * color;
}

glm::dvec3 shadePoint(const LightingSetup& setup, const glm::dvec3& p, const glm::dvec3& n) {
  glm::dvec3 c = setup.includeAmbient ? ambientTerm(setup.material, setup.globalAmbient) : glm::dvec3(0.0);
  for (const PhongLight& light : setup.lights) c += lightContribution(light, setup.material, p, n, setup.eye);
  return c;
}

glm::dvec3 PerPixelLightingShader::litColor(const FragmentInput& in) const {
  const double* v = in.varyings;
  const glm::dvec3 p(v[kVaryingPosition], v[kVaryingPosition + 1], v[kVaryingPosition + 2]);
  glm::dvec3 n(v[kVaryingNormal], v[kVaryingNormal + 1], v[kVaryingNormal + 2]);
  const double len = glm::length(n);
  n = len > 0.0 ? n / len : n;
  if (in.facing == BackFacing) n = -n;
  return shadePoint(setup_, p, n);
}

glm::dvec4 PerPixelLightingShader::shade(const FragmentInput& in) const { return glm::dvec4(litColor(in), 1.0); }

glm::dvec3 gouraudVertexColor(const LightingSetup& setup, const glm::dvec3& p, const glm::dvec3& n) {
  return shadePoint(setup, p, n);
}

}  // namespace shadowref
