// The oracle on hand-computed scenes: a box over a floor under a point light and under a
// directional light (shadow outline by similar triangles), and a camera inside one or two shadow
// volumes (z-pass falls short of z-fail by exactly that many).
#include <span>
#include <catch2/catch.hpp>

#include <cmath>

#include "scene/primitives.h"
#include "scene/scene.h"
#include "oracle/oracle.h"
#include "oracle/stencil_comparison.h"

using namespace shadowref;
using namespace shadowref::oracle;

namespace {

glm::dmat4 translate(const glm::dvec3& t) {
  glm::dmat4 m(1.0);
  m[3] = glm::dvec4(t, 1.0);
  return m;
}

void addNode(Scene& scene, const std::string& name, Mesh mesh, const glm::dvec3& at) {
  scene.meshes.push_back(std::make_shared<Mesh>(std::move(mesh)));
  Node node;
  node.name = name;
  node.mesh = static_cast<int>(scene.meshes.size()) - 1;
  node.local = translate(at);
  scene.roots.push_back(node);
}

// Instance 0: a 20 x 20 floor slab with its top at y = 0; instance 1: a unit cube spanning
// y in [1, 2] above the origin. Both cast shadows. 201 x 161 so that pixel (100, 80) has its centre
// exactly at the viewport's centre, on the line of sight to the target.
Scene boxOverFloor() {
  Scene scene;
  scene.width = 201;
  scene.height = 161;
  scene.camera.eye = {0.0, 8.0, 6.0};
  scene.camera.target = {0.0, 0.0, 0.0};
  scene.camera.fovYDegrees = 60.0;
  scene.camera.nearPlane = 0.1;
  addNode(scene, "floor", makePlane({20.0, 20.0}, 0.2), {0.0, 0.0, 0.0});
  addNode(scene, "box", makeBox({1.0, 1.0, 1.0}), {0.0, 1.5, 0.0});
  return scene;
}

Light pointLight(const glm::dvec3& at) {
  Light l;
  l.type = LightType::Point;
  l.position = at;
  return l;
}

struct FloorTally {
  int shadowed = 0, lit = 0, mismatches = 0;
};

// Checks every floor pixel away from edges and from the analytic outline against `inShadow`.
FloorTally checkFloor(const OracleImage& img, bool (*inShadow)(const glm::dvec3&), double (*outlineDistance)(const glm::dvec3&)) {
  FloorTally tally;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const size_t i = img.index(x, y);
      if (img.hitInstance[i] != 0 || img.nearEdge[i]) continue;
      const glm::dvec3 p = img.hitPoint[i];
      if (std::abs(p.y) > 1e-9 || outlineDistance(p) < 0.02) continue;
      const bool shadow = inShadow(p);
      (shadow ? tally.shadowed : tally.lit)++;
      const int expected = shadow ? 1 : 0;
      if (img.zpass[i] != expected || img.zfail[i] != expected || img.lit[i] != (shadow ? 0 : 1)) {
        ++tally.mismatches;
        UNSCOPED_INFO("pixel " << x << "," << y << " hit (" << p.x << ", " << p.z << ") zpass " << img.zpass[i]
                               << " zfail " << img.zfail[i] << " lit " << int(img.lit[i]));
      }
    }
  return tally;
}

size_t countMarked(std::span<const uint8_t> v) {
  size_t n = 0;
  for (uint8_t b : v) n += b;
  return n;
}

}  // namespace

TEST_CASE("oracle: the centre pixel's ray goes through the camera target", "[oracle]") {
  const Scene scene = boxOverFloor();
  const OracleImage img = castOracle(scene, pointLight({0.0, 5.0, 0.0}));
  REQUIRE(img.width == 201);
  REQUIRE(img.height == 161);
  const size_t centre = img.index(100, 80);
  REQUIRE(img.hitMask[centre] == 1);
  CHECK(img.hitInstance[centre] == 0);
  CHECK(glm::length(img.hitPoint[centre]) < 1e-9);
  // Row 0 is the bottom: the eye looks down at the floor, so the bottom row hits nearer the
  // camera (larger z) than the top row does.
  CHECK(img.hitPoint[img.index(100, 0)].z > img.hitPoint[img.index(100, 160)].z);
}

TEST_CASE("oracle: a box under a point light shades the floor square |x|, |z| < 5/6, counting 1 inside, 0 outside",
          "[oracle]") {
  // Light (0, 5, 0), the box's top face at y = 2 is the silhouette; similar triangles scale its
  // half-size 0.5 by 5 / (5 - 2) on the floor.
  const OracleImage img = castOracle(boxOverFloor(), pointLight({0.0, 5.0, 0.0}));
  const FloorTally tally = checkFloor(
      img, [](const glm::dvec3& p) { return std::abs(p.x) < 5.0 / 6.0 && std::abs(p.z) < 5.0 / 6.0; },
      [](const glm::dvec3& p) {
        // Distance to the square's outline (inside or out).
        const double dx = std::abs(p.x) - 5.0 / 6.0, dz = std::abs(p.z) - 5.0 / 6.0;
        if (dx < 0.0 && dz < 0.0) return std::min(-dx, -dz);
        return std::hypot(std::max(dx, 0.0), std::max(dz, 0.0));
      });
  CHECK(tally.mismatches == 0);
  CHECK(tally.shadowed > 100);
  CHECK(tally.lit > 5000);
  CHECK(countMarked(img.nearEdge) < img.nearEdge.size() / 4);  // the exclusions leave most pixels to compare
}

TEST_CASE("oracle: on the box, the light-facing top is lit with count 0 and the sides are self-shadowed with count 1",
          "[oracle]") {
  const OracleImage img = castOracle(boxOverFloor(), pointLight({0.0, 5.0, 0.0}));
  int top = 0, side = 0;
  for (size_t i = 0; i < img.hitInstance.size(); ++i) {
    if (img.hitInstance[i] != 1 || img.nearEdge[i]) continue;
    const glm::dvec3 p = img.hitPoint[i];
    const bool onTop = std::abs(p.y - 2.0) < 1e-9;
    (onTop ? top : side)++;
    CHECK(img.zfail[i] == (onTop ? 0 : 1));
    CHECK(img.zpass[i] == img.zfail[i]);
    CHECK(img.lit[i] == (onTop ? 1 : 0));
  }
  CHECK(top > 50);
  CHECK(side > 50);
}

TEST_CASE("oracle: a directional light along (0.5, -1, 0) shades the floor strip 0 < x < 1.5, |z| < 0.5", "[oracle]") {
  // Each box corner (x, y, z) lands at (x + 0.5 y, 0, z): x from -0.5 + 0.5 to 0.5 + 1.0.
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = {0.5, -1.0, 0.0};
  const OracleImage img = castOracle(boxOverFloor(), sun);
  const FloorTally tally = checkFloor(
      img, [](const glm::dvec3& p) { return p.x > 0.0 && p.x < 1.5 && std::abs(p.z) < 0.5; },
      [](const glm::dvec3& p) {
        const double dx = std::abs(p.x - 0.75) - 0.75, dz = std::abs(p.z) - 0.5;
        if (dx < 0.0 && dz < 0.0) return std::min(-dx, -dz);
        return std::hypot(std::max(dx, 0.0), std::max(dz, 0.0));
      });
  CHECK(tally.mismatches == 0);
  CHECK(tally.shadowed > 100);
  CHECK(tally.lit > 5000);
}

TEST_CASE("oracle: with the eye inside shadow volumes, z-fail exceeds z-pass by the number of volumes around it",
          "[oracle]") {
  // The eye sits under the box, inside its volume (half-width 0.5 (5 - y) / 3 = 0.73 at y = 0.6).
  // A second, smaller box higher up (top at y = 3.8, half-size 0.3: half-width 0.3 * 4.4 / 1.2 = 1.1
  // at the eye's height) puts it inside a second volume when present.
  for (const bool second : {false, true}) {
    Scene scene = boxOverFloor();
    if (second) addNode(scene, "high", makeBox({0.6, 0.6, 0.6}), {0.0, 3.5, 0.0});
    scene.camera.eye = {0.1, 0.6, 0.05};
    scene.camera.target = {5.0, 0.2, 1.0};
    scene.camera.nearPlane = 0.05;
    const OracleImage img = castOracle(scene, pointLight({0.0, 5.0, 0.0}));
    const int volumesAroundEye = second ? 2 : 1;
    int compared = 0, mismatches = 0;
    for (size_t i = 0; i < img.zpass.size(); ++i) {
      if (img.nearEdge[i]) continue;
      ++compared;
      mismatches += img.zfail[i] - img.zpass[i] != volumesAroundEye;
    }
    INFO("second box: " << second);
    CHECK(mismatches == 0);
    CHECK(compared > 10000);
  }
}

TEST_CASE("oracle: the result does not depend on the thread count", "[oracle]") {
  const Scene scene = boxOverFloor();
  const Light light = pointLight({0.3, 5.0, -0.2});
  OracleOptions one, three;
  one.threads = 1;
  three.threads = 3;
  const OracleImage a = castOracle(scene, light, one), b = castOracle(scene, light, three);
  CHECK(a.zpass == b.zpass);
  CHECK(a.zfail == b.zfail);
  CHECK(a.lit == b.lit);
  CHECK(a.nearEdge == b.nearEdge);
  CHECK(a.hitPoint == b.hitPoint);
}

TEST_CASE("oracle: a stencil comparison skips edge pixels and compares counts modulo 256", "[oracle]") {
  OracleImage img;
  img.width = 3;
  img.height = 1;
  img.zpass = {1, -1, 5};
  img.zfail = {1, 2, 0};
  img.nearEdge = {0, 0, 1};
  img.hitInstance = {0, 0, -1};
  // -1 wrapped by DECR_WRAP is 255; the third pixel is near an edge and never compared.
  const StencilComparison zpass = compareStencil(img, std::vector<uint8_t>{1, 255, 0}, CountKind::ZPass);
  CHECK(zpass.compared == 2);
  CHECK(zpass.matches());
  const StencilComparison zfail = compareStencil(img, std::vector<uint8_t>{1, 255, 0}, CountKind::ZFail);
  CHECK(zfail.mismatches == 1);
  CHECK(zfail.report == "1,0: stencil 255, oracle 2 (hit instance 0)\n");
}

TEST_CASE("oracle: a mirrored instance (negative determinant) casts the same shadow as the unmirrored one",
          "[oracle]") {
  // The cube is symmetric in x, so mirroring it there changes only its triangles' winding in world
  // space; the volume's outside must still be the outside.
  const Light light = pointLight({0.3, 5.0, -0.2});
  const Scene plain = boxOverFloor();
  Scene mirrored = boxOverFloor();
  mirrored.roots[1].local[0][0] = -1.0;
  REQUIRE(glm::determinant(mirrored.roots[1].local) < 0.0);
  const OracleImage a = castOracle(plain, light), b = castOracle(mirrored, light);
  size_t compared = 0, differing = 0, shadowed = 0;
  for (size_t i = 0; i < a.zfail.size(); ++i) {
    if (a.nearEdge[i] || b.nearEdge[i]) continue;
    ++compared;
    shadowed += a.zfail[i] > 0;
    differing += a.zpass[i] != b.zpass[i] || a.zfail[i] != b.zfail[i] || a.lit[i] != b.lit[i];
  }
  CHECK(differing == 0);
  CHECK(shadowed > 300);
  CHECK(compared > 20000);
}

TEST_CASE("oracle: a finite far plane ends the primary rays there, P_inf does not", "[oracle]") {
  // The floor's centre is 10 units deep in view space; the bottom row hits it at a depth of about
  // 7 (8 / sin(53.13° + 30°) along a ray 30° off the axis).
  Scene scene = boxOverFloor();
  scene.camera.farPlane = 9.5;
  const Light light = pointLight({0.0, 5.0, 0.0});
  const OracleImage clipped = castOracle(scene, light);
  CHECK(clipped.hitMask[clipped.index(100, 80)] == 0);
  CHECK(clipped.hitMask[clipped.index(100, 0)] == 1);
  OracleOptions infinite;
  infinite.forceInfiniteProjection = true;
  CHECK(castOracle(scene, light, infinite).hitMask[clipped.index(100, 80)] == 1);
}
