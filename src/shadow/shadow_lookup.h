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

// A receiver's plane in world space, (n, d) with n · p + d = 0 on it, n = (b − a) × (c − a) for
// the triangle a, b, c (unnormalised). (0, 0, 0, 0): no plane (a degenerate triangle, or none known).
glm::dvec4 trianglePlane(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// The receiver plane's depth slope per texel in a width × height map looked up through T
// (receiver-plane depth bias, [Isidoro 2006]). A projective T maps a plane to a plane: the world
// plane π becomes π' = T^−T · π in (s, t, r, q), and on it a π'_s · s/q + π'_t · t/q + π'_r · r/q
// + π'_q = 0, so r/q is affine in (s/q, t/q) with slopes −π'_s / π'_r and −π'_t / π'_r: exact over
// the whole triangle, for orthographic, perspective and N_T-warped maps alike. Zero slope (every
// tap compares r/q) for no plane, or a plane that contains the light's rays (π'_r = 0: the
// receiver is edge-on to the light, unlit anyway).
DepthSlope receiverDepthSlope(const glm::dmat4& T, const glm::dvec4& worldPlane, int width, int height);

struct ShadowLookup {
  glm::dmat4 textureMatrix{1.0};
  DepthCompareSampler sampler;  // texture, compare func (LEQUAL), compare-fail value (0.4)
  int pcf = 1;                  // k x k percentage-closer filtering [Reeves et al. 1987]; 1 = nearest ([Hempe 2004])
  double constantBias = 0.0;
  // A map fitted to the casters (caster_fit.h): a point whose s/q or t/q lies outside [0, 1] is
  // shadowed by no caster and is lit (1), as a border of depth 1 with GL_CLAMP_TO_BORDER gives.
  bool outsideLit = false;
  // Receiver-plane depth bias [Isidoro 2006] (scene.h, ReceiverPlaneBias): with Kernel and PCF
  // (pcf > 1) each tap compares the receiver plane's depth at that tap's texel centre
  // (DepthCompareSampler::samplePcf) instead of the point's own depth, so the receiver's own
  // slope never fails an outer tap and the map pass keeps the offset of nearest sampling
  // (pcfOffsetFactor, light_shadow.h); nearest sampling is unchanged. With Texel every tap, the
  // nearest one's included, compares the plane at its texel's centre, where the map pass drew the
  // texel's depth: a planar receiver then meets its own depth there up to rounding, whatever its
  // slope. Without a plane (the point's triangle not known) the taps compare the point's depth.
  ReceiverPlaneBias receiverPlaneBias = ReceiverPlaneBias::Off;

  // 1 where lit, failValue where shadowed, between them at PCF edges. Outside the map the
  // sampler clamps to the edge texel, as GL_CLAMP_TO_EDGE does (unless outsideLit). Behind a perspective light
  // (q ≤ 0) the projection is meaningless; such points lie outside a spot cone, so they are not
  // shadowed by the map (1): the spot's own cone term leaves them dark.
  // `receiverPlane`: the world plane of the triangle the point lies on (trianglePlane), for
  // receiverPlaneBias.
  double factor(const glm::dvec3& worldPosition, const glm::dvec4& receiverPlane = glm::dvec4(0.0)) const;
  // factor() of `count` points given as coordinate columns (x[k], y[k], z[k]), into out[k]: the
  // same bits, the texture matrix and the division four points at a time. The points lie on one
  // receiver plane.
  void factors(const double* x, const double* y, const double* z, int count, double* out,
               const glm::dvec4& receiverPlane = glm::dvec4(0.0)) const;
  // The slope the taps follow on `receiverPlane`: receiverDepthSlope with receiverPlaneBias Kernel
  // and PCF, or Texel (at the texels' centres); else zero.
  DepthSlope tapSlope(const glm::dvec4& receiverPlane) const;
  // factor() with the taps' slope given.
  double factorOnSlope(const glm::dvec3& worldPosition, DepthSlope slope) const;
};

// A point light's six cube-face maps (light_view.h, pointLightCubeViews): the face is chosen by
// the direction from the light to p (cubeFaceFor), then that face's map is looked up as above.
struct CubeShadowLookup {
  glm::dvec3 lightPosition{0.0};
  std::array<ShadowLookup, 6> faces;  // indexed by CubeFace

  double factor(const glm::dvec3& worldPosition, const glm::dvec4& receiverPlane = glm::dvec4(0.0)) const;
};

}  // namespace shadowref
