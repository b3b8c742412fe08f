#include <cmath>

#include <catch2/catch.hpp>

#include "shadow/light_view.h"

using namespace shadowref;
using Catch::Matchers::WithinAbs;

namespace {

glm::dvec4 apply(const glm::dmat4& T, const glm::dvec3& p) { return T * glm::dvec4(p, 1.0); }
glm::dvec3 projected(const glm::dvec4& strq) { return glm::dvec3(strq) / strq.w; }

Aabb box(const glm::dvec3& lo, const glm::dvec3& hi) {
  Aabb b;
  b.add(lo);
  b.add(hi);
  return b;
}

Light directional(const glm::dvec3& direction) {
  Light l;
  l.type = LightType::Directional;
  l.direction = direction;
  return l;
}

}  // namespace

TEST_CASE("bias matrix maps [-1,1]^3 to [0,1]^3 with its translation in the last column", "[shadowmap]") {
  const glm::dmat4 b = biasMatrix();
  CHECK(b[3] == glm::dvec4(0.5, 0.5, 0.5, 1.0));
  CHECK(b * glm::dvec4(-1.0, -1.0, -1.0, 1.0) == glm::dvec4(0.0, 0.0, 0.0, 1.0));
  CHECK(b * glm::dvec4(1.0, 1.0, 1.0, 1.0) == glm::dvec4(1.0, 1.0, 1.0, 1.0));
  CHECK(b * glm::dvec4(0.5, -0.5, 0.0, 1.0) == glm::dvec4(0.75, 0.25, 0.5, 1.0));
}

TEST_CASE("directional light straight down: T maps world x to s and world -z to t over the box", "[shadowmap]") {
  // Box [-2,2] x [0,1] x [-4,4]; the light looks down -y with up = -z, so light x = world x,
  // light y = world -z; the ortho window is x in [-2,2], y in [-4,4]. The eye sits at
  // centre - d * radius = (0, 0.5 + 4.5, 0), so the box spans depths 4 .. 5, widened by
  // kLightDepthMargin * 1 at each end: near 3.999, far 5.001.
  const LightView v = directionalLightView(directional({0.0, -1.0, 0.0}), box({-2.0, 0.0, -4.0}, {2.0, 1.0, 4.0}));
  CHECK_THAT(v.nearPlane, WithinAbs(3.999, 1e-12));
  CHECK_THAT(v.farPlane, WithinAbs(5.001, 1e-12));
  const glm::dmat4 T = textureMatrix(v);

  // (1, 0, 2): s = (1 + 2) / 4, t = (-2 + 4) / 8; depth 5 -> z_ndc = (2*5 - 9) / 1.002.
  const glm::dvec4 a = apply(T, {1.0, 0.0, 2.0});
  CHECK(a.w == 1.0);
  CHECK_THAT(a.x, WithinAbs(0.75, 1e-12));
  CHECK_THAT(a.y, WithinAbs(0.25, 1e-12));
  CHECK_THAT(a.z, WithinAbs(0.5 + 0.5 / 1.002, 1e-12));

  // (-2, 1, -4): the corner at light (-2, 4), depth 4 -> z_ndc = (8 - 9) / 1.002.
  const glm::dvec4 b = apply(T, {-2.0, 1.0, -4.0});
  CHECK_THAT(b.x, WithinAbs(0.0, 1e-12));
  CHECK_THAT(b.y, WithinAbs(1.0, 1e-12));
  CHECK_THAT(b.z, WithinAbs(0.5 - 0.5 / 1.002, 1e-12));
}

TEST_CASE("oblique directional light: the box fills [0,1]^2 and depth grows along the light", "[shadowmap]") {
  const Light light = directional({0.3, -1.0, 0.2});
  const Aabb bounds = box({-3.0, -1.0, -2.0}, {4.0, 2.0, 5.0});
  const glm::dmat4 T = textureMatrix(directionalLightView(light, bounds));
  glm::dvec3 lo(1e9), hi(-1e9);
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 c{(i & 1) ? 4.0 : -3.0, (i & 2) ? 2.0 : -1.0, (i & 4) ? 5.0 : -2.0};
    const glm::dvec3 strq = projected(apply(T, c));
    lo = glm::min(lo, strq);
    hi = glm::max(hi, strq);
  }
  // Tight in s and t, inside (0, 1) in r by the margin.
  CHECK_THAT(lo.x, WithinAbs(0.0, 1e-12));
  CHECK_THAT(lo.y, WithinAbs(0.0, 1e-12));
  CHECK_THAT(hi.x, WithinAbs(1.0, 1e-12));
  CHECK_THAT(hi.y, WithinAbs(1.0, 1e-12));
  CHECK(lo.z > 0.0);
  CHECK(hi.z < 1.0);

  // A point and the same point moved along the light: same texel, larger depth.
  const glm::dvec3 p{0.5, 0.5, 0.5};
  const glm::dvec3 p1 = projected(apply(T, p));
  const glm::dvec3 p2 = projected(apply(T, p + 0.7 * glm::normalize(light.direction)));
  CHECK_THAT(p2.x, WithinAbs(p1.x, 1e-12));
  CHECK_THAT(p2.y, WithinAbs(p1.y, 1e-12));
  CHECK(p2.z > p1.z);
}

TEST_CASE("spot light: perspective with fov = 2 * cutoff, near/far fitted to the box", "[shadowmap]") {
  // Light at (0,10,0) looking down, cutoff 45 deg -> fovY 90, aspect 1. Box y in [0,1] lies at
  // depths 9 .. 10; margin 1e-3 * (10 - 9): near 8.999, far 10.001.
  Light light;
  light.type = LightType::Spot;
  light.position = {0.0, 10.0, 0.0};
  light.direction = {0.0, -1.0, 0.0};
  light.spotCutoffDegrees = 45.0;
  const LightView v = spotLightView(light, box({-5.0, 0.0, -5.0}, {5.0, 1.0, 5.0}));
  CHECK_THAT(v.nearPlane, WithinAbs(8.999, 1e-12));
  CHECK_THAT(v.farPlane, WithinAbs(10.001, 1e-12));
  const glm::dmat4 T = textureMatrix(v);

  // (2, 0, -3): light eye (2, 3, -10); x_ndc = 2/10, y_ndc = 3/10 (cot 45 = 1);
  // z_ndc = ((f+n)/(f-n) * 10 - 2fn/(f-n)) / 10.
  const double n = 8.999, f = 10.001;
  const glm::dvec3 a = projected(apply(T, {2.0, 0.0, -3.0}));
  CHECK_THAT(a.x, WithinAbs(0.6, 1e-12));
  CHECK_THAT(a.y, WithinAbs(0.65, 1e-12));
  CHECK_THAT(a.z, WithinAbs(0.5 + 0.5 * ((f + n) / (f - n) * 10.0 - 2.0 * f * n / (f - n)) / 10.0, 1e-12));
  CHECK(apply(T, {2.0, 0.0, -3.0}).w == Approx(10.0));

  // On the axis: the map's centre; on the cone's edge at depth 10 (x = 10 tan 45): s = 1.
  const glm::dvec3 axis = projected(apply(T, {0.0, 0.5, 0.0}));
  CHECK_THAT(axis.x, WithinAbs(0.5, 1e-12));
  CHECK_THAT(axis.y, WithinAbs(0.5, 1e-12));
  CHECK_THAT(projected(apply(T, {10.0, 0.0, 0.0})).x, WithinAbs(1.0, 1e-12));
}

TEST_CASE("cubeFaceFor picks the major axis and its sign, ties to x then y", "[shadowmap]") {
  CHECK(cubeFaceFor({1.0, 0.5, -0.2}) == CubeFace::PositiveX);
  CHECK(cubeFaceFor({-2.0, 0.5, 1.9}) == CubeFace::NegativeX);
  CHECK(cubeFaceFor({0.3, 0.31, -0.1}) == CubeFace::PositiveY);
  CHECK(cubeFaceFor({-0.1, -3.0, 2.0}) == CubeFace::NegativeY);
  CHECK(cubeFaceFor({0.1, 0.2, 0.5}) == CubeFace::PositiveZ);
  CHECK(cubeFaceFor({0.0, 0.0, -1.0}) == CubeFace::NegativeZ);
  CHECK(cubeFaceFor({1.0, 1.0, 0.0}) == CubeFace::PositiveX);
  CHECK(cubeFaceFor({0.0, -1.0, 1.0}) == CubeFace::NegativeY);
  CHECK(cubeFaceFor({0.0, 0.0, 0.0}) == CubeFace::PositiveX);
}

TEST_CASE("cube face views reproduce GL's major-axis table (s_c, t_c, m_a)", "[shadowmap]") {
  // [GL 2.1, §3.8.6]: s = (s_c/|m_a| + 1)/2, t = (t_c/|m_a| + 1)/2 with, per face,
  //   +x: (-rz, -ry)  -x: (rz, -ry)  +y: (rx, rz)  -y: (rx, -rz)  +z: (rx, -ry)  -z: (-rx, -ry).
  Light light;
  light.position = {1.0, 2.0, 3.0};
  const auto views = pointLightCubeViews(light, box({-10.0, -10.0, -10.0}, {10.0, 10.0, 10.0}));
  const glm::dvec3 directions[] = {{2.0, 0.5, -0.7},  {-3.0, 1.0, 0.4}, {0.2, 1.5, -0.9},
                                   {0.6, -2.0, 0.3},  {-0.5, 0.8, 4.0}, {0.9, -0.2, -1.2}};
  for (const glm::dvec3& r : directions) {
    const CubeFace face = cubeFaceFor(r);
    double sc = 0, tc = 0, ma = 0;
    switch (face) {
      case CubeFace::PositiveX: sc = -r.z, tc = -r.y, ma = r.x; break;
      case CubeFace::NegativeX: sc = r.z, tc = -r.y, ma = r.x; break;
      case CubeFace::PositiveY: sc = r.x, tc = r.z, ma = r.y; break;
      case CubeFace::NegativeY: sc = r.x, tc = -r.z, ma = r.y; break;
      case CubeFace::PositiveZ: sc = r.x, tc = -r.y, ma = r.z; break;
      case CubeFace::NegativeZ: sc = -r.x, tc = -r.y, ma = r.z; break;
    }
    const glm::dvec3 strq = projected(apply(textureMatrix(views[size_t(face)]), light.position + r));
    INFO("face " << int(face));
    CHECK_THAT(strq.x, WithinAbs((sc / std::abs(ma) + 1.0) / 2.0, 1e-12));
    CHECK_THAT(strq.y, WithinAbs((tc / std::abs(ma) + 1.0) / 2.0, 1e-12));
    CHECK(strq.z > 0.0);
    CHECK(strq.z < 1.0);
  }
}

TEST_CASE("every face direction appears once: the six faces' forward vectors pick their own face", "[shadowmap]") {
  for (int f = 0; f < 6; ++f) CHECK(cubeFaceFor(cubeFaceForward(CubeFace(f))) == CubeFace(f));
}

TEST_CASE("point-light cube far plane reaches the farthest box corner", "[shadowmap]") {
  Light light;
  light.position = {0.0, 0.0, 0.0};
  const auto views = pointLightCubeViews(light, box({-1.0, -2.0, -3.0}, {1.0, 2.0, 3.0}));
  const double farthest = std::sqrt(1.0 + 4.0 + 9.0);
  CHECK(views[0].farPlane > farthest);
  CHECK(views[0].farPlane < farthest * 1.01);
  // The corner (1, 2, 3) lies in the +z face, inside its depth range.
  const glm::dvec3 strq = projected(apply(textureMatrix(views[size_t(CubeFace::PositiveZ)]), {1.0, 2.0, 3.0}));
  CHECK(strq.z < 1.0);
  CHECK(strq.z > 0.99);
}
