// Invariants every closed mesh must satisfy, shared by the [mesh] tests.
#pragma once

#include <numeric>
#include <set>
#include <vector>

#include <catch2/catch.hpp>

#include "scene/adjacency.h"
#include "scene/mesh.h"

namespace shadowref::testing {

// Welded vertices that some triangle uses (degenerate drops may leave others behind).
inline size_t usedVertexCount(const Mesh& m) {
  std::set<uint32_t> used;
  for (const glm::uvec3& t : m.weldedTriangles) used.insert({t.x, t.y, t.z});
  return used.size();
}

// V - E + F over the welded view.
inline long eulerCharacteristic(const Mesh& m) {
  return static_cast<long>(usedVertexCount(m)) - static_cast<long>(m.edges.size()) +
         static_cast<long>(m.weldedTriangles.size());
}

// Connected parts (triangles joined through shared welded vertices).
inline size_t componentCount(const Mesh& m) {
  std::vector<uint32_t> parent(m.weldedPositions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const glm::uvec3& t : m.weldedTriangles) {
    parent[find(t.y)] = find(t.x);
    parent[find(t.z)] = find(t.x);
  }
  std::set<uint32_t> roots;
  for (const glm::uvec3& t : m.weldedTriangles) roots.insert(find(t.x));
  return roots.size();
}

// Closed 2-manifold, consistently wound, enclosing positive volume (outward winding), with
// V - E + F = 2 * parts - 2 * genus.
inline void requireClosedOutward(const Mesh& m, int genus = 0) {
  INFO("mesh " << m.name);
  REQUIRE(!m.weldedTriangles.empty());
  REQUIRE(m.topology == Topology::Closed);
  REQUIRE(m.openEdges == 0);
  REQUIRE(m.nonManifoldEdges == 0);
  REQUIRE(m.inconsistentEdges == 0);
  for (const Edge& e : m.edges) REQUIRE(e.triangleCount == 2);
  // Each edge runs v1 -> v0 in its second triangle: the two windings agree.
  for (const Edge& e : m.edges) {
    const glm::uvec3 t = m.weldedTriangles[e.t1];
    bool reversed = false;
    for (int i = 0; i < 3; ++i) reversed |= (t[i] == e.v1 && t[(i + 1) % 3] == e.v0);
    REQUIRE(reversed);
  }
  REQUIRE(2 * static_cast<long>(m.edges.size()) == 3 * static_cast<long>(m.weldedTriangles.size()));
  REQUIRE(eulerCharacteristic(m) == 2 * static_cast<long>(componentCount(m)) - 2 * genus);
  REQUIRE(signedVolume(m) > 0.0);
}

// Render normals agree with the winding: every corner's normal lies on the outer side of its face.
inline void requireNormalsAgreeWithWinding(const Mesh& m) {
  INFO("mesh " << m.name);
  REQUIRE(m.normals.size() == m.positions.size());
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) REQUIRE(glm::dot(m.normals[m.triangles[t][i]], m.faceNormals[t]) > 0.0);
}

}  // namespace shadowref::testing
