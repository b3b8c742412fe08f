// The shadow volumes of meshes that are not closed, consistently wound, outward solids
// (shadow/volume_casting.h): open (a lone triangle, a tent without floor or front), non-manifold
// (three fins on one edge), inconsistently wound and inside out. Expectations are built by hand
// from the geometry, or from a correctly wound copy of the same mesh.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <utility>

#include "scene/adjacency.h"
#include "scene/primitives.h"
#include "shadow/shadow_volume.h"
#include "volume_fixtures.h"

using namespace shadowref;

namespace {

Mesh meshOf(std::vector<glm::dvec3> positions, std::vector<glm::uvec3> triangles, const char* name) {
  Mesh m;
  m.name = name;
  m.positions = std::move(positions);
  m.triangles = std::move(triangles);
  computeSmoothNormals(m);
  buildAdjacency(m);
  return m;
}

// scenes/meshes/tent.obj: ridge along z at y = 1.2, eaves at x = +-1, the back gable at z = -1.2;
// no floor, the front open. Counter-clockwise seen from outside.
Mesh tent() {
  return meshOf({{0, 1.2, 1.2}, {1, 0, 1.2}, {1, 0, -1.2}, {0, 1.2, -1.2}, {-1, 0, -1.2}, {-1, 0, 1.2}},
                {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {4, 3, 2}}, "tent");
}

Mesh loneTriangle() { return meshOf({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}, "triangle"); }

// Three fins on the edge (0,0,0)-(0,1,0), each running it 1 -> 0.
Mesh fins() {
  return meshOf({{0, 0, 0}, {0, 1, 0}, {0.6, 0.5, 0}, {-0.3, 0.5, 0.52}, {-0.3, 0.5, -0.52}},
                {{0, 2, 1}, {0, 3, 1}, {0, 4, 1}}, "fins");
}

Mesh reversed(const Mesh& m) {
  Mesh r = m;
  for (glm::uvec3& t : r.triangles) std::swap(t.y, t.z);
  buildAdjacency(r);
  return r;
}

// A box with one face's two triangles wound the other way round.
Mesh boxWithFlippedFace() {
  Mesh box = makeBox({1.0, 1.0, 1.0});
  Mesh m = box;
  for (size_t t = 0; t < m.triangles.size(); ++t)
    if (box.faceNormals[t].y > 0.99) std::swap(m.triangles[t].y, m.triangles[t].z);
  buildAdjacency(m);
  return m;
}

std::multiset<std::array<uint32_t, 3>> asSet(const std::vector<glm::uvec3>& tris) {
  std::multiset<std::array<uint32_t, 3>> s;
  for (const glm::uvec3& t : tris) {
    // The same triangle whichever corner comes first: rotate the smallest index to the front.
    const int k = t.x <= t.y && t.x <= t.z ? 0 : t.y <= t.z ? 1 : 2;
    s.insert({t[k], t[(k + 1) % 3], t[(k + 2) % 3]});
  }
  return s;
}

// Every directed edge as often as its reverse: the capped volume is closed (with multiplicity).
bool balanced(const ShadowVolume& v) {
  const auto count = testing::directedEdgeCounts({&v.sides, &v.frontCap, &v.backCap});
  for (const auto& [e, n] : count) {
    const auto reverse = count.find({e.second, e.first});
    if (reverse == count.end() || reverse->second != n) return false;
  }
  return true;
}

std::vector<Mesh> irregularMeshes() {
  std::vector<Mesh> meshes{tent(), loneTriangle(), fins(), boxWithFlippedFace(), reversed(makeSphere(1.0, 10, 6)),
                           reversed(makeBox({2.0, 1.0, 3.0}))};
  return meshes;
}

}  // namespace

TEST_CASE("casting: closed outward meshes keep the silhouette volume, inside-out ones are reversed, the rest "
          "two-sided", "[volumes][irregular]") {
  CHECK(volumeCastingOf(makeBox({1.0, 1.0, 1.0})) == VolumeCasting::Silhouette);
  CHECK(volumeCastingOf(reversed(makeBox({1.0, 1.0, 1.0}))) == VolumeCasting::Reversed);
  CHECK(volumeCastingOf(tent()) == VolumeCasting::TwoSided);
  CHECK(volumeCastingOf(loneTriangle()) == VolumeCasting::TwoSided);
  CHECK(volumeCastingOf(fins()) == VolumeCasting::TwoSided);
  CHECK(volumeCastingOf(boxWithFlippedFace()) == VolumeCasting::TwoSided);
  CHECK(castingWarning(makeBox({1.0, 1.0, 1.0})).empty());
  for (const Mesh& m : irregularMeshes()) {
    INFO(m.name);
    CHECK_THAT(castingWarning(m), Catch::Contains("'" + m.name + "'"));
  }
  CHECK_THAT(castingWarning(tent()), Catch::Contains("is open (5 edges with one triangle)"));
  CHECK_THAT(castingWarning(fins()), Catch::Contains("non-manifold (1 edges with three or more triangles)"));
  CHECK_THAT(castingWarning(boxWithFlippedFace()), Catch::Contains("inconsistently wound (4 edges"));
  CHECK_THAT(castingWarning(reversed(makeBox({1.0, 1.0, 1.0}))), Catch::Contains("inside out"));
}

TEST_CASE("a lone triangle casts from either side: lit from behind, the volume of the triangle turned round",
          "[volumes][irregular]") {
  const Mesh tri = loneTriangle();
  const glm::dvec4 front{0.2, 0.2, 3.0, 1.0}, behind{0.2, 0.2, -3.0, 1.0};
  const ShadowVolume lit = buildShadowVolume(tri, front, SilhouetteAlgorithm::Kuhn, true);
  CHECK(lit.frontCap == std::vector<glm::uvec3>{{0, 1, 2}});
  CHECK(lit.silhouette.size() == 3);
  const ShadowVolume back = buildShadowVolume(tri, behind, SilhouetteAlgorithm::Kuhn, true);
  // Turned round with its first corner kept first (bit-equal depths, shadow_volume.cpp).
  CHECK(back.frontCap == std::vector<glm::uvec3>{{0, 2, 1}});
  CHECK(back.backCap == std::vector<glm::uvec3>{{3, 4, 5}});  // (0, 1, 2) at infinity faces away
  REQUIRE(back.silhouette.size() == 3);
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (const SilhouetteEdge& e : back.silhouette) edges.insert({e.a, e.b});
  CHECK(edges == std::set<std::pair<uint32_t, uint32_t>>{{0, 2}, {2, 1}, {1, 0}});
  CHECK(balanced(back));
  // Pointing outward: the truncated volume is positive, and equal from either side by symmetry of
  // the lights about the triangle's plane.
  CHECK(testing::truncatedSignedVolume(back, 1.0) > 0.0);
  CHECK(testing::truncatedSignedVolume(back, 1.0) == Approx(testing::truncatedSignedVolume(lit, 1.0)));
  // The light in the triangle's plane: no volume at all.
  const ShadowVolume edgeOn = buildShadowVolume(tri, {2.0, 3.0, 0.0, 1.0}, SilhouetteAlgorithm::Kuhn, true);
  CHECK(edgeOn.triangleCount() == 0);
}

TEST_CASE("the tent lit from one side: the ridge and the gable's top edge have two side quads, every open edge "
          "one, and z-pass gets the front cap", "[volumes][irregular]") {
  const Mesh mesh = tent();
  const glm::dvec4 light{5.0, 4.0, 0.3, 1.0};  // right of the tent, above the eave: the right roof faces it
  const ShadowVolume v = buildShadowVolume(mesh, light, SilhouetteAlgorithm::Kuhn, true);
  std::map<std::pair<uint32_t, uint32_t>, int> quads;  // unordered edge -> side quads
  for (const SilhouetteEdge& e : v.silhouette) ++quads[{std::min(e.a, e.b), std::max(e.a, e.b)}];
  // The left roof and the gable face away from the light and are turned round. The ridge: the lit
  // right roof and the turned-round left one run it alike, 3 -> 0. The same at the right roof's
  // back edge 2-3 with the turned-round gable; at the left roof's back edge 3-4 the two turned-round
  // triangles run it opposite ways and cancel.
  CHECK(quads[{0, 3}] == 2);
  CHECK(quads[{2, 3}] == 2);
  CHECK(quads.count({3, 4}) == 0);
  const std::vector<std::pair<uint32_t, uint32_t>> openEdges{{0, 1}, {1, 2}, {4, 5}, {0, 5}, {2, 4}};
  for (const auto& open : openEdges) CHECK(quads[open] == 1);
  CHECK(quads.count({0, 2}) == 0);  // interior diagonals of a roof quad cancel
  CHECK(quads.count({0, 4}) == 0);
  CHECK(v.silhouette.size() == 9);
  // Every triangle casts, once, as front cap and (point light) as back cap.
  CHECK(v.frontCap.size() == 5);
  CHECK(v.backCap.size() == 5);
  CHECK(balanced(v));
  CHECK(testing::truncatedSignedVolume(v, 1.0) > 0.0);

  const ShadowVolume zpass = buildShadowVolume(mesh, light, SilhouetteAlgorithm::Kuhn, false);
  CHECK(zpass.frontCapInZPass());
  CHECK(zpass.frontCap == v.frontCap);
  CHECK(zpass.backCap.empty());
  CHECK(zpass.sides == v.sides);
}

TEST_CASE("two-sided volumes are closed and count like their per-triangle volumes, for every silhouette "
          "algorithm and light", "[volumes][irregular]") {
  std::mt19937_64 rng(2024);
  for (const Mesh& original : irregularMeshes()) {
    for (int trial = 0; trial < 8; ++trial) {
      const Mesh mesh = testing::transformed(original, testing::randomRotation(rng));
      const bool directional = trial % 2 == 1;
      const glm::dvec4 light = testing::randomLight(rng, directional);
      INFO(original.name << " trial " << trial << " directional " << directional);
      const ShadowVolume parts = buildTriangleVolumes(mesh, light, true);
      REQUIRE(balanced(parts));
      for (SilhouetteAlgorithm algorithm : {SilhouetteAlgorithm::Kuhn, SilhouetteAlgorithm::YenKwoon,
                                            SilhouetteAlgorithm::Kilgard, SilhouetteAlgorithm::Lengyel}) {
        const ShadowVolume v = buildShadowVolume(mesh, light, algorithm, true);
        CHECK(balanced(v));
        CHECK(v.casting != VolumeCasting::Silhouette);
        // Same caps as the per-triangle volumes; the sides are theirs with opposite pairs removed.
        CHECK(asSet(v.frontCap) == asSet(parts.frontCap));
        CHECK(asSet(v.backCap) == asSet(parts.backCap));
        std::map<std::pair<uint32_t, uint32_t>, int> net, kept;
        for (const SilhouetteEdge& e : parts.silhouette) ++net[{e.a, e.b}], --net[{e.b, e.a}];
        for (const SilhouetteEdge& e : v.silhouette) ++kept[{e.a, e.b}];
        for (const auto& [e, n] : net)
          if (n > 0) CHECK(kept[e] == n);
        for (const auto& [e, n] : kept) CHECK(net[e] == n);
        if (!directional) {
          // Outward: every per-triangle volume encloses a positive volume, so their sum does.
          CHECK(testing::truncatedSignedVolume(v, 1.0) > 0.0);
          CHECK(testing::truncatedSignedVolume(v, 1.0) == Approx(testing::truncatedSignedVolume(parts, 1.0)));
        }
      }
    }
  }
}

TEST_CASE("an inside-out closed mesh gets the volume of the same mesh wound the right way", "[volumes][irregular]") {
  std::mt19937_64 rng(77);
  for (const Mesh& original : testing::closedTestMeshes()) {
    for (int trial = 0; trial < 6; ++trial) {
      const Mesh outward = testing::transformed(original, testing::randomRotation(rng));
      const Mesh insideOut = reversed(outward);
      REQUIRE(insideOut.insideOut);
      REQUIRE(insideOut.weldedPositions == outward.weldedPositions);  // the same vertex indices
      const glm::dvec4 light = testing::randomLight(rng, trial % 2 == 1);
      INFO(original.name << " trial " << trial);
      const ShadowVolume right = buildShadowVolume(outward, light, SilhouetteAlgorithm::Kuhn, true);
      const ShadowVolume v = buildShadowVolume(insideOut, light, SilhouetteAlgorithm::Kuhn, true);
      CHECK(v.casting == VolumeCasting::Reversed);
      CHECK(asSet(v.sides) == asSet(right.sides));
      CHECK(asSet(v.frontCap) == asSet(right.frontCap));
      CHECK(testing::everyEdgeOnceEachWay(testing::directedEdgeCounts({&v.sides, &v.frontCap, &v.backCap})));
      // Truncated at reach r, the right volume ends in the averted faces scaled by s = 1 + r about
      // the light, this one in the light-facing faces (turned round) scaled alike: the two differ
      // by the scaled mesh, s³ times its volume.
      const double s = 2.5;
      if (light.w != 0.0)
        CHECK(testing::truncatedSignedVolume(v, 1.5) ==
              Approx(testing::truncatedSignedVolume(right, 1.5) - s * s * s * signedVolume(outward)).epsilon(1e-9));
    }
  }
}

TEST_CASE("a closed outward mesh's volume is unchanged: no front cap without caps", "[volumes][irregular]") {
  const ShadowVolume v = buildShadowVolume(makeSphere(1.0, 12, 8), {3, 1, 0.5, 1}, SilhouetteAlgorithm::Kuhn, false);
  CHECK(v.casting == VolumeCasting::Silhouette);
  CHECK_FALSE(v.frontCapInZPass());
  CHECK(v.frontCap.empty());
}
