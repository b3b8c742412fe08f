#include <catch2/catch.hpp>

#include "scene/primitives.h"
#include "shadow/extrusion.h"
#include "shadow/facing.h"
#include "shadow/shadow_volume.h"
#include "volume_fixtures.h"

using namespace shadowref;

TEST_CASE("extrusion: V∞ = (V·L_w − L.xyz, 0) for point and directional lights ([Kuhn 2016, §3.4])", "[volumes][extrusion]") {
  CHECK(extrudeToInfinity({1, 2, 3}, {0, 5, 0, 1}) == glm::dvec4(1, -3, 3, 0));
  CHECK(extrudeToInfinity({-4, 0.5, 2}, {1, 1, 1, 1}) == glm::dvec4(-5, -0.5, 1, 0));
  // Directional: every vertex goes to the same point, the direction the light travels.
  CHECK(extrudeToInfinity({1, 2, 3}, {0, 1, 0, 0}) == glm::dvec4(0, -1, 0, 0));
  CHECK(extrudeToInfinity({-7, 9, 0}, {0, 1, 0, 0}) == glm::dvec4(0, -1, 0, 0));
}

TEST_CASE("extrusion: the side quad of edge A -> B is B, A, D, C with D = A∞, C = B∞, both w = 0",
          "[volumes][extrusion]") {
  const glm::dvec3 a(0, 0, 0), b(1, 0, 0);
  const glm::dvec4 light(0.25, 0.5, 4, 1);
  const auto q = sideQuad(a, b, light);
  CHECK(q[0] == glm::dvec4(b, 1));
  CHECK(q[1] == glm::dvec4(a, 1));
  CHECK(q[2] == glm::dvec4(-0.25, -0.5, -4, 0));
  CHECK(q[3] == glm::dvec4(0.75, -0.5, -4, 0));
}

TEST_CASE("extrusion: side triangles (B, A, D) and (B, D, C), one triangle when D = C (directional)",
          "[volumes][extrusion]") {
  std::vector<glm::uvec3> out;
  appendSideTriangles({3, 7, 0}, InfiniteIndexing{10, false}, out);
  CHECK(out == std::vector<glm::uvec3>{{7, 3, 13}, {7, 13, 17}});
  out.clear();
  appendSideTriangles({3, 7, 0}, InfiniteIndexing{10, true}, out);
  CHECK(out == std::vector<glm::uvec3>{{7, 3, 10}});
}

TEST_CASE("extrusion: every side face's normal points away from a convex occluder", "[volumes][extrusion]") {
  // The plane of a side contains the silhouette edge and the light; a convex occluder lies wholly
  // on its inner side. The normal of the finite triangle (B, A, A + (A·L_w − L)) must see every
  // occluder vertex behind or on the plane.
  std::mt19937_64 rng(99);
  for (const Mesh& original : {makeBox({2.0, 1.0, 3.0}), makeSphere(1.0, 14, 9), makeCylinder(1.0, 2.0, 12)}) {
    for (int trial = 0; trial < 10; ++trial) {
      const Mesh mesh = testing::transformed(original, testing::randomRotation(rng));
      const glm::dvec4 light = testing::randomLight(rng, trial % 2 == 1);
      const ShadowVolume v = buildShadowVolume(mesh, light, SilhouetteAlgorithm::Kuhn, false);
      REQUIRE(!v.silhouette.empty());
      for (const SilhouetteEdge& e : v.silhouette) {
        const auto q = sideQuad(mesh.weldedPositions[e.a], mesh.weldedPositions[e.b], light);
        const glm::dvec3 B(q[0]), A(q[1]), D = A + glm::dvec3(q[2]);
        const glm::dvec3 n = glm::normalize(glm::cross(A - B, D - B));
        double worst = -1.0;
        for (const glm::dvec3& p : mesh.weldedPositions) worst = std::max(worst, glm::dot(n, p - A));
        INFO(original.name << " trial " << trial);
        CHECK(worst < 1e-9);
      }
    }
  }
}
