#include <bit>
#include <cmath>
#include <cstdint>

#include <catch2/catch.hpp>

#include "shadow/light_view.h"
#include "shadow/shadow_lookup.h"

using namespace shadowref;
using Catch::Matchers::WithinAbs;

namespace {

DepthTexture uniformTexture(int size, float depth) { return DepthTexture::filled(size, size, depth); }

Aabb box(const glm::dvec3& lo, const glm::dvec3& hi) {
  Aabb b;
  b.add(lo);
  b.add(hi);
  return b;
}

}  // namespace

TEST_CASE("shadowCoordinates is T times the homogeneous world position", "[shadowmap]") {
  // With T = bias alone, world (x, y, z) in [-1,1]^3 gives (0.5x + 0.5, ...).
  const glm::dvec4 strq = shadowCoordinates(biasMatrix(), {-0.5, 0.5, 0.2});
  CHECK(strq == glm::dvec4(0.25, 0.75, 0.6, 1.0));
}

TEST_CASE("shadow lookup: R <= D is lit, R > D gets the compare-fail value 0.4", "[shadowmap]") {
  DepthTexture map = uniformTexture(2, 0.5f);
  ShadowLookup lookup;
  lookup.textureMatrix = biasMatrix();
  lookup.sampler.texture = &map;
  CHECK(lookup.sampler.failValue == 0.4);  // [Hempe 2004, §5.1.2] default
  // (-0.5, -0.5, z): texel (0, 0); r = 0.5 z + 0.5.
  CHECK(lookup.factor({-0.5, -0.5, 0.0}) == 1.0);   // R = 0.5 = D: lit (LEQUAL)
  CHECK(lookup.factor({-0.5, -0.5, -0.2}) == 1.0);  // R = 0.4 < D
  CHECK(lookup.factor({-0.5, -0.5, 0.1}) == 0.4);   // R = 0.55 > D: shadowed
}

TEST_CASE("constant bias moves R towards the light by the bias, in homogeneous form", "[shadowmap]") {
  CHECK(withConstantBias({1.0, 2.0, 3.0, 2.0}, 0.25) == glm::dvec4(1.0, 2.0, 2.5, 2.0));
  DepthTexture map = uniformTexture(2, 0.5f);
  ShadowLookup lookup;
  lookup.textureMatrix = biasMatrix();
  lookup.sampler.texture = &map;
  lookup.constantBias = 0.1;
  CHECK(lookup.factor({-0.5, -0.5, 0.1}) == 1.0);  // R = 0.55 - 0.1 = 0.45 <= 0.5
  CHECK(lookup.factor({-0.5, -0.5, 0.3}) == 0.4);  // R = 0.65 - 0.1 = 0.55 > 0.5
}

TEST_CASE("PCF 3x3 averages nine comparisons of 1 or the fail value", "[shadowmap]") {
  // 4x4 map: the left column holds an occluder at depth 0.2, the rest 0.9.
  DepthTexture map = uniformTexture(4, 0.9f);
  for (int y = 0; y < 4; ++y) map.set(0, y, 0.2f);
  ShadowLookup lookup;
  lookup.textureMatrix = biasMatrix();
  lookup.sampler.texture = &map;
  lookup.pcf = 3;
  // Texel (1, 1) centre: s = t = 1.5/4 -> world x = y = 2s - 1 = -0.25; r = 0.5 (z = 0).
  // Neighbourhood x 0..2: column 0 (3 texels) shadowed, 6 lit: (6 + 3 * 0.4) / 9.
  CHECK_THAT(lookup.factor({-0.25, -0.25, 0.0}), WithinAbs((6.0 + 3.0 * 0.4) / 9.0, 1e-12));
  lookup.pcf = 1;
  CHECK(lookup.factor({-0.25, -0.25, 0.0}) == 1.0);
  CHECK(lookup.factor({-0.9, -0.25, 0.0}) == 0.4);
}

TEST_CASE("receiverDepthSlope: a world plane's depth change per texel, by hand and by projection", "[shadowmap]") {
  // T = bias: s = (x + 1)/2, t = (y + 1)/2, r = (z + 1)/2. The plane z = 0.2 x + 0.4 y + 0.1 has
  // dr/ds = dz/dx = 0.2 and dr/dt = 0.4; per texel of a 4 x 8 map 0.05 and 0.05.
  auto onPlane = [](double x, double y) { return glm::dvec3(x, y, 0.2 * x + 0.4 * y + 0.1); };
  const glm::dvec4 plane = trianglePlane(onPlane(0.0, 0.0), onPlane(1.0, 0.0), onPlane(0.0, 1.0));
  const DepthSlope slope = receiverDepthSlope(biasMatrix(), plane, 4, 8);
  CHECK_THAT(slope.x, WithinAbs(0.05, 1e-15));
  CHECK_THAT(slope.y, WithinAbs(0.05, 1e-15));
  // The vertex order (the plane's sign) does not matter.
  const DepthSlope flipped = receiverDepthSlope(biasMatrix(), trianglePlane(onPlane(0.0, 0.0), onPlane(0.0, 1.0), onPlane(1.0, 0.0)), 4, 8);
  CHECK_THAT(flipped.x, WithinAbs(0.05, 1e-15));
  CHECK_THAT(flipped.y, WithinAbs(0.05, 1e-15));
  // Edge-on to the light (the plane x = 0.3 holds the rays along z), or no plane: no slope.
  const DepthSlope edgeOn = receiverDepthSlope(biasMatrix(), glm::dvec4(1.0, 0.0, 0.0, -0.3), 4, 8);
  CHECK((edgeOn.x == 0.0 && edgeOn.y == 0.0));
  const DepthSlope none = receiverDepthSlope(biasMatrix(), trianglePlane({0, 0, 0}, {1, 1, 1}, {2, 2, 2}), 4, 8);
  CHECK((none.x == 0.0 && none.y == 0.0));

  // A spot light's perspective map: r/q is affine in (s/q, t/q) over a plane, with the slope the
  // function gives; checked against points of the plane projected one by one.
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {1.0, 5.0, 0.5};
  spot.direction = {-0.2, -1.0, 0.1};
  const glm::dmat4 T = textureMatrix(spotLightView(spot, box({-2.0, 0.0, -2.0}, {2.0, 1.0, 2.0})));
  auto tilted = [](double x, double z) { return glm::dvec3(x, 0.3 * x - 0.5 * z + 0.2, z); };
  const int size = 256;
  const DepthSlope s = receiverDepthSlope(T, trianglePlane(tilted(-1.0, -1.0), tilted(1.0, -1.0), tilted(0.0, 1.0)), size, size);
  for (const glm::dvec2& a : {glm::dvec2(0.1, 0.2), glm::dvec2(-0.7, 0.4), glm::dvec2(0.5, -0.9)})
    for (const glm::dvec2& b : {glm::dvec2(0.3, 0.3), glm::dvec2(-0.2, -0.6)}) {
      const glm::dvec4 pa = T * glm::dvec4(tilted(a.x, a.y), 1.0), pb = T * glm::dvec4(tilted(b.x, b.y), 1.0);
      const double ds = (pb.x / pb.w - pa.x / pa.w) * size, dt = (pb.y / pb.w - pa.y / pa.w) * size;
      CHECK_THAT(pb.z / pb.w - pa.z / pa.w, WithinAbs(s.x * ds + s.y * dt, 1e-12));
    }
}

TEST_CASE("PCF with receiver-plane bias: a sloped receiver's own map passes every tap", "[shadowmap]") {
  // A 16 x 16 map of the plane z = 0.6 x + 0.1 through T = bias (r = (z + 1)/2), drawn with no
  // offset: each texel holds the plane's depth at its centre. A point on the plane at a texel's
  // centre (minus a hair for rounding) passes its own tap; a fixed r fails the taps nearer the light.
  const int n = 16;
  DepthTexture map = uniformTexture(n, 0.0f);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) map.set(x, y, float((0.6 * (2.0 * (x + 0.5) / n - 1.0) + 0.1 + 1.0) / 2.0));
  ShadowLookup lookup;
  lookup.textureMatrix = biasMatrix();
  lookup.sampler.texture = &map;
  lookup.pcf = 3;
  lookup.constantBias = 1e-6;
  auto onPlane = [](double x, double y) { return glm::dvec3(x, y, 0.6 * x + 0.1); };
  const glm::dvec4 plane = trianglePlane(onPlane(0.0, 0.0), onPlane(1.0, 0.0), onPlane(0.0, 1.0));
  const glm::dvec3 p = onPlane(2.0 * 7.5 / n - 1.0, 2.0 * 5.5 / n - 1.0);  // texel (7, 5)'s centre
  CHECK(lookup.factor(p) == Approx((6.0 + 3.0 * 0.4) / 9.0).epsilon(1e-12));  // column 6 nearer
  CHECK(lookup.factor(p, plane) == Approx((6.0 + 3.0 * 0.4) / 9.0).epsilon(1e-12));  // the bias is off
  lookup.receiverPlaneBias = ReceiverPlaneBias::Kernel;
  CHECK(lookup.factor(p, plane) == 1.0);
  CHECK(lookup.factor(p) == Approx((6.0 + 3.0 * 0.4) / 9.0).epsilon(1e-12));  // no plane known
  // A real occluder in column 8 (nearer than the plane by more than its slope) still shadows.
  for (int y = 0; y < n; ++y) map.set(8, y, 0.1f);
  CHECK(lookup.factor(p, plane) == Approx((6.0 + 3.0 * 0.4) / 9.0).epsilon(1e-12));
}

TEST_CASE("shadow lookup behind a perspective light (q <= 0) does not shadow", "[shadowmap]") {
  DepthTexture map = uniformTexture(2, 0.0f);  // everything would be shadowed
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {0.0, 5.0, 0.0};
  spot.direction = {0.0, -1.0, 0.0};
  ShadowLookup lookup;
  lookup.textureMatrix = textureMatrix(spotLightView(spot, box({-1.0, 0.0, -1.0}, {1.0, 1.0, 1.0})));
  lookup.sampler.texture = &map;
  CHECK(lookup.factor({0.0, 8.0, 0.0}) == 1.0);  // above the light
  CHECK(lookup.factor({0.0, 0.5, 0.0}) == 0.4);  // in front of it
}

TEST_CASE("a directional map over a ground plane: the occluder's footprint is shadowed", "[shadowmap]") {
  // Light straight down over [-2,2] x [0,1] x [-4,4] (light_view_test: s = (x + 2)/4,
  // t = (4 - z)/8). A 16x16 map holds the ground (y = 0) everywhere and an occluder square at
  // y = 1 over x in [0, 1], z in [-1, 0]; its texels get the occluder's depth.
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = {0.0, -1.0, 0.0};
  const glm::dmat4 T = textureMatrix(directionalLightView(sun, box({-2.0, 0.0, -4.0}, {2.0, 1.0, 4.0})));
  auto depthOf = [&](const glm::dvec3& p) { const glm::dvec4 q = T * glm::dvec4(p, 1.0); return float(q.z / q.w); };
  const int n = 16;
  DepthTexture map = uniformTexture(n, 0.0f);
  for (int ty = 0; ty < n; ++ty)
    for (int tx = 0; tx < n; ++tx) {
      const double s = (tx + 0.5) / n, t = (ty + 0.5) / n;
      const double x = 4.0 * s - 2.0, z = 4.0 - 8.0 * t;
      const bool occluded = x > 0.0 && x < 1.0 && z > -1.0 && z < 0.0;
      map.set(tx, ty, depthOf({x, occluded ? 1.0 : 0.0, z}));
    }
  ShadowLookup lookup;
  lookup.textureMatrix = T;
  lookup.sampler.texture = &map;
  lookup.constantBias = 1e-4;  // the ground compares against its own depth
  CHECK(lookup.factor({0.5, 0.0, -0.5}) == 0.4);   // under the occluder
  CHECK(lookup.factor({0.5, 1.0, -0.5}) == 1.0);   // the occluder's top itself
  CHECK(lookup.factor({-1.0, 0.0, -0.5}) == 1.0);  // beside it
  CHECK(lookup.factor({0.5, 0.0, 2.0}) == 1.0);
}

TEST_CASE("cube shadow lookup uses the face the direction from the light selects", "[shadowmap]") {
  Light light;
  light.position = {0.0, 0.0, 0.0};
  const auto views = pointLightCubeViews(light, box({-4.0, -4.0, -4.0}, {4.0, 4.0, 4.0}));
  // Every face's map is empty (depth 1) except +y, which is full of a near occluder (depth 0).
  DepthTexture empty = uniformTexture(8, 1.0f), blocked = uniformTexture(8, 0.0f);
  CubeShadowLookup cube;
  cube.lightPosition = light.position;
  for (int f = 0; f < 6; ++f) {
    cube.faces[size_t(f)].textureMatrix = textureMatrix(views[size_t(f)]);
    cube.faces[size_t(f)].sampler.texture = CubeFace(f) == CubeFace::PositiveY ? &blocked : &empty;
  }
  CHECK(cube.factor({0.3, 2.0, -0.5}) == 0.4);  // +y
  CHECK(cube.factor({2.0, 0.3, -0.5}) == 1.0);  // +x
  CHECK(cube.factor({0.3, -2.0, 0.5}) == 1.0);  // -y
  CHECK(cube.factor({-1.0, 0.5, 3.0}) == 1.0);  // +z
}

TEST_CASE("factors of a batch of points are factor's bits, point by point", "[shadowmap]") {
  // A random 16x16 map under a spot light's perspective T (q <= 0 behind it), with and without a
  // constant bias, every compare function, points inside and far outside the map (clamped).
  DepthTexture map = uniformTexture(16, 0.5f);
  uint32_t seed = 12345;
  auto next = [&] {
    seed = seed * 1664525u + 1013904223u;
    return double(seed >> 8) / double(1u << 24);
  };
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) map.set(x, y, float(next()));
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {0.3, 4.0, -0.2};
  spot.direction = {0.1, -1.0, 0.05};
  ShadowLookup lookup;
  lookup.textureMatrix = textureMatrix(spotLightView(spot, box({-2.0, 0.0, -2.0}, {2.0, 1.0, 2.0})));
  lookup.sampler.texture = &map;
  constexpr int kMost = 64;  // a whole fragment batch
  double x[kMost], y[kMost], z[kMost], out[kMost];
  for (int k = 0; k < kMost; ++k) {
    x[k] = 8.0 * next() - 4.0;
    y[k] = 6.0 * next() - 1.0;  // some above the light: q <= 0
    z[k] = 8.0 * next() - 4.0;
  }
  // Counts that are not multiples of four: the last points padded to a step of four.
  for (int count : {0, 1, 2, 3, 5, 6, 7, 61, 64}) {
    INFO(count << " points");
    for (double bias : {0.0, 0.003}) {
      for (int f = 0; f < 8; ++f) {
        lookup.constantBias = bias;
        lookup.sampler.func = CompareFunc(f);
        std::fill_n(out, kMost, -1.0);
        lookup.factors(x + kMost - count, y + kMost - count, z + kMost - count, count, out);
        int lit = 0, shadowed = 0;
        for (int k = 0; k < count; ++k) {
          const int i = kMost - count + k;
          const double expected = lookup.factor({x[i], y[i], z[i]});
          CHECK(std::bit_cast<uint64_t>(out[k]) == std::bit_cast<uint64_t>(expected));
          lit += expected == 1.0;
          shadowed += expected == 0.4;
        }
        for (int k = count; k < kMost; ++k) CHECK(out[k] == -1.0);  // nothing written past the batch
        if (count == kMost && lookup.sampler.func == CompareFunc::LEqual) CHECK((lit > 5 && shadowed > 5));
      }
    }
  }
}
