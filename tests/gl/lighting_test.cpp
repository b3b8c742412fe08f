// The Phong illumination model ([Kuhn 2016, §2.3]) with hand-computed values. The scene: surface
// point p = (0, 0, 0) with normal n = (0, 0, 1), light at (0, 3, 4) -> L = (0, 0.6, 0.8), N.L =
// 0.8; eye at (0, 0, 5) -> V = (0, 0, 1). Phong: R = 2 (N.L) N - L = (0, -0.6, 0.8), R.V = 0.8.
// Blinn: H = (L + V) / |L + V| = (0, 0.6, 1.8) / sqrt(3.6), N.H = 1.8 / sqrt(3.6), (N.H)^8 = 0.9^4.
#include <bit>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/lighting.h"
#include "exec/renderer.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

const glm::dvec3 kP(0.0), kN(0.0, 0.0, 1.0), kEye(0.0, 0.0, 5.0);

PhongMaterial material(bool blinn) {
  PhongMaterial m;
  m.ambient = glm::dvec3(0.2);
  m.diffuse = glm::dvec3(0.5);
  m.specular = glm::dvec3(0.25);
  m.shininess = 8.0;
  m.blinn = blinn;
  return m;
}

PhongLight pointLight() {
  PhongLight l;
  l.position = {0.0, 3.0, 4.0, 1.0};
  return l;
}

void checkGrey(const glm::dvec3& c, double expected) {
  CHECK(c.r == Approx(expected).epsilon(1e-12));
  CHECK(c.g == Approx(expected).epsilon(1e-12));
  CHECK(c.b == Approx(expected).epsilon(1e-12));
}

}  // namespace

TEST_CASE("Phong: point light diffuse kd Id N.L plus specular ks Is (R.V)^n", "[raster][lighting]") {
  // 0.5 * 0.8 + 0.25 * 0.8^8 = 0.4 + 0.04194304
  checkGrey(lightContribution(pointLight(), material(false), kP, kN, kEye), 0.44194304);
}

TEST_CASE("Blinn-Phong: the specular term uses (N.H)^n", "[raster][lighting]") {
  // 0.4 + 0.25 * 0.9^4 = 0.4 + 0.164025
  checkGrey(lightContribution(pointLight(), material(true), kP, kN, kEye), 0.564025);
}

TEST_CASE("point light attenuation 1 / (kc + kl d + kq d^2)", "[raster][lighting]") {
  PhongLight l = pointLight();
  l.attenuation = {1.0, 0.1, 0.02};  // d = 5: 1 / (1 + 0.5 + 0.5) = 0.5
  checkGrey(lightContribution(l, material(false), kP, kN, kEye), 0.5 * 0.44194304);
}

TEST_CASE("directional light: direction towards the light, never attenuated", "[raster][lighting]") {
  PhongLight l = pointLight();
  l.position = {0.0, 30.0, 40.0, 0.0};  // normalised to (0, 0.6, 0.8)
  l.attenuation = {1.0, 0.1, 0.02};
  checkGrey(lightContribution(l, material(false), kP, kN, kEye), 0.44194304);
  // Moving the surface point does not change L for a directional light.
  checkGrey(lightContribution(l, material(false), {7.0, -2.0, 0.0}, kN, {7.0, -2.0, 5.0}), 0.44194304);
}

TEST_CASE("spot light: inside the cutoff scaled by cos^exponent, outside dark", "[raster][lighting]") {
  PhongLight l = pointLight();
  l.spotDirection = {0.0, 0.0, -1.0};  // the angle to -L: cos = 0.8
  l.spotExponent = 2.0;
  l.spotCosCutoff = 0.7;  // cutoff about 45.6 degrees: p is inside
  checkGrey(lightContribution(l, material(false), kP, kN, kEye), 0.64 * 0.44194304);
  l.spotCosCutoff = 0.9;  // about 25.8 degrees: p is outside
  checkGrey(lightContribution(l, material(false), kP, kN, kEye), 0.0);
}

TEST_CASE("a surface facing away from the light gets neither diffuse nor specular", "[raster][lighting]") {
  checkGrey(lightContribution(pointLight(), material(false), kP, -kN, kEye), 0.0);
}

TEST_CASE("shadePoint adds emission + global ambient * ka to the lights", "[raster][lighting]") {
  LightingSetup setup;
  setup.material = material(false);
  setup.material.emission = glm::dvec3(0.05);
  setup.globalAmbient = glm::dvec3(0.5);  // 0.5 * 0.2 = 0.1
  setup.lights = {pointLight(), pointLight()};
  setup.eye = kEye;
  checkGrey(shadePoint(setup, kP, kN), 0.05 + 0.1 + 2 * 0.44194304);
  setup.includeAmbient = false;
  checkGrey(shadePoint(setup, kP, kN), 2 * 0.44194304);
}

TEST_CASE("Gouraud and per-pixel shading agree on a flat triangle under a directional light", "[raster][lighting]") {
  // World triangle in the plane z = 0 with normal (0, 0, 1); the directional light gives
  // 0.5 * 0.8 diffuse + 0.2 * 0.5 ambient = 0.5 everywhere, with no specular.
  LightingSetup setup;
  setup.material = material(false);
  setup.material.specular = glm::dvec3(0.0);
  setup.globalAmbient = glm::dvec3(0.5);
  PhongLight sun;
  sun.position = {0.0, 3.0, 4.0, 0.0};
  setup.lights = {sun};
  setup.eye = kEye;

  Framebuffer gouraudFb(16, 16), perPixelFb(16, 16);
  const RenderState s = fullViewportState(gouraudFb);
  const glm::dvec3 world[3] = {{-1.0, -1.0, 0.0}, {2.0, -0.5, 0.0}, {0.0, 3.0, 0.0}};
  std::vector<ClipVertex> g = windowTriangles(s.viewport, {{1, 1, 0.3}, {15, 2, 0.6}, {4, 15, 0.9}});
  std::vector<ClipVertex> pp = g;
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3 c = gouraudVertexColor(setup, world[i], kN);
    for (int k = 0; k < 3; ++k) g[i].varyings[kVaryingColor + k] = c[k];
    for (int k = 0; k < 3; ++k) pp[i].varyings[kVaryingPosition + k] = world[i][k];
    for (int k = 0; k < 3; ++k) pp[i].varyings[kVaryingNormal + k] = kN[k];
  }
  const GouraudShader gouraud;
  const PerPixelLightingShader perPixel(setup);
  Renderer rg(gouraudFb), rp(perPixelFb);
  draw(rg, s, g, &gouraud);
  draw(rp, s, pp, &perPixel);
  int lit = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const glm::vec4 a = gouraudFb.colorAt(x, y), b = perPixelFb.colorAt(x, y);
      INFO("pixel " << x << "," << y);
      for (int k = 0; k < 4; ++k) CHECK(a[k] == Approx(b[k]).margin(1e-6));
      if (a.a == 1.0f) {
        ++lit;
        CHECK(a.r == Approx(0.5f).margin(1e-6));
        CHECK(b.g == Approx(0.5f).margin(1e-6));
      }
    }
  CHECK(lit > 50);
}

TEST_CASE("per-pixel lighting of a batch gives each fragment the bits of shade()", "[raster][lighting][spans]") {
  // The batch form runs the same arithmetic column by column; every light kind and material
  // variant, back faces, zero normals and a point exactly at the light are in the mix.
  TestRandom r(4242);
  for (int round = 0; round < 40; ++round) {
    LightingSetup setup;
    setup.material.diffuse = {r.uniform(), r.uniform(), r.uniform()};
    setup.material.specular = round % 4 == 0 ? glm::dvec3(0.0) : glm::dvec3(r.uniform(), r.uniform(), r.uniform());
    setup.material.shininess = round % 5 == 0 ? 0.0 : r.uniform(1.0, 128.0);
    setup.material.blinn = round % 2 == 0;
    setup.globalAmbient = glm::dvec3(0.1);
    setup.includeAmbient = round % 3 != 0;
    setup.eye = {r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)};
    const int lights = 1 + r.below(3);
    for (int i = 0; i < lights; ++i) {
      PhongLight l;
      const int kind = r.below(3);  // point, directional, spot
      l.position = kind == 1 ? glm::dvec4(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1), 0.0)
                             : glm::dvec4(r.uniform(-4, 4), r.uniform(-4, 4), r.uniform(-4, 4), r.uniform(0.5, 2.0));
      l.diffuse = {r.uniform(), r.uniform(), r.uniform()};
      l.specular = {r.uniform(), r.uniform(), r.uniform()};
      l.attenuation = {1.0, r.uniform(0.0, 0.3), r.uniform(0.0, 0.1)};
      if (kind == 2) {
        l.spotDirection = {r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)};
        l.spotCosCutoff = r.uniform(0.0, 0.9);
        l.spotExponent = r.uniform(0.0, 20.0);
      }
      setup.lights.push_back(l);
    }
    const PerPixelLightingShader shader(setup);
    FragmentBatch batch;
    batch.count = 1 + r.below(kMaxBatch);
    batch.facing = round % 3 == 1 ? BackFacing : FrontFacing;
    std::vector<int> xs(size_t(batch.count));
    std::vector<double> depth(size_t(batch.count), 0.5);
    std::vector<std::vector<double>> columns(6, std::vector<double>(size_t(batch.count)));
    for (int k = 0; k < batch.count; ++k) {
      xs[size_t(k)] = k;
      for (int j = 0; j < 6; ++j) columns[size_t(j)][size_t(k)] = r.uniform(-3.0, 3.0);
      if (k == 0) for (int j = 3; j < 6; ++j) columns[size_t(j)][0] = 0.0;  // zero normal
      if (k == 1 && setup.lights[0].position.w != 0.0)  // exactly at the first light
        for (int j = 0; j < 3; ++j)
          columns[size_t(j)][1] = setup.lights[0].position[j] / setup.lights[0].position.w;
    }
    batch.x = xs.data();
    batch.depth = depth.data();
    for (int j = 0; j < 6; ++j) batch.varyings[j] = columns[size_t(j)].data();
    std::vector<glm::dvec4> out(size_t(batch.count));
    shader.shadeBatch(batch, out.data());
    for (int k = 0; k < batch.count; ++k) {
      double v[6];
      for (int j = 0; j < 6; ++j) v[j] = columns[size_t(j)][size_t(k)];
      FragmentInput in;
      in.x = k;
      in.facing = batch.facing;
      in.varyings = v;
      const glm::dvec4 expected = shader.shade(in);
      INFO("round " << round << ", fragment " << k);
      for (int c = 0; c < 4; ++c) REQUIRE(std::bit_cast<uint64_t>(out[size_t(k)][c]) == std::bit_cast<uint64_t>(expected[c]));
    }
  }
}

TEST_CASE("the colour shaders' batch forms give shade()'s bits", "[raster][lighting]") {
  // GouraudShader copies three interpolated columns with alpha 1, ColorVaryingShader four.
  TestRandom r(77);
  const GouraudShader gouraud;
  const ColorVaryingShader rgba;
  for (const FragmentShader* shader : {static_cast<const FragmentShader*>(&gouraud), static_cast<const FragmentShader*>(&rgba)}) {
    FragmentBatch batch;
    batch.count = 1 + r.below(kMaxBatch);
    std::vector<int> xs(size_t(batch.count));
    std::vector<double> depth(size_t(batch.count), 0.25);
    std::vector<std::vector<double>> columns(4, std::vector<double>(size_t(batch.count)));
    for (int k = 0; k < batch.count; ++k) {
      xs[size_t(k)] = k;
      for (int j = 0; j < 4; ++j) columns[size_t(j)][size_t(k)] = r.uniform(-0.5, 1.5);
    }
    columns[1][0] = -0.0;  // the sign of zero is kept
    batch.x = xs.data();
    batch.depth = depth.data();
    for (int j = 0; j < 4; ++j) batch.varyings[j] = columns[size_t(j)].data();
    std::vector<glm::dvec4> out(size_t(batch.count), glm::dvec4(-7.0));
    shader->shadeBatch(batch, out.data());
    for (int k = 0; k < batch.count; ++k) {
      double v[4];
      for (int j = 0; j < 4; ++j) v[j] = columns[size_t(j)][size_t(k)];
      FragmentInput in;
      in.x = k;
      in.varyings = v;
      const glm::dvec4 expected = shader->shade(in);
      INFO("varyings " << shader->varyingCount() << ", fragment " << k);
      for (int c = 0; c < 4; ++c) REQUIRE(std::bit_cast<uint64_t>(out[size_t(k)][c]) == std::bit_cast<uint64_t>(expected[c]));
    }
  }
}

