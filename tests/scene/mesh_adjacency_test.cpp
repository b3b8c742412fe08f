#include <catch2/catch.hpp>

#include <tuple>
#include <vector>

#include "scene/adjacency.h"
#include "scene/primitives.h"
#include "mesh_checks.h"

using namespace shadowref;

namespace {

Mesh fromTriangles(std::vector<glm::dvec3> positions, std::vector<glm::uvec3> triangles) {
  Mesh m;
  m.name = "test";
  m.positions = std::move(positions);
  m.triangles = std::move(triangles);
  computeSmoothNormals(m);
  return m;
}

// A tetrahedron, counter-clockwise seen from outside.
Mesh tetrahedron() {
  return fromTriangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                       {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

}  // namespace

TEST_CASE("a tetrahedron is closed: 4 vertices, 6 edges, 4 faces, volume 1/6", "[mesh]") {
  Mesh m = tetrahedron();
  buildAdjacency(m);
  shadowref::testing::requireClosedOutward(m);
  CHECK(m.edges.size() == 6);
  CHECK(signedVolume(m) == Approx(1.0 / 6.0));
}

TEST_CASE("edges come in order of first appearance, v0 -> v1 as they run in t0", "[mesh]") {
  Mesh m = tetrahedron();
  buildAdjacency(m);
  // Triangle 0 is (0, 2, 1): its edges 0->2, 2->1, 1->0 come first, in that order.
  REQUIRE(m.edges.size() == 6);
  CHECK(m.edges[0].v0 == 0);
  CHECK(m.edges[0].v1 == 2);
  CHECK(m.edges[1].v0 == 2);
  CHECK(m.edges[1].v1 == 1);
  CHECK(m.edges[2].v0 == 1);
  CHECK(m.edges[2].v1 == 0);
  CHECK(m.edges[0].t0 == 0);
  // Edge 1-0 appears again in triangle 1 (0, 1, 3), running 0 -> 1.
  CHECK(m.edges[2].t1 == 1);
  // Triangle 1 adds 1->3 and 3->0 as new edges.
  CHECK(m.edges[3].v0 == 1);
  CHECK(m.edges[3].v1 == 3);
  CHECK(m.edges[3].t0 == 1);
}

TEST_CASE("a single triangle is open with three open edges", "[mesh]") {
  Mesh m = fromTriangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  buildAdjacency(m);
  CHECK(m.topology == Topology::Open);
  CHECK(m.openEdges == 3);
  CHECK(m.nonManifoldEdges == 0);
  for (const Edge& e : m.edges) CHECK(e.t1 == kNoTriangle);
}

TEST_CASE("a tetrahedron missing one face is open with exactly three open edges", "[mesh]") {
  Mesh m = tetrahedron();
  m.triangles.pop_back();
  buildAdjacency(m);
  CHECK(m.topology == Topology::Open);
  CHECK(m.openEdges == 3);
  CHECK(m.edges.size() == 6);
}

TEST_CASE("three triangles on one edge make it non-manifold", "[mesh]") {
  // Three fins sharing the edge (0,0,0)-(0,0,1).
  Mesh m = fromTriangles({{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, -1, 0}},
                         {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  buildAdjacency(m);
  CHECK(m.topology == Topology::NonManifold);
  CHECK(m.nonManifoldEdges == 1);
  CHECK(m.openEdges == 6);
  CHECK(m.edges[0].triangleCount == 3);
}

TEST_CASE("non-manifold wins over open in the classification", "[mesh]") {
  Mesh m = fromTriangles({{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, -1, 0}},
                         {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  buildAdjacency(m);
  CHECK(m.openEdges > 0);
  CHECK(m.topology == Topology::NonManifold);
}

TEST_CASE("a neighbour wound the wrong way round is counted as inconsistent", "[mesh]") {
  Mesh m = tetrahedron();
  std::swap(m.triangles[3].y, m.triangles[3].z);
  buildAdjacency(m);
  CHECK(m.topology == Topology::Closed);  // still two triangles per edge
  CHECK(m.inconsistentEdges == 3);
}

TEST_CASE("render vertices at bit-equal positions weld, -0.0 and +0.0 included", "[mesh]") {
  // Two triangles sharing an edge, the second with its own copies and a negative zero.
  Mesh m = fromTriangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {-0.0, 1, -0.0}, {1, 1, 0}},
                         {{0, 1, 2}, {3, 5, 4}});
  buildAdjacency(m);
  CHECK(m.weldedPositions.size() == 4);
  CHECK(m.weldIndex == std::vector<uint32_t>{0, 1, 2, 1, 2, 3});
  CHECK(m.edges.size() == 5);
  CHECK(m.openEdges == 4);
  CHECK(!std::signbit(m.weldedPositions[2].x));
}

TEST_CASE("positions that differ in the last bit do not weld", "[mesh]") {
  const double nearlyOne = std::nextafter(1.0, 0.0);
  Mesh m = fromTriangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {nearlyOne, 0, 0}, {0, 1, 0}, {1, 1, 0}},
                         {{0, 1, 2}, {3, 5, 4}});
  buildAdjacency(m);
  CHECK(m.weldedPositions.size() == 5);
}

TEST_CASE("degenerate triangles are dropped from both views with a warning each", "[mesh]") {
  Mesh m = tetrahedron();
  m.positions.push_back({0.5, 0.5, 0.5});
  m.positions.push_back({1.0, 1.0, 1.0});
  m.positions.push_back({2.0, 2.0, 2.0});  // collinear with the previous two: zero area
  m.normals.resize(m.positions.size(), glm::dvec3(0, 1, 0));
  m.triangles.insert(m.triangles.begin() + 1, glm::uvec3(4, 5, 6));  // zero area
  m.triangles.push_back(glm::uvec3(0, 1, 1));                        // repeated corner
  std::vector<std::string> warnings;
  buildAdjacency(m, &warnings);
  REQUIRE(warnings.size() == 2);
  CHECK(warnings[0].find("triangle 1") != std::string::npos);
  CHECK(warnings[0].find("zero area") != std::string::npos);
  CHECK(warnings[1].find("triangle 5") != std::string::npos);
  CHECK(m.triangles.size() == 4);
  CHECK(m.weldedTriangles.size() == 4);
  CHECK(m.faceNormals.size() == 4);
  CHECK(m.triangles[1] == glm::uvec3(0, 1, 3));  // the tetrahedron's second face moved up
  shadowref::testing::requireClosedOutward(m);
}

TEST_CASE("face normals are unit, from the welded positions, and bounds cover them", "[mesh]") {
  Mesh m = tetrahedron();
  buildAdjacency(m);
  CHECK(m.faceNormals[0] == glm::dvec3(0, 0, -1));
  CHECK(m.faceNormals[3].x == Approx(1.0 / std::sqrt(3.0)));
  CHECK(m.bounds.min == glm::dvec3(0.0));
  CHECK(m.bounds.max == glm::dvec3(1.0));
}

TEST_CASE("building adjacency twice gives the same result", "[mesh]") {
  Mesh m = tetrahedron();
  buildAdjacency(m);
  const size_t edges = m.edges.size();
  buildAdjacency(m);
  CHECK(m.edges.size() == edges);
  CHECK(m.weldedPositions.size() == 4);
}

TEST_CASE("crease normals keep a cube's corners sharp and split them per face", "[mesh]") {
  // A cube as 8 shared corners: crease normals must split each corner into 3 render vertices.
  std::vector<glm::dvec3> c;
  for (int i = 0; i < 8; ++i) c.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  Mesh m = fromTriangles(c, {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                             {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}});
  computeCreaseNormals(m, 40.0);
  buildAdjacency(m);
  CHECK(m.positions.size() == 24);
  CHECK(m.weldedPositions.size() == 8);
  shadowref::testing::requireClosedOutward(m);
  shadowref::testing::requireNormalsAgreeWithWinding(m);
  for (const glm::dvec3& n : m.normals) CHECK(std::abs(n.x) + std::abs(n.y) + std::abs(n.z) == Approx(1.0));
}

TEST_CASE("every triangle knows its three edges, also the triangles of a non-manifold edge", "[mesh]") {
  Mesh m = fromTriangles({{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, -1, 0}},
                         {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  buildAdjacency(m);
  REQUIRE(m.triangleEdges.size() == 3);
  for (uint32_t t = 0; t < 3; ++t)
    for (int i = 0; i < 3; ++i) {
      // The edge stands for the unordered pair of the triangle's corners i and i + 1.
      const Edge& e = m.edges.at(m.triangleEdges[t][i]);
      const uint32_t a = m.weldedTriangles[t][i], b = m.weldedTriangles[t][(i + 1) % 3];
      CHECK(((e.v0 == a && e.v1 == b) || (e.v0 == b && e.v1 == a)));
    }
  // The shared edge 0-1 is one Edge for all three fins.
  CHECK(m.triangleEdges[0][0] == m.triangleEdges[1][0]);
  CHECK(m.triangleEdges[0][0] == m.triangleEdges[2][0]);
}

TEST_CASE("a closed mesh wound clockwise seen from outside is inside out: it encloses a negative volume",
          "[mesh]") {
  Mesh m = tetrahedron();
  for (glm::uvec3& t : m.triangles) std::swap(t.y, t.z);
  buildAdjacency(m);
  CHECK(m.topology == Topology::Closed);
  CHECK(m.inconsistentEdges == 0);
  CHECK(m.enclosedVolume == Approx(-1.0 / 6.0));  // the tetrahedron's 1/6, negated
  CHECK(m.insideOut);
  Mesh outward = tetrahedron();
  buildAdjacency(outward);
  CHECK(outward.enclosedVolume == Approx(1.0 / 6.0));
  CHECK_FALSE(outward.insideOut);
}

TEST_CASE("neither an open nor an inconsistently wound mesh, nor a closed one enclosing nothing, is inside out",
          "[mesh]") {
  Mesh open = tetrahedron();
  open.triangles.pop_back();
  for (glm::uvec3& t : open.triangles) std::swap(t.y, t.z);
  buildAdjacency(open);
  CHECK_FALSE(open.insideOut);  // "inside" needs a closed surface

  Mesh mixed = tetrahedron();
  std::swap(mixed.triangles[3].y, mixed.triangles[3].z);
  std::swap(mixed.triangles[2].y, mixed.triangles[2].z);
  std::swap(mixed.triangles[1].y, mixed.triangles[1].z);  // three of four reversed: volume < 0
  buildAdjacency(mixed);
  CHECK(mixed.inconsistentEdges > 0);
  CHECK_FALSE(mixed.insideOut);

  // A triangle and its reverse, back to back: closed and consistent, enclosing nothing.
  Mesh sheet = fromTriangles({{0.1, 0.2, 0.3}, {1.1, 0.2, 0.3}, {1.1, 1.7, 0.9}}, {{0, 1, 2}, {0, 2, 1}});
  buildAdjacency(sheet);
  CHECK(sheet.topology == Topology::Closed);
  CHECK(sheet.inconsistentEdges == 0);
  CHECK_FALSE(sheet.insideOut);
}

TEST_CASE("a box's eight corners: bit 0 of the index picks max.x, bit 1 max.y, bit 2 max.z", "[mesh]") {
  const Aabb box{{-1.0, 2.0, 3.0}, {4.0, 5.0, 7.5}};
  const std::array<glm::dvec3, 8> c = box.corners();
  CHECK(c[0] == glm::dvec3(-1.0, 2.0, 3.0));
  CHECK(c[1] == glm::dvec3(4.0, 2.0, 3.0));
  CHECK(c[2] == glm::dvec3(-1.0, 5.0, 3.0));
  CHECK(c[3] == glm::dvec3(4.0, 5.0, 3.0));
  CHECK(c[4] == glm::dvec3(-1.0, 2.0, 7.5));
  CHECK(c[7] == glm::dvec3(4.0, 5.0, 7.5));
  // Every corner lies in the box, and together they span it.
  Aabb spanned;
  for (const glm::dvec3& p : c) spanned.add(p);
  CHECK(spanned.min == box.min);
  CHECK(spanned.max == box.max);
}

namespace {

// The boxes (min, max, wound outwards?) as one mesh, adjacency built.
Mesh boxes(std::vector<std::tuple<glm::dvec3, glm::dvec3, bool>> list) {
  Mesh all;
  all.name = "boxes";
  for (const auto& [lo, hi, outward] : list) {
    const Mesh b = makeBoxBetween(lo, hi);
    const uint32_t base = uint32_t(all.positions.size());
    all.positions.insert(all.positions.end(), b.positions.begin(), b.positions.end());
    all.normals.insert(all.normals.end(), b.normals.begin(), b.normals.end());
    for (const glm::uvec3& t : b.triangles)
      all.triangles.push_back(outward ? t + glm::uvec3(base) : glm::uvec3(t.x, t.z, t.y) + glm::uvec3(base));
  }
  buildAdjacency(all);
  return all;
}

}  // namespace

TEST_CASE("closed parts: an inside-out part beside an outward one is mixed winding, a cavity is not", "[mesh]") {
  // Two outward boxes: two parts, neither inside out.
  const Mesh two = boxes({{{0, 0, 0}, {1, 1, 1}, true}, {{2, 0, 0}, {3, 1, 1}, true}});
  CHECK(closedPartWinding(two).parts == 2);
  CHECK(closedPartWinding(two).insideOut == 0);
  CHECK_FALSE(two.mixedWinding);
  // A 2 m box and, beside it, a unit box wound inside out: 8 − 1 = 7 m³, positive, yet one part
  // is inside out.
  const Mesh mixed = boxes({{{0, 0, 0}, {2, 2, 2}, true}, {{3, 0, 0}, {4, 1, 1}, false}});
  CHECK(mixed.enclosedVolume == Approx(7.0));
  CHECK(closedPartWinding(mixed).parts == 2);
  CHECK(closedPartWinding(mixed).insideOut == 1);
  CHECK(mixed.mixedWinding);
  CHECK_FALSE(mixed.insideOut);
  // The same the other way round (total −8 + 1): still mixed, not inside out as a whole.
  const Mesh mostlyInsideOut = boxes({{{0, 0, 0}, {2, 2, 2}, false}, {{3, 0, 0}, {4, 1, 1}, true}});
  CHECK(mostlyInsideOut.mixedWinding);
  CHECK_FALSE(mostlyInsideOut.insideOut);
  // A hollow box: the inner surface wound inwards is a cavity (inside the outer part), its
  // negative volume right: 8 − 1 = 7 m³, not mixed.
  const Mesh hollow = boxes({{{0, 0, 0}, {2, 2, 2}, true}, {{0.5, 0.5, 0.5}, {1.5, 1.5, 1.5}, false}});
  CHECK(hollow.enclosedVolume == Approx(7.0));
  CHECK(closedPartWinding(hollow).insideOut == 0);
  CHECK_FALSE(hollow.mixedWinding);
  // One box wound inside out is inside out as a whole, not mixed.
  const Mesh reversed = boxes({{{0, 0, 0}, {1, 1, 1}, false}});
  CHECK(closedPartWinding(reversed).insideOut == 1);
  CHECK(reversed.insideOut);
  CHECK_FALSE(reversed.mixedWinding);
}
