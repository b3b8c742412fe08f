#include "shadow/light_view.h"

#include <algorithm>
#include <cmath>

#include "gl/projection.h"

namespace shadowref {

namespace {

glm::dvec3 toEye(const glm::dmat4& view, const glm::dvec3& p) { return glm::dvec3(view * glm::dvec4(p, 1.0)); }

// Light eye space looks down −z: the distance in front of the light is −z.
struct DepthRange {
  double nearest = kInfinity, farthest = -kInfinity;
};

DepthRange depthRangeOf(const glm::dmat4& view, const Aabb& bounds) {
  DepthRange r;
  for (const glm::dvec3& c : bounds.corners()) {
    const double d = -toEye(view, c).z;
    r.nearest = std::min(r.nearest, d);
    r.farthest = std::max(r.farthest, d);
  }
  return r;
}

}  // namespace

glm::dvec3 lightUpVector(const glm::dvec3& direction) {
  const glm::dvec3 d = glm::normalize(direction);
  return std::abs(d.y) > 0.999 ? glm::dvec3(0.0, 0.0, -1.0) : glm::dvec3(0.0, 1.0, 0.0);
}

LightView directionalLightView(const Light& light, const Aabb& bounds) {
  const glm::dvec3 d = glm::normalize(light.direction);
  const glm::dvec3 centre = bounds.center();
  const double radius = 0.5 * glm::length(bounds.max - bounds.min);
  // Any eye on the line works for an orthographic view; this one puts the box just in front.
  const glm::dvec3 eye = centre - d * radius;
  LightView v;
  v.view = lookAt(eye, centre, lightUpVector(d));
  glm::dvec3 lo(kInfinity), hi(-kInfinity);
  for (const glm::dvec3& c : bounds.corners()) {
    const glm::dvec3 e = toEye(v.view, c);
    lo = glm::min(lo, e);
    hi = glm::max(hi, e);
  }
  // A flat box facing the light has no depth extent; pad by its size then, so near < far.
  const double depth = hi.z - lo.z > 0.0 ? hi.z - lo.z : std::max(radius, 1.0);
  v.nearPlane = -hi.z - kLightDepthMargin * depth;
  v.farPlane = -lo.z + kLightDepthMargin * depth;
  v.projection = ortho(lo.x, hi.x, lo.y, hi.y, v.nearPlane, v.farPlane);
  return v;
}

LightView spotLightView(const Light& light, const Aabb& bounds) {
  const glm::dvec3 d = glm::normalize(light.direction);
  LightView v;
  v.view = lookAt(light.position, light.position + d, lightUpVector(d));
  const DepthRange r = depthRangeOf(v.view, bounds);
  // A box entirely behind the light leaves nothing to see; any valid range will do then.
  const double farthest = r.farthest > 0.0 ? r.farthest : 1.0;
  const double nearest = std::clamp(r.nearest, farthest * kMinNearOverFar, farthest);
  const double margin = kLightDepthMargin * std::max(farthest - nearest, farthest * kMinNearOverFar);
  v.nearPlane = std::max(nearest - margin, farthest * kMinNearOverFar);
  v.farPlane = farthest + margin;
  v.projection = perspective(2.0 * light.spotCutoffDegrees, 1.0, v.nearPlane, v.farPlane);
  return v;
}

LightView shadowLightView(const Light& light, const Aabb& bounds) {
  return light.type == LightType::Directional ? directionalLightView(light, bounds) : spotLightView(light, bounds);
}

glm::dmat4 biasMatrix() {
  glm::dmat4 b(0.5);  // diagonal 0.5, then [3][3] = 1
  b[3] = glm::dvec4(0.5, 0.5, 0.5, 1.0);  // column 3: the translation
  return b;
}

glm::dmat4 textureMatrix(const LightView& light) { return biasMatrix() * light.projection * light.view; }

glm::dmat4 textureMatrix(const LightView& light, const glm::dmat4& trapezoidNT) {
  return biasMatrix() * trapezoidNT * light.projection * light.view;
}

CubeFace cubeFaceFor(const glm::dvec3& r) {
  const glm::dvec3 a = glm::abs(r);
  if (a.x >= a.y && a.x >= a.z) return r.x >= 0.0 ? CubeFace::PositiveX : CubeFace::NegativeX;
  if (a.y >= a.z) return r.y >= 0.0 ? CubeFace::PositiveY : CubeFace::NegativeY;
  return r.z >= 0.0 ? CubeFace::PositiveZ : CubeFace::NegativeZ;
}

// [GL 2.1, §3.8.6]: for major axis +x, s_c = −r_z, t_c = −r_y; −x: +r_z, −r_y; +y: +r_x, +r_z;
// −y: +r_x, −r_z; +z: +r_x, −r_y; −z: −r_x, −r_y. A view with these forward and up vectors and a
// 90° perspective gives x_ndc = s_c / |m_a| and y_ndc = t_c / |m_a| (checked in light_view_test).
glm::dvec3 cubeFaceForward(CubeFace face) {
  switch (face) {
    case CubeFace::PositiveX: return {1.0, 0.0, 0.0};
    case CubeFace::NegativeX: return {-1.0, 0.0, 0.0};
    case CubeFace::PositiveY: return {0.0, 1.0, 0.0};
    case CubeFace::NegativeY: return {0.0, -1.0, 0.0};
    case CubeFace::PositiveZ: return {0.0, 0.0, 1.0};
    case CubeFace::NegativeZ: return {0.0, 0.0, -1.0};
  }
  return {1.0, 0.0, 0.0};
}

glm::dvec3 cubeFaceUp(CubeFace face) {
  switch (face) {
    case CubeFace::PositiveY: return {0.0, 0.0, 1.0};
    case CubeFace::NegativeY: return {0.0, 0.0, -1.0};
    default: return {0.0, -1.0, 0.0};
  }
}

std::array<LightView, 6> pointLightCubeViews(const Light& light, const Aabb& bounds, double nearPlane) {
  double farthest = 0.0;
  for (const glm::dvec3& c : bounds.corners()) farthest = std::max(farthest, glm::length(c - light.position));
  const double farPlane = std::max(farthest * (1.0 + kLightDepthMargin), 1e-6);
  const double near = nearPlane > 0.0 ? nearPlane : farPlane * kMinNearOverFar;
  std::array<LightView, 6> views;
  for (int f = 0; f < 6; ++f) {
    const CubeFace face = CubeFace(f);
    LightView& v = views[size_t(f)];
    v.view = lookAt(light.position, light.position + cubeFaceForward(face), cubeFaceUp(face));
    v.nearPlane = near;
    v.farPlane = farPlane;
    v.projection = perspective(90.0, 1.0, near, farPlane);
  }
  return views;
}

}  // namespace shadowref
