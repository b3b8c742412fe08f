// The oracle's projective segment-triangle test (src/oracle/projective_crossing.h),
// checked against direct determinants, against finite stand-ins for triangles with vertices at
// infinity, and against the winding number of analytically known shadow volumes.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>

#include "scene/primitives.h"
#include "shadow/shadow_volume.h"
#include "oracle/projective_crossing.h"

using namespace shadowref;
using namespace shadowref::oracle;

namespace {

// A seeded generator of our own, so the cases are the same with every standard library.
struct Xorshift {
  uint64_t s = 0x9E3779B97F4A7C15ull;
  double uniform(double lo, double hi) {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return lo + (hi - lo) * double(s >> 11) * (1.0 / 9007199254740992.0);
  }
  glm::dvec3 vec3(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
  glm::dvec4 vec4(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
};

// Sum over all crossings of a ray to infinity: +1 entering, -1 leaving.
int signedCrossings(const ShadowVolume& volume, const glm::dvec3& origin, const glm::dvec3& direction) {
  const ProjectiveSegment ray = makeRayToInfinity(origin, direction, 0.0);
  int sum = 0;
  for (VolumePart part : {VolumePart::Side, VolumePart::FrontCap, VolumePart::BackCap})
    for (const glm::uvec3& t : volume.part(part)) {
      const Crossing c = crossSegment(
          makeProjectiveTriangle(volume.positions[t[0]], volume.positions[t[1]], volume.positions[t[2]]), ray);
      if (c.hit) sum += c.entering ? 1 : -1;
    }
  return sum;
}

}  // namespace

TEST_CASE("oracle: the Plücker pairing of lines AB and XY is det[A B X Y]", "[oracle]") {
  Xorshift rng;
  for (int i = 0; i < 100; ++i) {
    const glm::dvec4 a = rng.vec4(-2, 2), b = rng.vec4(-2, 2), x = rng.vec4(-2, 2), y = rng.vec4(-2, 2);
    const double expected = glm::determinant(glm::dmat4(a, b, x, y));
    CHECK(pluckerPairing(pluckerLine(a, b), pluckerLine(x, y)) == Approx(expected).margin(1e-12));
  }
}

TEST_CASE("oracle: a triangle's plane functional is det[V0 V1 V2 X], negative on its counter-clockwise side",
          "[oracle]") {
  Xorshift rng;
  for (int i = 0; i < 100; ++i) {
    const glm::dvec4 v0 = rng.vec4(-2, 2), v1 = rng.vec4(-2, 2), v2 = rng.vec4(-2, 2), x = rng.vec4(-2, 2);
    const ProjectiveTriangle t = makeProjectiveTriangle(v0, v1, v2);
    CHECK(glm::dot(t.plane, x) == Approx(glm::determinant(glm::dmat4(v0, v1, v2, x))).margin(1e-12));
  }
  // Counter-clockwise seen from +z: the outside (+z) has pi < 0; a triangle at infinity has
  // exactly (0, 0, 0, c).
  const ProjectiveTriangle floor = makeProjectiveTriangle({0, 0, 0, 1}, {1, 0, 0, 1}, {0, 1, 0, 1});
  CHECK(glm::dot(floor.plane, glm::dvec4(0.2, 0.2, 1.0, 1.0)) < 0.0);
  const ProjectiveTriangle atInfinity = makeProjectiveTriangle({1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0});
  CHECK(atInfinity.plane.x == 0.0);
  CHECK(atInfinity.plane.y == 0.0);
  CHECK(atInfinity.plane.z == 0.0);
  CHECK(atInfinity.plane.w != 0.0);
}

TEST_CASE("oracle: a ray through a finite triangle crosses it once, entering from the outside, at the right t",
          "[oracle]") {
  // Counter-clockwise seen from +z.
  const ProjectiveTriangle t = makeProjectiveTriangle({0, 0, 0, 1}, {2, 0, 0, 1}, {0, 2, 0, 1});
  const Crossing down = crossSegment(t, makeRayToInfinity({0.5, 0.5, 3.0}, {0.0, 0.0, -1.0}, 0.0));
  REQUIRE(down.hit);
  CHECK(down.entering);
  CHECK(rayParameter(down, 0.0) == Approx(3.0));
  const Crossing up = crossSegment(t, makeRayToInfinity({0.5, 0.5, -1.0}, {0.0, 0.0, 0.5}, 0.0));
  REQUIRE(up.hit);
  CHECK_FALSE(up.entering);
  CHECK(rayParameter(up, 0.0) == Approx(2.0));
  CHECK_FALSE(crossSegment(t, makeRayToInfinity({1.5, 1.5, 3.0}, {0, 0, -1}, 0.0)).hit);  // beyond the hypotenuse
  CHECK_FALSE(crossSegment(t, makeRayToInfinity({0.5, 0.5, 3.0}, {0, 0, 1}, 0.0)).hit);   // pointing away
  CHECK_FALSE(crossSegment(t, makeRayToInfinity({0.5, 0.5, 3.0}, {0, 0, -1}, 4.0)).hit);  // starts beyond it
}

TEST_CASE("oracle: a ray through the edge shared by two triangles is claimed by exactly one of them", "[oracle]") {
  // The square [0,1]^2 at z = 0 as two triangles sharing the diagonal (0,0)-(1,1).
  const glm::dvec4 a{0, 0, 0, 1}, b{1, 0, 0, 1}, c{1, 1, 0, 1}, d{0, 1, 0, 1};
  const ProjectiveTriangle lower = makeProjectiveTriangle(a, b, c), upper = makeProjectiveTriangle(a, c, d);
  for (double s : {0.125, 0.25, 0.5, 0.75}) {
    const ProjectiveSegment ray = makeRayToInfinity({s, s, 1.0}, {0, 0, -1}, 0.0);
    const int claims = int(crossSegment(lower, ray).hit) + int(crossSegment(upper, ray).hit);
    CHECK(claims == 1);
  }
}

TEST_CASE("oracle: a side quad extruded to infinity crosses rays exactly where a far finite stand-in does",
          "[oracle]") {
  const glm::dvec3 light{0.3, 5.0, -0.2};
  const glm::dvec3 a{-0.5, 1.0, 0.4}, b{0.6, 1.1, 0.5};
  const glm::dvec4 aInf(a - light, 0.0), bInf(b - light, 0.0);
  const double far = 1e6;
  const glm::dvec4 aFar(a + far * (a - light), 1.0), bFar(b + far * (b - light), 1.0);
  // The quad B, A, D, C (extrusion.h) as its two triangles, at infinity and as a finite stand-in.
  const ProjectiveTriangle inf0 = makeProjectiveTriangle(glm::dvec4(b, 1), glm::dvec4(a, 1), aInf);
  const ProjectiveTriangle inf1 = makeProjectiveTriangle(glm::dvec4(b, 1), aInf, bInf);
  const ProjectiveTriangle fin0 = makeProjectiveTriangle(glm::dvec4(b, 1), glm::dvec4(a, 1), aFar);
  const ProjectiveTriangle fin1 = makeProjectiveTriangle(glm::dvec4(b, 1), aFar, bFar);
  Xorshift rng;
  int crossings = 0;
  for (int i = 0; i < 4000; ++i) {
    const glm::dvec3 o = rng.vec3(-3, 3), d = rng.vec3(-1, 1);
    const ProjectiveSegment ray = makeRayToInfinity(o, d, 0.0);
    for (int k = 0; k < 2; ++k) {
      const Crossing ci = crossSegment(k == 0 ? inf0 : inf1, ray);
      const Crossing cf = crossSegment(k == 0 ? fin0 : fin1, ray);
      if (ci.hit && rayParameter(ci, 0.0) > 1e3) continue;  // beyond what the stand-in reaches
      REQUIRE(ci.hit == cf.hit);
      if (!ci.hit) continue;
      ++crossings;
      CHECK(ci.entering == cf.entering);
      CHECK(rayParameter(ci, 0.0) == Approx(rayParameter(cf, 0.0)).epsilon(1e-6));
    }
  }
  CHECK(crossings > 200);  // the comparison saw many crossings, not just misses
}

TEST_CASE("oracle: along any ray the signed crossings of a closed point-light volume are minus the origin's "
          "inside count", "[oracle]") {
  // A unit cube under a point light straight above: the front cap is the top face (y = 0.5), the
  // volume is the frustum below it, |x|, |z| < 0.5 (5 - y) / 4.5 for y < 0.5; the back cap closes it
  // at infinity. Walking from the origin out past infinity leaves every volume, so the crossings
  // sum to 0 - inside(origin).
  const Mesh box = makeBox({1.0, 1.0, 1.0});
  const ShadowVolume volume = buildShadowVolume(box, glm::dvec4(0.0, 5.0, 0.0, 1.0));
  REQUIRE_FALSE(volume.backCap.empty());
  auto inside = [](const glm::dvec3& p) {
    const double half = 0.5 * (5.0 - p.y) / 4.5;
    return p.y < 0.5 && std::abs(p.x) < half && std::abs(p.z) < half;
  };
  Xorshift rng;
  int insideCases = 0;
  for (int i = 0; i < 3000; ++i) {
    const glm::dvec3 o{rng.uniform(-1.5, 1.5), rng.uniform(-4, 1), rng.uniform(-1.5, 1.5)};
    const glm::dvec3 d = rng.vec3(-1, 1);
    insideCases += inside(o);
    INFO("origin " << o.x << " " << o.y << " " << o.z << " direction " << d.x << " " << d.y << " " << d.z);
    REQUIRE(signedCrossings(volume, o, d) == -int(inside(o)));
  }
  CHECK(insideCases > 100);
}

TEST_CASE("oracle: along any ray the signed crossings of a directional-light volume are minus the origin's "
          "inside count", "[oracle]") {
  // Light travelling along (0.5, -1, 0): the cube's volume is the prism swept from the light-facing
  // faces, whose points satisfy |z| < 0.5 and lie in the cube's shadow: (x + 0.5 s, y - s) inside
  // the cube for some s >= 0 (or in the cube itself). No back cap: the sides meet at one point at
  // infinity.
  const Mesh box = makeBox({1.0, 1.0, 1.0});
  const glm::dvec3 travel{0.5, -1.0, 0.0};
  Light light;
  light.type = LightType::Directional;
  light.direction = travel;
  const ShadowVolume volume = buildShadowVolume(box, light.homogeneous());
  CHECK(volume.backCap.empty());
  auto inside = [](const glm::dvec3& p) {
    if (std::abs(p.z) >= 0.5) return false;
    // Walk back towards the light: p - s * travel for s >= 0 must enter the cube's xy square.
    // x - 0.5 s in (-0.5, 0.5) and y + s in (-0.5, 0.5) for some s >= 0.
    const double sLo = std::max({0.0, -0.5 - p.y, 2.0 * (p.x - 0.5)});
    const double sHi = std::min(0.5 - p.y, 2.0 * (p.x + 0.5));
    return sLo < sHi;
  };
  Xorshift rng;
  int insideCases = 0;
  for (int i = 0; i < 3000; ++i) {
    const glm::dvec3 o{rng.uniform(-1.5, 3.0), rng.uniform(-4, 1), rng.uniform(-1.5, 1.5)};
    const glm::dvec3 d = rng.vec3(-1, 1);
    insideCases += inside(o);
    INFO("origin " << o.x << " " << o.y << " " << o.z);
    REQUIRE(signedCrossings(volume, o, d) == -int(inside(o)));
  }
  CHECK(insideCases > 100);
}
