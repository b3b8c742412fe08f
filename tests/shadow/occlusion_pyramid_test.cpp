#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include "shadow/occlusion_pyramid.h"

using namespace shadowref;

namespace {

Aabb boxAround(const glm::dvec3& centre, double half) {
  Aabb b;
  b.add(centre - glm::dvec3(half));
  b.add(centre + glm::dvec3(half));
  return b;
}

Aabb boxBetween(const glm::dvec3& lo, const glm::dvec3& hi) {
  Aabb b;
  b.add(lo);
  b.add(hi);
  return b;
}

// Camera at the origin looking down -z, near plane z = -1.
Camera forwardCamera(double fovY) {
  Camera c;
  c.eye = {0, 0, 0};
  c.target = {0, 0, -1};
  c.up = {0, 1, 0};
  c.fovYDegrees = fovY;
  c.nearPlane = 1.0;
  return c;
}

// Slab test: does the segment p -> q (or the ray from p along q when `ray`) meet the box?
bool segmentHitsBox(const glm::dvec3& p, const glm::dvec3& q, bool ray, const Aabb& box) {
  const glm::dvec3 d = ray ? q : q - p;
  double t0 = 0.0, t1 = ray ? 1e30 : 1.0;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (p[k] < box.min[k] || p[k] > box.max[k]) return false;
      continue;
    }
    double a = (box.min[k] - p[k]) / d[k], b = (box.max[k] - p[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("occlusion pyramid: near-plane corners with halfWidth = tan(fovY/2)·aspect·near", "[volumes][occlusion_pyramid]") {
  Camera c = forwardCamera(90.0);
  c.nearPlane = 0.5;
  const auto k = nearPlaneCorners(c, 2.0);
  const double h = 0.5, w = 1.0;  // tan(45°)·0.5 and that times the aspect
  const glm::dvec3 expected[4] = {{-w, -h, -0.5}, {w, -h, -0.5}, {w, h, -0.5}, {-w, h, -0.5}};
  for (int i = 0; i < 4; ++i)
    for (int a = 0; a < 3; ++a) CHECK(k[i][a] == Approx(expected[i][a]).margin(1e-15));
}

TEST_CASE("occlusion pyramid: boxes clearly inside need z-fail, boxes clearly outside do not", "[volumes][occlusion_pyramid]") {
  const Camera c = forwardCamera(90.0);            // near rectangle x, y in [-1, 1] at z = -1
  const glm::dvec4 light(0, 0, -11, 1);            // 10 beyond the near plane
  CHECK(needsZFail(boxAround({0, 0, -6}, 0.1), c, 1.0, light));      // on the axis, half-way
  CHECK(needsZFail(boxAround({0.9, 0.9, -1.5}, 0.05), c, 1.0, light));  // near a corner edge
  CHECK_FALSE(needsZFail(boxAround({5, 0, -6}, 0.1), c, 1.0, light));  // beside it (half-width 0.5 there)
  CHECK_FALSE(needsZFail(boxAround({0, 0, 5}, 0.1), c, 1.0, light));   // behind the camera
  CHECK_FALSE(needsZFail(boxAround({0, 0, -20}, 0.5), c, 1.0, light)); // beyond the light
  CHECK_FALSE(needsZFail(boxAround({0, 0, -0.5}, 0.1), c, 1.0, light)); // between eye and near plane
  CHECK_FALSE(needsZFail(Aabb{}, c, 1.0, light));                       // nothing
}

TEST_CASE("occlusion pyramid: the camera inside a shadow volume needs z-fail ([Kuhn 2016, Fig. 3.3])", "[volumes][occlusion_pyramid]") {
  const Camera c = forwardCamera(60.0);
  // An occluder between the light and the whole near rectangle: the camera is in its shadow.
  CHECK(needsZFail(boxBetween({-3, -3, -6}, {3, 3, -5}), c, 1.5, {0, 0, -11, 1}));
  // Light behind the camera, occluder between them.
  CHECK(needsZFail(boxAround({0, 0, 5}, 0.2), c, 1.5, {0, 0, 10, 1}));
  CHECK_FALSE(needsZFail(boxAround({0, 0, -6}, 0.2), c, 1.5, {0, 0, 10, 1}));
}

TEST_CASE("occlusion pyramid: the fovX formula of [Kuhn 2016, §4.2.1] would miss a box the correct width catches (erratum)",
          "[volumes][occlusion_pyramid]") {
  const Camera c = forwardCamera(60.0);
  const double aspect = 1.0;
  const double correct = std::tan(std::numbers::pi / 6.0);  // 0.577: tan(fovY/2)·aspect·near
  // [Kuhn 2016, §4.2.1]: fovX = 2·atan(fovY·0.5)·aspect (fovY in radians), halfWidth =
  // tan(fovX/2)·near = 0.5236.
  const double fovY = std::numbers::pi / 3.0;
  const double wrong = std::tan(2.0 * std::atan(fovY * 0.5) * aspect / 2.0);
  REQUIRE(wrong < 0.53);
  REQUIRE(correct > 0.577);
  // A thin box just behind the near plane, in the strip between the two widths.
  const Aabb box = boxBetween({0.545, -0.01, -1.02}, {0.56, 0.01, -1.0});
  const glm::dvec4 light(0, 0, -11, 1);
  CHECK(needsZFail(box, c, aspect, light));
  OcclusionPyramid erroneous = makeOcclusionPyramid(c, aspect, light);
  for (glm::dvec3& corner : erroneous.nearCorners) corner.x *= wrong / correct;
  CHECK_FALSE(intersects(erroneous, box));
}

TEST_CASE("occlusion pyramid: a directional light sweeps the near rectangle into a prism towards the light",
          "[volumes][occlusion_pyramid]") {
  const Camera c = forwardCamera(90.0);
  // Light ahead of the camera at infinity: the prism runs from the near rectangle along -z.
  const glm::dvec4 ahead(0, 0, -1, 0);
  CHECK(needsZFail(boxAround({0, 0, -1000}, 0.5), c, 1.0, ahead));
  CHECK(needsZFail(boxAround({0.9, -0.9, -50}, 0.2), c, 1.0, ahead));
  CHECK_FALSE(needsZFail(boxAround({0, 5, -1000}, 0.5), c, 1.0, ahead));
  CHECK_FALSE(needsZFail(boxAround({0, 0, 3}, 0.5), c, 1.0, ahead));  // behind the camera
  // Sun overhead: the vertical near rectangle swept upwards is a flat wall x in [-1, 1], y >= -1,
  // z = -1; boxes high above it meet it, boxes high above but off the wall do not.
  const glm::dvec4 overhead(0, 1, 0, 0);
  CHECK(needsZFail(boxBetween({-0.5, 100, -1.5}, {0.5, 101, -0.5}), c, 1.0, overhead));
  CHECK_FALSE(needsZFail(boxBetween({-0.5, 100, -3}, {0.5, 101, -2}), c, 1.0, overhead));
  CHECK_FALSE(needsZFail(boxBetween({-0.5, -5, -1.5}, {0.5, -3, -0.5}), c, 1.0, overhead));  // below
}

TEST_CASE("occlusion pyramid: never says z-pass when a segment from the near rectangle to the light hits the box",
          "[volumes][occlusion_pyramid]") {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int needed = 0, notNeeded = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Camera c;
    c.eye = {3 * u(rng), 3 * u(rng), 3 * u(rng)};
    c.target = c.eye + glm::dvec3(u(rng), u(rng), u(rng));
    c.up = {0, 1, 0};
    c.fovYDegrees = 50.0 + 30.0 * u(rng);
    c.nearPlane = 0.5 + 0.4 * u(rng);
    const double aspect = 1.4 + 0.4 * u(rng);
    const bool directional = trial % 4 == 3;
    const glm::dvec4 light = directional ? glm::dvec4(glm::normalize(glm::dvec3(u(rng), u(rng), u(rng))), 0.0)
                                         : glm::dvec4(6 * u(rng), 6 * u(rng), 6 * u(rng), 1.0);
    const Aabb box = boxAround({4 * u(rng), 4 * u(rng), 4 * u(rng)}, 0.3 + 0.7 * std::abs(u(rng)));
    const auto k = nearPlaneCorners(c, aspect);
    bool hit = false;
    for (int i = 0; i <= 16 && !hit; ++i)
      for (int j = 0; j <= 16 && !hit; ++j) {
        const double s = i / 16.0, t = j / 16.0;
        const glm::dvec3 p = k[0] + s * (k[1] - k[0]) + t * (k[3] - k[0]);
        hit = segmentHitsBox(p, directional ? glm::dvec3(light) : glm::dvec3(light), directional, box);
      }
    const bool answer = needsZFail(box, c, aspect, light);
    INFO("trial " << trial);
    if (hit) CHECK(answer);
    (answer ? needed : notNeeded)++;
  }
  // The sample covers both answers, so the test is not vacuous.
  CHECK(needed > 10);
  CHECK(notNeeded > 20);
}
