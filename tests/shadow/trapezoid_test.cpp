#include <array>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/projection.h"
#include "shadow/light_view.h"
#include "shadow/trapezoid.h"

using namespace shadowref;
using Catch::Matchers::WithinAbs;

namespace {

constexpr double kPi = 3.14159265358979323846;

glm::dvec2 warp(const glm::dmat4& NT, const glm::dvec2& p) {
  const glm::dvec4 r = NT * glm::dvec4(p, 0.0, 1.0);
  return glm::dvec2(r) / r.w;
}

glm::dvec2 warpClip(const glm::dmat4& NT, const glm::dvec4& clip) {
  const glm::dvec4 r = NT * clip;
  return glm::dvec2(r) / r.w;
}

void requireNear(const glm::dvec2& got, const glm::dvec2& want, double eps = 1e-9) {
  INFO("got (" << got.x << ", " << got.y << "), want (" << want.x << ", " << want.y << ")");
  CHECK_THAT(got.x, WithinAbs(want.x, eps));
  CHECK_THAT(got.y, WithinAbs(want.y, eps));
}

Aabb box(const glm::dvec3& lo, const glm::dvec3& hi) {
  Aabb b;
  b.add(lo);
  b.add(hi);
  return b;
}

// The square's corners N_T sends t0..t3 to (trapezoid_to_square.h).
const glm::dvec2 kSquare[4] = {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}};

// A TSM configuration: camera, directional light fitted to a large scene box.
struct Setup {
  Camera camera;
  double aspect = 4.0 / 3.0;
  glm::dvec3 lightDirection;
  Aabb scene = box({-60.0, -1.0, -60.0}, {60.0, 12.0, 60.0});

  std::array<glm::dvec4, 8> cornersInLightClip() const {
    Light light;
    light.type = LightType::Directional;
    light.direction = lightDirection;
    const LightView v = directionalLightView(light, scene);
    return transformCorners(v.projection * v.view, frustumCorners(camera, aspect));
  }
};

Setup outdoor(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& lightDirection) {
  Setup s;
  s.camera.eye = eye;
  s.camera.target = target;
  s.camera.fovYDegrees = 60.0;
  s.camera.nearPlane = 0.5;
  s.camera.farPlane = 40.0;
  s.lightDirection = lightDirection;
  return s;
}

// Several views of a scene under a sun, none looking along the light.
std::array<Setup, 5> typicalSetups() {
  return {outdoor({0.0, 2.0, 10.0}, {0.0, 0.0, 0.0}, {0.3, -1.0, 0.2}),
          outdoor({5.0, 8.0, 5.0}, {-10.0, 0.0, -3.0}, {-0.5, -1.0, 0.1}),
          outdoor({0.0, 1.0, 0.0}, {1.0, 1.0, 0.0}, {0.0, -1.0, 0.0}),          // level view, sun overhead
          outdoor({-3.0, 4.0, 2.0}, {5.0, 0.5, 9.0}, {0.9, -0.3, -0.6}),        // low sun from the side
          outdoor({2.0, 3.0, -4.0}, {2.5, 2.0, -14.0}, {0.0, -1.0, 0.5})};      // looking towards the sun
}

double signedArea(const Trapezoid& tz) {
  double a = 0.0;
  for (int i = 0; i < 4; ++i) {
    const glm::dvec2 p = tz.t[i], q = tz.t[(i + 1) % 4];
    a += p.x * q.y - p.y * q.x;
  }
  return a / 2.0;
}

}  // namespace

TEST_CASE("eta formula of the 80% rule against hand calculations", "[shadowmap]") {
  // [Hempe 2004, Listing 10c]: lambda = 1, delta' = 0.4, xi = -0.6: (0.4 - 0.24) / (1 - 0.8 + 0.6)
  // = 0.2.
  CHECK_THAT(trapezoidEta(1.0, 0.4), WithinAbs(0.2, 1e-15));
  // lambda = 10, delta' = 2: (20 - 12) / (10 - 4 + 6) = 2/3.
  CHECK_THAT(trapezoidEta(10.0, 2.0), WithinAbs(2.0 / 3.0, 1e-15));
  // The 1D projection of [Hempe 2004, §4.1.2] with that eta sends the top line (y = eta from q) to
  // +1, the base line (eta + lambda) to -1 and the focus point (eta + delta') to xi.
  const double lambda = 10.0, deltaPrime = 2.0, eta = trapezoidEta(lambda, deltaPrime);
  auto project = [&](double y) {
    const double xi = -(lambda + 2.0 * eta) / lambda * y + 2.0 * (lambda + eta) * eta / lambda;
    const double omega = y;
    return xi / omega;
  };
  CHECK_THAT(project(eta), WithinAbs(1.0, 1e-14));
  CHECK_THAT(project(eta + lambda), WithinAbs(-1.0, 1e-14));
  CHECK_THAT(project(eta + deltaPrime), WithinAbs(-0.6, 1e-14));
}

TEST_CASE("N_T of a hand-made trapezoid is (x, y) -> (-x/y, 3/y - 2)", "[shadowmap]") {
  // Apex at the origin, top line y = 1, base line y = 3, side lines y = |x|; centre line +y.
  // t0 base-right, t1 base-left, t2 top-left, t3 top-right (counter-clockwise).
  // By hand: Y = A + B/y with Y(1) = 1, Y(3) = -1 gives B = 3, A = -2; X = -x/y sends
  // t3 = (1, 1) to -1 and t2 = (-1, 1) to +1.
  const TrapezoidCorners t{{{3.0, 3.0}, {-3.0, 3.0}, {-1.0, 1.0}, {1.0, 1.0}}};
  const glm::dmat4 NT = trapezoidToSquare(t);
  for (int i = 0; i < 4; ++i) requireNear(warp(NT, t[size_t(i)]), kSquare[i], 1e-12);
  for (const glm::dvec2 p : {glm::dvec2(0.0, 2.0), glm::dvec2(0.5, 1.2), glm::dvec2(-2.0, 2.5), glm::dvec2(1.9, 2.9)})
    requireNear(warp(NT, p), {-p.x / p.y, 3.0 / p.y - 2.0}, 1e-12);
  // lambda = 2, eta = 1: delta' = 8/7 solves the eta formula, and y = 1 + 8/7 lands on -0.6.
  CHECK_THAT(trapezoidEta(2.0, 8.0 / 7.0), WithinAbs(1.0, 1e-14));
  CHECK_THAT(warp(NT, {0.0, 1.0 + 8.0 / 7.0}).y, WithinAbs(-0.6, 1e-12));
  // Orientation-preserving: det of the x, y, w part is positive.
  const glm::dmat3 xyw{glm::dvec3(NT[0][0], NT[0][1], NT[0][3]), glm::dvec3(NT[1][0], NT[1][1], NT[1][3]),
                       glm::dvec3(NT[3][0], NT[3][1], NT[3][3])};
  CHECK(glm::determinant(xyw) > 0.0);
}

TEST_CASE("each of the 8 N_T steps does what [Hempe 2004, §4.1.2] says it does", "[shadowmap]") {
  // An asymmetric, rotated trapezoid.
  const double a = 0.7;
  const glm::dmat2 rot{std::cos(a), std::sin(a), -std::sin(a), std::cos(a)};
  const glm::dvec2 off{0.3, -0.2};
  const TrapezoidCorners t{{rot * glm::dvec2(2.5, 3.0) + off, rot * glm::dvec2(-4.0, 3.0) + off,
                            rot * glm::dvec2(-1.0, 1.2) + off, rot * glm::dvec2(0.5, 1.2) + off}};
  auto at = [](const glm::dmat4& m, const glm::dvec2& p) { return m * glm::dvec4(p, 0.0, 1.0); };
  auto xy = [](const glm::dvec4& p) { return glm::dvec2(p) / p.w; };

  const glm::dmat4 T1 = trapezoidStepT1(t);
  requireNear(xy(at(T1, (t[2] + t[3]) / 2.0)), {0.0, 0.0}, 1e-12);  // top centre at the origin

  const glm::dmat4 R = trapezoidStepR(t);
  CHECK_THAT(xy(at(R * T1, t[2])).y, WithinAbs(0.0, 1e-12));  // top line on the x axis
  CHECK_THAT(xy(at(R * T1, t[3])).y, WithinAbs(0.0, 1e-12));
  CHECK(xy(at(R * T1, t[2])).x > 0.0);

  const glm::dmat4 T2 = trapezoidStepT2(t, R * T1);
  requireNear(xy(at(T2 * R * T1, sideLineIntersection(t))), {0.0, 0.0}, 1e-12);  // apex at origin

  const glm::dmat4 H = trapezoidStepH(t, T2 * R * T1);
  const glm::dmat4 upToH = H * T2 * R * T1;
  CHECK_THAT(xy(at(upToH, t[2])).x, WithinAbs(-xy(at(upToH, t[3])).x, 1e-12));  // symmetric about y
  CHECK_THAT(xy(at(upToH, t[0])).x, WithinAbs(-xy(at(upToH, t[1])).x, 1e-12));

  const glm::dmat4 S1 = trapezoidStepS1(t, upToH);
  requireNear(xy(at(S1 * upToH, t[2])), {1.0, 1.0}, 1e-12);  // top at y = 1, sides at 90 deg
  requireNear(xy(at(S1 * upToH, t[3])), {-1.0, 1.0}, 1e-12);

  const glm::dmat4 N = trapezoidStepN();
  const glm::dmat4 upToN = N * S1 * upToH;
  // A rectangle: t0, t3 share x = -1; t1, t2 share x = +1; t0, t1 share y; t2, t3 share y.
  CHECK_THAT(xy(at(upToN, t[0])).x, WithinAbs(-1.0, 1e-12));
  CHECK_THAT(xy(at(upToN, t[1])).x, WithinAbs(1.0, 1e-12));
  CHECK_THAT(xy(at(upToN, t[0])).y, WithinAbs(xy(at(upToN, t[1])).y, 1e-12));
  CHECK_THAT(xy(at(upToN, t[2])).y, WithinAbs(xy(at(upToN, t[3])).y, 1e-12));

  const glm::dmat4 T3 = trapezoidStepT3(t, upToN);
  CHECK_THAT(xy(at(T3 * upToN, t[0])).y, WithinAbs(-xy(at(T3 * upToN, t[2])).y, 1e-12));  // centred

  const glm::dmat4 S2 = trapezoidStepS2(t, T3 * upToN);
  const glm::dmat4 NT = S2 * T3 * upToN;
  for (int i = 0; i < 4; ++i) requireNear(xy(at(NT, t[size_t(i)])), kSquare[i], 1e-12);
  const glm::dmat4 composed = trapezoidToSquare(t);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) CHECK_THAT(composed[c][r], WithinAbs(NT[c][r], 1e-12));
}

TEST_CASE("Hempe's H with 1/y_u ([Hempe 2004, §4.1.2] step 4) gives the same N_T as Martin & Tan's", "[shadowmap]") {
  const TrapezoidCorners t{{{2.0, 5.0}, {-3.0, 4.0}, {-1.0, 1.0}, {0.5, 1.5}}};
  const glm::dmat4 T1 = trapezoidStepT1(t), R = trapezoidStepR(t), T2 = trapezoidStepT2(t, R * T1);
  const glm::dmat4 H = trapezoidStepH(t, T2 * R * T1);
  glm::dmat4 seedH = H;
  const glm::dvec4 u = T2 * R * T1 * (glm::dvec4(t[2], 0.0, 1.0) + glm::dvec4(t[3], 0.0, 1.0)) / 2.0;
  seedH[1][1] = 1.0 / u.y;
  const glm::dmat4 seedS1 = trapezoidStepS1(t, seedH * T2 * R * T1);
  CHECK(seedS1[1][1] == Approx(1.0).epsilon(1e-14));  // y already scaled by Hempe's H
  const glm::dmat4 a = trapezoidStepS1(t, H * T2 * R * T1) * H, b = seedS1 * seedH;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) CHECK_THAT(a[c][r], WithinAbs(b[c][r], 1e-12));
}

TEST_CASE("TSM: N_T maps t0..t3 to the square's corners and every frustum corner inside it", "[shadowmap]") {
  for (const Setup& s : typicalSetups()) {
    const auto clip = s.cornersInLightClip();
    const Trapezoid tz = computeTrapezoid(clip, 0.4);
    REQUIRE_FALSE(tz.fallback);
    REQUIRE_FALSE(tz.parallelSides);
    // t0 -> (-1,-1), t1 -> (1,-1) on the base (far) line; t2 -> (1,1), t3 -> (-1,1) on the top.
    for (int i = 0; i < 4; ++i) requireNear(warp(tz.NT, tz.t[i]), kSquare[i]);
    for (const glm::dvec4& c : clip) {
      const glm::dvec4 w = tz.NT * c;
      CHECK(w.w > 0.0);
      const glm::dvec2 p = glm::dvec2(w) / w.w;
      CHECK(std::abs(p.x) <= 1.0 + 1e-9);
      CHECK(std::abs(p.y) <= 1.0 + 1e-9);
    }
    // Counter-clockwise corners, and so an orientation-preserving N_T.
    CHECK(signedArea(tz) > 0.0);
  }
}

TEST_CASE("TSM: the trapezoid is tight: the top and base lines and both side lines touch the frustum",
          "[shadowmap]") {
  for (const Setup& s : typicalSetups()) {
    const auto clip = s.cornersInLightClip();
    const Trapezoid tz = computeTrapezoid(clip, 0.4);
    double xMin = 1e9, xMax = -1e9, yMin = 1e9, yMax = -1e9;
    for (const glm::dvec4& c : clip) {
      const glm::dvec2 p = warpClip(tz.NT, c);
      xMin = std::min(xMin, p.x), xMax = std::max(xMax, p.x);
      yMin = std::min(yMin, p.y), yMax = std::max(yMax, p.y);
    }
    CHECK_THAT(xMin, WithinAbs(-1.0, 1e-9));
    CHECK_THAT(xMax, WithinAbs(1.0, 1e-9));
    CHECK_THAT(yMin, WithinAbs(-1.0, 1e-9));
    CHECK_THAT(yMax, WithinAbs(1.0, 1e-9));
  }
}

TEST_CASE("TSM 80% rule: the focus point maps to y = -0.6 and q lies eta beyond the top line", "[shadowmap]") {
  for (const Setup& s : typicalSetups()) {
    for (double focus : {0.2, 0.4, 0.5}) {
      const auto clip = s.cornersInLightClip();
      const Trapezoid tz = computeTrapezoid(clip, focus);
      REQUIRE_FALSE(tz.parallelSides);
      // The focus point: focus of the way from the near to the far plane centre, in world space.
      const auto world = frustumCorners(s.camera, s.aspect);
      const glm::dvec3 nearC = (world[0] + world[1] + world[2] + world[3]) / 4.0;
      const glm::dvec3 farC = (world[4] + world[5] + world[6] + world[7]) / 4.0;
      const glm::dvec3 focusWorld = nearC + focus * (farC - nearC);
      Light light;
      light.type = LightType::Directional;
      light.direction = s.lightDirection;
      const LightView v = directionalLightView(light, s.scene);
      const glm::dvec4 focusClip = v.projection * v.view * glm::dvec4(focusWorld, 1.0);
      CHECK_THAT(warpClip(tz.NT, focusClip).y, WithinAbs(kEightyPercentLine, 1e-9));

      CHECK_THAT(tz.eta, WithinAbs(trapezoidEta(tz.lambda, tz.deltaPrime), 1e-12));
      // q is the side lines' intersection, eta from the top line, on the side away from the base.
      requireNear(sideLineIntersection({tz.t[0], tz.t[1], tz.t[2], tz.t[3]}), tz.apex, 1e-9);
      const glm::dvec2 d = glm::normalize(tz.farCentre - tz.nearCentre);
      CHECK_THAT(glm::dot((tz.t[2] + tz.t[3]) / 2.0 - tz.apex, d), WithinAbs(tz.eta, 1e-9));
      CHECK_THAT(glm::dot((tz.t[0] + tz.t[1]) / 2.0 - tz.apex, d), WithinAbs(tz.eta + tz.lambda, 1e-9));
    }
  }
}

TEST_CASE("TSM also works in a spot light's post-perspective space", "[shadowmap]") {
  Camera camera;
  camera.eye = {0.0, 2.0, 8.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.nearPlane = 0.5;
  camera.farPlane = 12.0;
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {4.0, 30.0, -2.0};
  spot.direction = glm::dvec3(0.0, 0.0, 0.0) - spot.position;
  spot.spotCutoffDegrees = 40.0;
  const LightView v = spotLightView(spot, box({-20.0, -1.0, -20.0}, {20.0, 5.0, 20.0}));
  const auto clip = transformCorners(v.projection * v.view, frustumCorners(camera, 1.5));
  const Trapezoid tz = computeTrapezoid(clip, 0.4);
  REQUIRE_FALSE(tz.fallback);
  for (int i = 0; i < 4; ++i) requireNear(warp(tz.NT, tz.t[i]), kSquare[i]);
  for (const glm::dvec4& c : clip) {
    const glm::dvec2 p = warpClip(tz.NT, c);
    CHECK(std::abs(p.x) <= 1.0 + 1e-9);
    CHECK(std::abs(p.y) <= 1.0 + 1e-9);
  }
}

TEST_CASE("TSM falls back to the bounding rectangle when the camera looks along the light", "[shadowmap]") {
  // Looking straight down a vertical sun, and straight up into it.
  for (const glm::dvec3 target : {glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(0.0, 20.0, 0.0)}) {
    Setup s = outdoor({0.0, 10.0, 0.0}, target, {0.0, -1.0, 0.0});
    s.camera.up = {0.0, 0.0, -1.0};
    const Trapezoid tz = computeTrapezoid(s.cornersInLightClip(), 0.4);
    CHECK(tz.fallback);
    // The bounding rectangle: every corner inside, the near and far corners on its edges.
    for (const glm::dvec4& c : s.cornersInLightClip()) {
      const glm::dvec2 p = warpClip(tz.NT, c);
      CHECK(std::abs(p.x) <= 1.0 + 1e-9);
      CHECK(std::abs(p.y) <= 1.0 + 1e-9);
    }
    for (int i = 0; i < 4; ++i) requireNear(warp(tz.NT, tz.t[i]), kSquare[i]);
  }
}

TEST_CASE("TSM fallback boundary: light inside the field of view falls back, just outside does not",
          "[shadowmap]") {
  // Camera fov 60 deg, aspect 1, looking down -y and tilted about z by theta. With an
  // orthographic light along -y, the near plane lies inside the far plane exactly when
  // tan(theta) < tan(30 deg) (trapezoid.h), so at 29 deg it falls back and at 31 deg it does not.
  auto tilted = [](double degrees) {
    const double th = degrees * kPi / 180.0;
    Setup s = outdoor({0.0, 10.0, 0.0}, {std::sin(th), 10.0 - std::cos(th), 0.0}, {0.0, -1.0, 0.0});
    s.camera.up = {0.0, 0.0, -1.0};
    s.aspect = 1.0;
    return computeTrapezoid(s.cornersInLightClip(), 0.4);
  };
  CHECK(tilted(0.0).fallback);
  CHECK(tilted(5.0).fallback);
  CHECK(tilted(29.0).fallback);
  const Trapezoid outside = tilted(31.0);
  CHECK_FALSE(outside.fallback);
  for (int i = 0; i < 4; ++i) requireNear(warp(outside.NT, outside.t[i]), kSquare[i]);
  CHECK_FALSE(tilted(60.0).fallback);
}

TEST_CASE("near-inside-far test needs all four near corners inside, not just one ([Hempe 2004, Listing 10e] text)",
          "[shadowmap]") {
  // Far polygon: the square [-2,2]^2 (clockwise, to check orientation independence).
  std::array<glm::dvec2, 8> p{};
  p[4] = {-2.0, -2.0}, p[5] = {-2.0, 2.0}, p[6] = {2.0, 2.0}, p[7] = {2.0, -2.0};
  p[0] = {-0.5, -0.5}, p[1] = {0.5, -0.5}, p[2] = {0.5, 0.5}, p[3] = {-0.5, 0.5};
  CHECK(nearPlaneInsideFarPlane(p));
  p[2] = {2.5, 0.5};  // one corner outside
  CHECK_FALSE(nearPlaneInsideFarPlane(p));
  p[2] = {2.0, 0.5};  // on the edge: not strictly inside
  CHECK_FALSE(nearPlaneInsideFarPlane(p));
}

TEST_CASE("TSM equals standard mapping when the trapezoid degenerates to the full light view", "[shadowmap]") {
  // Looking down the light with a far plane larger than the scene: the bounding rectangle,
  // clipped to the light's view, is all of [-1,1]^2, and N_T is the identity, so
  // bias * N_T * P * V == bias * P * V.
  Setup s = outdoor({0.0, 10.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, -1.0, 0.0});
  s.camera.up = {0.0, 0.0, -1.0};
  s.camera.farPlane = 200.0;
  s.scene = box({-20.0, -1.0, -20.0}, {20.0, 12.0, 20.0});
  const Trapezoid tz = computeTrapezoid(s.cornersInLightClip(), 0.4);
  REQUIRE(tz.fallback);
  CHECK(tz.NT == glm::dmat4(1.0));
  Light light;
  light.type = LightType::Directional;
  light.direction = s.lightDirection;
  const LightView v = directionalLightView(light, s.scene);
  CHECK(textureMatrix(v, tz.NT) == textureMatrix(v));
}

TEST_CASE("fallback N_T is the affine fit of the bounding rectangle to the square", "[shadowmap]") {
  // A small frustum inside the scene, looking down the light: rectangle [x0,x1] x [y0,y1] in light
  // post-projective space; N_T = scale 2/(x1-x0), 2/(y1-y0) and translate its centre to 0.
  Setup s = outdoor({3.0, 10.0, -2.0}, {3.0, 0.0, -2.0}, {0.0, -1.0, 0.0});
  s.camera.up = {0.0, 0.0, -1.0};
  s.camera.farPlane = 9.0;
  const auto clip = s.cornersInLightClip();
  const Trapezoid tz = computeTrapezoid(clip, 0.4);
  REQUIRE(tz.fallback);
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const glm::dvec4& c : clip) {
    x0 = std::min(x0, c.x / c.w), x1 = std::max(x1, c.x / c.w);
    y0 = std::min(y0, c.y / c.w), y1 = std::max(y1, c.y / c.w);
  }
  CHECK(tz.NT[0][3] == 0.0);  // affine: last row (0, 0, 0, 1)
  CHECK(tz.NT[1][3] == 0.0);
  CHECK(tz.NT[3][3] == 1.0);
  CHECK_THAT(tz.NT[0][0], WithinAbs(2.0 / (x1 - x0), 1e-9));
  CHECK_THAT(tz.NT[1][1], WithinAbs(2.0 / (y1 - y0), 1e-9));
  requireNear(warp(tz.NT, {x0, y0}), {-1.0, -1.0});
  requireNear(warp(tz.NT, {x1, y1}), {1.0, 1.0});
}

TEST_CASE("a focus region past the 80% line gives parallel side lines: the centre-line rectangle",
          "[shadowmap]") {
  // lambda - 2 delta' - lambda xi <= 0 when delta' >= 0.8 lambda: focus 0.95 of the way.
  const Setup s = typicalSetups()[0];
  const auto clip = s.cornersInLightClip();
  const Trapezoid tz = computeTrapezoid(clip, 0.95);
  REQUIRE(tz.parallelSides);
  CHECK_FALSE(tz.fallback);
  for (int i = 0; i < 4; ++i) requireNear(warp(tz.NT, tz.t[i]), kSquare[i]);
  for (const glm::dvec4& c : clip) {
    const glm::dvec2 p = warpClip(tz.NT, c);
    CHECK(std::abs(p.x) <= 1.0 + 1e-9);
    CHECK(std::abs(p.y) <= 1.0 + 1e-9);
  }
}

TEST_CASE("frustumCorners agree with the camera's projection: they land on the NDC cube's corners",
          "[shadowmap]") {
  Camera c;
  c.eye = {1.0, 2.0, 3.0};
  c.target = {-2.0, 0.5, -1.0};
  c.fovYDegrees = 50.0;
  c.nearPlane = 0.25;
  c.farPlane = kInfinity;
  const auto corners = frustumCorners(c, 1.6, 30.0);
  // Through the camera's own gluPerspective · gluLookAt: the corners of the NDC cube, in order.
  const glm::dmat4 pv = perspective(50.0, 1.6, 0.25, 30.0) * lookAt(c.eye, c.target, c.up);
  const glm::dvec3 ndc[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                             {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  for (size_t i = 0; i < 8; ++i) {
    const glm::dvec4 q = pv * glm::dvec4(corners[i], 1.0);
    const glm::dvec3 got = glm::dvec3(q) / q.w;
    for (int k = 0; k < 3; ++k) CHECK_THAT(got[k], WithinAbs(ndc[i][k], 1e-9));
  }
  // Near corners at distance near along the view axis, far corners at 30; x/y signs in order.
  const glm::dvec3 f = glm::normalize(c.target - c.eye);
  for (int i = 0; i < 4; ++i) CHECK_THAT(glm::dot(corners[size_t(i)] - c.eye, f), WithinAbs(0.25, 1e-12));
  for (int i = 4; i < 8; ++i) CHECK_THAT(glm::dot(corners[size_t(i)] - c.eye, f), WithinAbs(30.0, 1e-12));
  // The far corner is the near corner scaled from the eye by far / near.
  for (int i = 0; i < 4; ++i) {
    const glm::dvec3 scaled = c.eye + (corners[size_t(i)] - c.eye) * (30.0 / 0.25);
    CHECK(glm::length(scaled - corners[size_t(i + 4)]) < 1e-9);
  }
  // Half-height at the near plane: tan(25 deg) * near; aspect 1.6 in width.
  const double h = std::tan(25.0 * kPi / 180.0) * 0.25;
  CHECK_THAT(glm::length(corners[3] - corners[0]), WithinAbs(2.0 * h, 1e-12));
  CHECK_THAT(glm::length(corners[1] - corners[0]), WithinAbs(2.0 * h * 1.6, 1e-12));
}

TEST_CASE("fitFarToBounds reaches the farthest box corner along the view, within the camera far", "[shadowmap]") {
  Camera c;
  c.eye = {0.0, 1.0, 10.0};
  c.target = {0.0, 1.0, 0.0};  // looking down -z
  c.nearPlane = 0.1;
  c.farPlane = kInfinity;
  const Aabb scene = box({-5.0, 0.0, -7.0}, {5.0, 3.0, 5.0});
  CHECK_THAT(fitFarToBounds(c, scene), WithinAbs(17.0, 1e-12));
  c.farPlane = 12.0;
  CHECK_THAT(fitFarToBounds(c, scene), WithinAbs(12.0, 1e-12));
}

TEST_CASE("trapezoidalView: points inside the camera frustum land in the map, warped w >= 1", "[shadowmap]") {
  for (Setup s : typicalSetups()) {
    s.camera.farPlane = kInfinity;  // TSM fits a finite far to the scene
    Light light;
    light.type = LightType::Directional;
    light.direction = s.lightDirection;
    const LightView lv = directionalLightView(light, s.scene);
    const TrapezoidalView tv = trapezoidalView(s.camera, s.aspect, lv, s.scene, 0.4);
    REQUIRE_FALSE(tv.trapezoid.fallback);
    const auto corners = frustumCorners(s.camera, s.aspect, fitFarToBounds(s.camera, s.scene));
    // Interior points: fixed convex combinations of the eight corners.
    for (int k = 0; k < 27; ++k) {
      const double a = (k % 3 + 0.5) / 3.0, b = ((k / 3) % 3 + 0.5) / 3.0, c = (k / 9 + 0.5) / 3.0;
      const glm::dvec3 nearP = glm::mix(glm::mix(corners[0], corners[1], a), glm::mix(corners[3], corners[2], a), b);
      const glm::dvec3 farP = glm::mix(glm::mix(corners[4], corners[5], a), glm::mix(corners[7], corners[6], a), b);
      const glm::dvec3 p = glm::mix(nearP, farP, c);
      const glm::dvec4 warped = tv.mapProjection * lv.view * glm::dvec4(p, 1.0);
      CHECK(warped.w >= 1.0 - 1e-12);
      CHECK(std::abs(warped.z) <= warped.w);  // inside the depth range: not clipped by the warp
      const glm::dvec4 strq = tv.texture * glm::dvec4(p, 1.0);
      for (int i = 0; i < 3; ++i) {
        CHECK(strq[i] / strq.w >= -1e-12);
        CHECK(strq[i] / strq.w <= 1.0 + 1e-12);
      }
    }
  }
}

TEST_CASE("shadowLightView is orthographic for a directional light, perspective for a spot", "[shadowmap]") {
  const Aabb scene = box({-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0});
  Light l;
  l.type = LightType::Directional;
  CHECK(shadowLightView(l, scene).projection[2][3] == 0.0);
  l.type = LightType::Spot;
  l.position = {0.0, 5.0, 0.0};
  CHECK(shadowLightView(l, scene).projection[2][3] == -1.0);
}

TEST_CASE("the fallback rectangle: the points' bounds cut to [-1, 1]², the whole view when nothing is left",
          "[shadowmap]") {
  // Hand-made: x from -0.5 to 2 (cut to 1), y from -0.2 to 0.9.
  const std::vector<glm::dvec2> points = {{-0.5, -0.2}, {0.3, 0.9}, {2.0, 0.1}};
  const Trapezoid tz = boundingRectangle(points);
  CHECK(tz.fallback);
  CHECK(tz.t[0] == glm::dvec2(-0.5, -0.2));
  CHECK(tz.t[1] == glm::dvec2(1.0, -0.2));
  CHECK(tz.t[2] == glm::dvec2(1.0, 0.9));
  CHECK(tz.t[3] == glm::dvec2(-0.5, 0.9));
  for (int i = 0; i < 4; ++i) requireNear(warp(tz.NT, tz.t[i]), kSquare[i]);
  // Every point outside the view: the rectangle is the view itself, N_T the identity on it.
  const std::vector<glm::dvec2> outside = {{3.0, 3.0}, {4.0, 5.0}};
  const Trapezoid whole = boundingRectangle(outside);
  CHECK(whole.t[0] == glm::dvec2(-1.0, -1.0));
  CHECK(whole.t[2] == glm::dvec2(1.0, 1.0));
  requireNear(warp(whole.NT, {0.25, -0.5}), {0.25, -0.5});
}
