#include <catch2/catch.hpp>

#include "scene/primitives.h"
#include "shadow/caps.h"
#include "shadow/facing.h"
#include "shadow/shadow_volume.h"
#include "volume_fixtures.h"

using namespace shadowref;

TEST_CASE("caps: front cap = the light-facing triangles as they are, back cap = the others at infinity",
          "[volumes][caps]") {
  const Mesh box = makeBox({2.0, 2.0, 2.0});
  const glm::dvec4 light(6, 6, 6, 1);  // a corner: three faces lit
  const ShadowVolume v = buildShadowVolume(box, light, SilhouetteAlgorithm::Kuhn, true);
  CHECK(v.frontCap.size() == 6);
  CHECK(v.backCap.size() == 6);
  CHECK(v.stats.frontCapTriangles == 6);
  CHECK(v.stats.backCapTriangles == 6);
  std::vector<uint8_t> facing;
  computeFacing(box, light, facing);
  std::vector<glm::uvec3> lit, unlit;
  for (size_t t = 0; t < facing.size(); ++t) (facing[t] ? lit : unlit).push_back(box.weldedTriangles[t]);
  CHECK(v.frontCap == lit);
  REQUIRE(v.backCap.size() == unlit.size());
  for (size_t i = 0; i < unlit.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const glm::dvec4 p = v.positions[v.backCap[i][k]];
      CHECK(p == extrudeToInfinity(box.weldedPositions[unlit[i][k]], light));
      CHECK(p.w == 0.0);
    }
}

TEST_CASE("caps: the front cap's vertices are bit-for-bit the mesh's render positions with w = 1",
          "[volumes][caps]") {
  const Mesh sphere = makeSphere(1.3, 16, 10);
  const ShadowVolume v = buildShadowVolume(sphere, {0.3, 4, 1, 1}, SilhouetteAlgorithm::Kuhn, true);
  REQUIRE(!v.frontCap.empty());
  // Every render vertex of a lit triangle, looked up through the weld, is the cap vertex.
  for (size_t t = 0; t < sphere.triangles.size(); ++t) {
    const glm::uvec3 w = sphere.weldedTriangles[t];
    if (std::find(v.frontCap.begin(), v.frontCap.end(), w) == v.frontCap.end()) continue;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec4 cap = v.positions[w[k]];
      CHECK(cap == glm::dvec4(sphere.positions[sphere.triangles[t][k]], 1.0));
    }
  }
}

TEST_CASE("caps: a directional light has a front cap but no back cap", "[volumes][caps]") {
  const Mesh sphere = makeSphere(1.0, 12, 8);
  const ShadowVolume v = buildShadowVolume(sphere, {0, 1, 0, 0}, SilhouetteAlgorithm::Kuhn, true);
  CHECK(v.frontCap.size() == v.stats.facingTriangles);
  CHECK(!v.frontCap.empty());
  CHECK(v.backCap.empty());
  // One shared point at infinity, the direction the light travels.
  CHECK(v.positions.size() == sphere.weldedPositions.size() + 1);
  CHECK(v.positions.back() == glm::dvec4(0, -1, 0, 0));
}

TEST_CASE("caps: counts add up to the mesh, without caps neither is built", "[volumes][caps]") {
  std::mt19937_64 rng(5);
  for (const Mesh& mesh : testing::closedTestMeshes()) {
    const glm::dvec4 light = testing::randomLight(rng, false);
    const ShadowVolume capped = buildShadowVolume(mesh, light, SilhouetteAlgorithm::Kuhn, true);
    CHECK(capped.frontCap.size() + capped.backCap.size() == mesh.weldedTriangles.size());
    CHECK(capped.frontCap.size() == capped.stats.facingTriangles);
    const ShadowVolume bare = buildShadowVolume(mesh, light, SilhouetteAlgorithm::Kuhn, false);
    CHECK(bare.frontCap.empty());
    CHECK(bare.backCap.empty());
    CHECK(bare.sides == capped.sides);
  }
}
