#include <catch2/catch.hpp>

#include "scene/primitives.h"
#include "shadow/shadow_volume.h"
#include "volume_fixtures.h"

using namespace shadowref;

TEST_CASE("shadow volume: with caps it is a closed 2-manifold, every edge used once each way",
          "[volumes][shadow_volume]") {
  std::mt19937_64 rng(31337);
  for (const Mesh& original : testing::closedTestMeshes()) {
    for (int trial = 0; trial < 8; ++trial) {
      const Mesh mesh = testing::transformed(original, testing::randomRotation(rng));
      const bool directional = trial % 2 == 1;
      const glm::dvec4 light = testing::randomLight(rng, directional);
      for (SilhouetteAlgorithm algorithm : {SilhouetteAlgorithm::Kuhn, SilhouetteAlgorithm::YenKwoon,
                                            SilhouetteAlgorithm::Kilgard, SilhouetteAlgorithm::Lengyel}) {
        INFO(original.name << " trial " << trial << " directional " << directional << " " << name(algorithm));
        const ShadowVolume v = buildShadowVolume(mesh, light, algorithm, true);
        CHECK(testing::everyEdgeOnceEachWay(testing::directedEdgeCounts({&v.sides, &v.frontCap, &v.backCap})));
      }
    }
  }
}

TEST_CASE("shadow volume: without caps the sides are open along the silhouette and its image at infinity",
          "[volumes][shadow_volume]") {
  const Mesh sphere = makeSphere(1.0, 12, 8);
  const ShadowVolume v = buildShadowVolume(sphere, {3, 1, 0.5, 1}, SilhouetteAlgorithm::Kuhn, false);
  const auto count = testing::directedEdgeCounts({&v.sides});
  // A directed edge without its reverse is a border. Near the occluder the border is the
  // silhouette reversed (the front cap, which runs it a -> b, is missing); at infinity it is the
  // silhouette carried to infinity (the back cap would run it the other way).
  std::set<std::pair<uint32_t, uint32_t>> border, expected;
  for (const auto& [e, n] : count)
    if (!count.count({e.second, e.first})) border.insert(e);
  for (const SilhouetteEdge& e : v.silhouette) {
    expected.insert({e.b, e.a});
    expected.insert({v.infinite(e.a), v.infinite(e.b)});
  }
  CHECK(border == expected);
}

TEST_CASE("shadow volume: faces point outward — the truncated volume of a point light has positive volume",
          "[volumes][shadow_volume]") {
  std::mt19937_64 rng(8);
  for (const Mesh& original : testing::closedTestMeshes()) {
    for (int trial = 0; trial < 6; ++trial) {
      const Mesh mesh = testing::transformed(original, testing::randomRotation(rng));
      const glm::dvec4 light = testing::randomLight(rng, false);
      const ShadowVolume v = buildShadowVolume(mesh, light, SilhouetteAlgorithm::Kuhn, true);
      INFO(original.name << " trial " << trial);
      const double v1 = testing::truncatedSignedVolume(v, 1.0), v2 = testing::truncatedSignedVolume(v, 2.0);
      CHECK(v1 > 0.0);
      CHECK(v2 > v1);  // reaching further encloses more: the sides open away from the light
    }
  }
}

TEST_CASE("shadow volume: a cube lit from straight above, truncated, encloses frustum plus scaled cube",
          "[volumes][shadow_volume]") {
  // Cube [-1, 1]³, light at (0, 5, 0): the top face is lit. Truncated at reach r every point at
  // infinity becomes V + r(V − L), i.e. V scaled about the light by s = 1 + r. The surface is then
  // top face + sides + the five other faces scaled: a frustum from the top face (side 2, 4 below
  // the light) down to the scaled top square (side 2s), on which the scaled cube (side 2s) sits.
  const Mesh cube = makeBox({2.0, 2.0, 2.0});
  const ShadowVolume v = buildShadowVolume(cube, {0, 5, 0, 1}, SilhouetteAlgorithm::Kuhn, true);
  const double r = 1.0, s = 1.0 + r;
  const double height = 4.0 * r, a0 = 4.0, a1 = 4.0 * s * s;
  const double frustum = height / 3.0 * (a0 + a1 + std::sqrt(a0 * a1));
  CHECK(testing::truncatedSignedVolume(v, r) == Approx(frustum + 8.0 * s * s * s).epsilon(1e-12));
}

TEST_CASE("shadow volume: stats count edges, side triangles and caps", "[volumes][shadow_volume]") {
  const Mesh box = makeBox({2.0, 2.0, 2.0});
  const ShadowVolume point = buildShadowVolume(box, {6, 6, 6, 1});
  CHECK(point.stats.facingTriangles == 6);
  CHECK(point.stats.silhouetteEdges == 6);
  CHECK(point.stats.sideTriangles == 12);
  CHECK(point.stats.frontCapTriangles == 6);
  CHECK(point.stats.backCapTriangles == 6);
  CHECK(point.triangleCount() == 24);
  CHECK(point.positions.size() == 16);
  const ShadowVolume sun = buildShadowVolume(box, {0, 0, 1, 0});
  CHECK(sun.stats.silhouetteEdges == 4);
  CHECK(sun.stats.sideTriangles == 4);  // D = C: one triangle per edge
  CHECK(sun.stats.backCapTriangles == 0);
}

TEST_CASE("shadow volume: a reused workspace and output give the same volume as fresh ones", "[volumes][shadow_volume]") {
  ShadowVolumeWorkspace workspace;
  ShadowVolume reused;
  std::mt19937_64 rng(77);
  for (const Mesh& mesh : testing::closedTestMeshes()) {
    for (SilhouetteAlgorithm algorithm : {SilhouetteAlgorithm::YenKwoon, SilhouetteAlgorithm::Lengyel}) {
      const glm::dvec4 light = testing::randomLight(rng, false);
      buildShadowVolume(mesh, light, algorithm, true, reused, &workspace);
      const ShadowVolume fresh = buildShadowVolume(mesh, light, algorithm, true);
      CHECK(reused.positions == fresh.positions);
      CHECK(reused.sides == fresh.sides);
      CHECK(reused.frontCap == fresh.frontCap);
      CHECK(reused.backCap == fresh.backCap);
    }
  }
}

TEST_CASE("shadow volume: the per-triangle volumes are closed, and their sides cancel to the silhouette's",
          "[volumes][shadow_volume]") {
  std::mt19937_64 rng(12);
  for (const Mesh& mesh : testing::closedTestMeshes()) {
    const glm::dvec4 light = testing::randomLight(rng, false);
    const ShadowVolume parts = buildTriangleVolumes(mesh, light, true);
    const ShadowVolume whole = buildShadowVolume(mesh, light, SilhouetteAlgorithm::Kuhn, true);
    // Closed: each directed edge as often as its reverse.
    const auto count = testing::directedEdgeCounts({&parts.sides, &parts.frontCap, &parts.backCap});
    for (const auto& [e, n] : count) {
      auto reverse = count.find({e.second, e.first});
      CHECK((reverse != count.end() && reverse->second == n));
    }
    // Side quads of edges interior to the lit region come in opposite pairs; what is left over
    // is the silhouette volume's sides.
    std::map<std::pair<uint32_t, uint32_t>, int> net;
    for (const SilhouetteEdge& e : parts.silhouette) {
      ++net[{e.a, e.b}];
      --net[{e.b, e.a}];
    }
    std::set<std::pair<uint32_t, uint32_t>> remaining, silhouette;
    for (const auto& [e, n] : net)
      if (n > 0) remaining.insert(e);
    for (const SilhouetteEdge& e : whole.silhouette) silhouette.insert({e.a, e.b});
    CHECK(remaining == silhouette);
    // As surfaces, whole − parts = the averted and the lit faces scaled about the light: the mesh
    // scaled by s = 1 + reach, enclosing s³ times its volume.
    const double reach = 1.5, s = 1.0 + reach;
    CHECK(testing::truncatedSignedVolume(whole, reach) - testing::truncatedSignedVolume(parts, reach) ==
          Approx(s * s * s * signedVolume(mesh)).epsilon(1e-9));
  }
}

TEST_CASE("shadow volume: a second build with reused buffers does not reallocate them", "[volumes][shadow_volume]") {
  const Mesh torus = makeTorus(1.0, 0.4, 24, 12);
  const glm::dvec4 light(2, 3, 1, 1);
  for (SilhouetteAlgorithm algorithm : {SilhouetteAlgorithm::Kuhn, SilhouetteAlgorithm::YenKwoon,
                                        SilhouetteAlgorithm::Kilgard, SilhouetteAlgorithm::Lengyel}) {
    INFO(name(algorithm));
    ShadowVolumeWorkspace ws;
    ShadowVolume v;
    buildShadowVolume(torus, light, algorithm, true, v, &ws);
    const void* before[] = {v.positions.data(), v.sides.data(), v.frontCap.data(), v.backCap.data(),
                            v.silhouette.data(), ws.facing.data(), ws.silhouette.toggleSlots.data(),
                            ws.silhouette.neighbours.data(), ws.silhouette.lengyelEdges.data()};
    buildShadowVolume(torus, light, algorithm, true, v, &ws);
    const void* after[] = {v.positions.data(), v.sides.data(), v.frontCap.data(), v.backCap.data(),
                           v.silhouette.data(), ws.facing.data(), ws.silhouette.toggleSlots.data(),
                           ws.silhouette.neighbours.data(), ws.silhouette.lengyelEdges.data()};
    for (size_t i = 0; i < std::size(before); ++i) CHECK(before[i] == after[i]);
  }
}
