// The camera pass's shadow test ([Hempe 2004, §3.1, §5.1.4]), as a fragment shader calls it: the
// world position p through the texture matrix T (light_view.h: bias · P_light · V_light, for TSM
// bias · N_T · P_light · V_light), strq = T · p, then the depth-compare sampler on (s/q, t/q) with
// r/q against the stored depth D: R ≤ D lit (1), otherwise the compare-fail value.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "gl/depth_compare_sampler.h"
#include "shadow/light_view.h"

namespace shadowref {

// strq = T · (p, 1): EYE_LINEAR texgen with the texture matrix, on world coordinates.
glm::dvec4 shadowCoordinates(const glm::dmat4& T, const glm::dvec3& worldPosition);

// A constant bias against self-shadowing (the alternative to polygon offset and back
// faces only, [Hempe 2004, §3.2] "ein bestimmter Wert zu den Tiefenwerten ... hinzuaddiert"): the
// thesis adds it to the map's depths; subtracting it from R instead is the same comparison, R −
// bias ≤ D, without touching the map. Applied in homogeneous form, r − bias · q, so the sampler's
// division gives r/q − bias.
glm::dvec4 withConstantBias(const glm::dvec4& strq, double constantBias);

struct ShadowLookup {
  glm::dmat4 textureMatrix{1.0};
  DepthCompareSampler sampler;  // texture, compare func (LEQUAL), compare-fail value (0.4)
  int pcf = 1;                  // k x k percentage-closer filtering [Reeves et al. 1987]; 1 = nearest ([Hempe 2004])
  double constantBias = 0.0;
  // A map fitted to the casters (caster_fit.h): a point whose s/q or t/q lies outside [0, 1] is
  // shadowed by no caster and is lit (1), as a border of depth 1 with GL_CLAMP_TO_BORDER gives.
  bool outsideLit = false;

  // 1 where lit, failValue where shadowed, between them at PCF edges. Outside the map the
  // sampler clamps to the edge texel, as GL_CLAMP_TO_EDGE does (unless outsideLit). Behind a perspective light
  // (q ≤ 0) the projection is meaningless; such points lie outside a spot cone, so they are not
  // shadowed by the map (1): the spot's own cone term leaves them dark.
  double factor(const glm::dvec3& worldPosition) const;
  // factor() of `count` points given as coordinate columns (x[k], y[k], z[k]), into out[k]: the
  // same bits, the texture matrix and the division four points at a time.
  void factors(const double* x, const double* y, const double* z, int count, double* out) const;
};

// A point light's six cube-face maps (light_view.h, pointLightCubeViews): the face is chosen by
// the direction from the light to p (cubeFaceFor), then that face's map is looked up as above.
struct CubeShadowLookup {
  glm::dvec3 lightPosition{0.0};
  std::array<ShadowLookup, 6> faces;  // indexed by CubeFace

  double factor(const glm::dvec3& worldPosition) const;
};

}  // namespace shadowref
