#include <span>
#include <catch2/catch.hpp>

#include <set>

#include "scene/primitives.h"
#include "shadow/facing.h"
#include "shadow/silhouette.h"
#include "volume_fixtures.h"

using namespace shadowref;

namespace {

constexpr SilhouetteAlgorithm kAll[] = {SilhouetteAlgorithm::Kuhn, SilhouetteAlgorithm::YenKwoon,
                                        SilhouetteAlgorithm::Kilgard, SilhouetteAlgorithm::Lengyel};

std::vector<SilhouetteEdge> silhouetteOf(const Mesh& mesh, const glm::dvec4& light, SilhouetteAlgorithm algorithm) {
  std::vector<uint8_t> facing;
  computeFacing(mesh, light, facing);
  std::vector<SilhouetteEdge> edges;
  findSilhouette(mesh, facing, algorithm, edges);
  return edges;
}

// Independent of every algorithm: for each pair of triangle corners a -> b, look through ALL
// triangles for the one running b -> a (O(n²)); silhouette when the first faces and the other does
// not, or when there is no other.
std::vector<testing::EdgeKey> bruteForceSilhouette(const Mesh& mesh, std::span<const uint8_t> facing) {
  std::vector<testing::EdgeKey> out;
  const auto& T = mesh.weldedTriangles;
  for (uint32_t t = 0; t < T.size(); ++t) {
    if (!facing[t]) continue;
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = T[t][i], b = T[t][(i + 1) % 3];
      uint32_t other = kNoTriangle;
      for (uint32_t u = 0; u < T.size(); ++u)
        for (int j = 0; j < 3; ++j)
          if (T[u][j] == b && T[u][(j + 1) % 3] == a) other = u;
      if (other == kNoTriangle || !facing[other]) out.emplace_back(a, b, t);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

glm::dvec3 at(const Mesh& m, uint32_t v) { return m.weldedPositions[v]; }

// Silhouette loops are closed on a closed mesh: every vertex is left as often as it is entered.
bool formsClosedLoops(const std::vector<SilhouetteEdge>& edges) {
  std::map<uint32_t, int> balance;
  for (const SilhouetteEdge& e : edges) {
    ++balance[e.a];
    --balance[e.b];
  }
  return std::all_of(balance.begin(), balance.end(), [](const auto& kv) { return kv.second == 0; });
}

}  // namespace

TEST_CASE("silhouette: a box lit from a face has the 4 edges of that face, counter-clockwise seen from the light",
          "[volumes][silhouette]") {
  const Mesh box = makeBox({2.0, 2.0, 2.0});
  for (SilhouetteAlgorithm algorithm : kAll) {
    for (const glm::dvec4 light : {glm::dvec4(0, 0, 5, 1), glm::dvec4(0, 0, 1, 0)}) {
      INFO(name(algorithm) << " light w " << light.w);
      const auto edges = silhouetteOf(box, light, algorithm);
      REQUIRE(edges.size() == 4);
      for (const SilhouetteEdge& e : edges) {
        const glm::dvec3 a = at(box, e.a), b = at(box, e.b);
        CHECK(a.z == 1.0);
        CHECK(b.z == 1.0);
        CHECK(glm::length(b - a) == 2.0);  // a side of the face, not its diagonal
        // The face centre (0, 0, 1) lies to the left of a -> b seen from +z: counter-clockwise.
        CHECK(glm::cross(b - a, glm::dvec3(0, 0, 1) - a).z > 0.0);
      }
      CHECK(formsClosedLoops(edges));
    }
  }
}

TEST_CASE("silhouette: a box lit from a corner direction has the 6-edge hexagon avoiding the lit and the far corner",
          "[volumes][silhouette]") {
  const Mesh box = makeBox({2.0, 2.0, 2.0});
  for (SilhouetteAlgorithm algorithm : kAll) {
    for (const glm::dvec4 light : {glm::dvec4(6, 6, 6, 1), glm::dvec4(glm::normalize(glm::dvec3(1, 1, 1)), 0)}) {
      INFO(name(algorithm) << " light w " << light.w);
      const auto edges = silhouetteOf(box, light, algorithm);
      REQUIRE(edges.size() == 6);
      std::set<uint32_t> corners;
      for (const SilhouetteEdge& e : edges) {
        const glm::dvec3 a = at(box, e.a), b = at(box, e.b);
        CHECK(glm::length(b - a) == 2.0);
        for (const glm::dvec3 p : {a, b}) {
          CHECK(p != glm::dvec3(1, 1, 1));
          CHECK(p != glm::dvec3(-1, -1, -1));
        }
        corners.insert(e.a);
        // Oriented as in the lit triangle: counter-clockwise seen from the light, i.e. the
        // hexagon winds positively about the direction (1, 1, 1).
        CHECK(glm::dot(glm::cross(a, b), glm::dvec3(1, 1, 1)) > 0.0);
      }
      CHECK(corners.size() == 6);
      CHECK(formsClosedLoops(edges));
    }
  }
}

TEST_CASE("silhouette: the four algorithms find the same oriented edges on closed meshes under random rotations and lights",
          "[volumes][silhouette]") {
  std::mt19937_64 rng(20240601);
  for (const Mesh& original : testing::closedTestMeshes()) {
    for (int trial = 0; trial < 12; ++trial) {
      const Mesh mesh = testing::transformed(original, testing::randomRotation(rng));
      REQUIRE(mesh.topology == Topology::Closed);
      const bool directional = trial % 3 == 2;
      const glm::dvec4 light = testing::randomLight(rng, directional);
      INFO("mesh " << original.name << " trial " << trial << " directional " << directional);
      std::vector<uint8_t> facing;
      computeFacing(mesh, light, facing);
      const auto expected = bruteForceSilhouette(mesh, facing);
      CHECK(!expected.empty());
      SilhouetteWorkspace workspace;  // reused across algorithms and trials on purpose
      for (SilhouetteAlgorithm algorithm : kAll) {
        INFO(name(algorithm));
        std::vector<SilhouetteEdge> edges;
        findSilhouette(mesh, facing, algorithm, edges, &workspace);
        CHECK(testing::sortedEdges(edges) == expected);
        CHECK(formsClosedLoops(edges));
      }
    }
  }
}

TEST_CASE("silhouette: Kuhn's edge loop reports edges in the order of the mesh's edge list", "[volumes][silhouette]") {
  const Mesh box = makeBox({2.0, 2.0, 2.0});
  const auto edges = silhouetteOf(box, {0, 0, 5, 1}, SilhouetteAlgorithm::Kuhn);
  std::vector<size_t> positions;
  for (const SilhouetteEdge& e : edges)
    for (size_t i = 0; i < box.edges.size(); ++i) {
      const Edge& m = box.edges[i];
      if ((m.v0 == e.a && m.v1 == e.b) || (m.v0 == e.b && m.v1 == e.a)) positions.push_back(i);
    }
  REQUIRE(positions.size() == edges.size());
  CHECK(std::is_sorted(positions.begin(), positions.end()));
}

namespace {

// A 2x2x2 box without its top (+y) face: four open edges around the rim.
Mesh openTopBox() {
  Mesh box = makeBox({2.0, 2.0, 2.0});
  Mesh open;
  open.name = "open-top box";
  open.positions = box.positions;
  open.normals = box.normals;
  for (size_t t = 0; t < box.triangles.size(); ++t)
    if (box.faceNormals[t].y < 0.99) open.triangles.push_back(box.triangles[t]);
  buildAdjacency(open);
  return open;
}

}  // namespace

TEST_CASE("silhouette: an open edge counts when its one triangle faces the light, not otherwise ([SV slides], [DSS article])",
          "[volumes][silhouette]") {
  const Mesh mesh = openTopBox();
  REQUIRE(mesh.topology == Topology::Open);
  REQUIRE(mesh.openEdges == 4);
  for (SilhouetteAlgorithm algorithm : kAll) {
    INFO(name(algorithm));
    // Lit from +x: the +x wall faces the light; its four sides are silhouette, the top one open.
    const auto edges = silhouetteOf(mesh, {5, 0, 0, 1}, algorithm);
    REQUIRE(edges.size() == 4);
    int openRimEdges = 0;
    for (const SilhouetteEdge& e : edges) {
      CHECK(at(mesh, e.a).x == 1.0);
      CHECK(at(mesh, e.b).x == 1.0);
      if (at(mesh, e.a).y == 1.0 && at(mesh, e.b).y == 1.0) ++openRimEdges;
    }
    CHECK(openRimEdges == 1);  // the rim edge of the -x wall (averted) is not among them
  }
  // And the four algorithms agree on the open mesh under random lights.
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const glm::dvec4 light = testing::randomLight(rng, trial % 2 == 1);
    std::vector<uint8_t> facing;
    computeFacing(mesh, light, facing);
    const auto expected = bruteForceSilhouette(mesh, facing);
    for (SilhouetteAlgorithm algorithm : kAll) {
      INFO(name(algorithm) << " trial " << trial);
      CHECK(testing::sortedEdges(silhouetteOf(mesh, light, algorithm)) == expected);
    }
  }
}

TEST_CASE("silhouette: a lone triangle lit from the front has 3 edges, lit from behind none", "[volumes][silhouette]") {
  Mesh tri;
  tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.triangles = {{0, 1, 2}};
  computeSmoothNormals(tri);
  buildAdjacency(tri);
  for (SilhouetteAlgorithm algorithm : kAll) {
    INFO(name(algorithm));
    const auto front = silhouetteOf(tri, {0.2, 0.2, 3, 1}, algorithm);
    CHECK(testing::sortedEdges(front) ==
          std::vector<testing::EdgeKey>{{0, 1, 0}, {1, 2, 0}, {2, 0, 0}});
    CHECK(silhouetteOf(tri, {0.2, 0.2, -3, 1}, algorithm).empty());
  }
}
