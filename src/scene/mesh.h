// A triangle mesh as the renderer and the shadow algorithms see it.
//
// Two views of the same triangles, index for index:
//  - the render view: vertices with their own normals (split at seams and creases), for shading;
//  - the welded view: one vertex per distinct position, for adjacency ([Kuhn 2016, §4.3.5]).
//    Welding is by exact position, so a welded vertex has bit-for-bit the coordinates of the render
//    vertices it stands for, and the shadow-volume front cap transforms exactly as the scene pass
//    did.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace shadowref {

struct Aabb {
  glm::dvec3 min{std::numeric_limits<double>::infinity()};
  glm::dvec3 max{-std::numeric_limits<double>::infinity()};
  bool empty() const { return min.x > max.x; }
  void add(const glm::dvec3& p) { min = glm::min(min, p); max = glm::max(max, p); }
  glm::dvec3 center() const { return (min + max) * 0.5; }
  // The eight corners; bit 0 of the index picks max.x, bit 1 max.y, bit 2 max.z.
  std::array<glm::dvec3, 8> corners() const {
    std::array<glm::dvec3, 8> c;
    for (size_t i = 0; i < 8; ++i)
      c[i] = {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z};
    return c;
  }
};

inline constexpr uint32_t kNoTriangle = std::numeric_limits<uint32_t>::max();

// An edge of the welded mesh with the triangles on either side ([Kuhn 2016, §4.3.5]).
// v0 -> v1 is the direction in which the edge runs in triangle t0 (counter-clockwise);
// a consistently wound neighbour t1 runs it v1 -> v0. t1 == kNoTriangle for an open edge.
struct Edge {
  uint32_t v0 = 0, v1 = 0;
  uint32_t t0 = kNoTriangle, t1 = kNoTriangle;
  uint32_t triangleCount = 0;  // 1 open, 2 manifold, >= 3 non-manifold
};

enum class Topology : uint8_t { Closed, Open, NonManifold };

struct Mesh {
  std::string name;

  // Render view.
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec3> normals;       // one per render vertex, unit length
  std::vector<glm::uvec3> triangles;     // counter-clockwise seen from outside

  // Welded view (built by buildAdjacency in adjacency.h).
  std::vector<glm::dvec3> weldedPositions;
  std::vector<glm::uvec3> weldedTriangles;  // weldedTriangles[i] is triangles[i], welded
  std::vector<uint32_t> weldIndex;          // render vertex -> welded vertex
  std::vector<Edge> edges;
  // triangleEdges[t][i]: the index in `edges` of triangle t's edge from corner i to corner i + 1.
  // Every triangle on a non-manifold edge points at the one Edge that stands for it.
  std::vector<glm::uvec3> triangleEdges;
  std::vector<glm::dvec3> faceNormals;      // unit, one per triangle, from the welded positions
  Topology topology = Topology::Closed;
  size_t openEdges = 0, nonManifoldEdges = 0;
  // Manifold edges whose two triangles run them the same way: a neighbour wound the other way
  // round, so inside and outside disagree (counted by buildAdjacency; 0 for a proper mesh).
  size_t inconsistentEdges = 0;
  // The signed volume the welded triangles enclose (adjacency.h, signedVolume): positive when a
  // closed mesh is wound counter-clockwise seen from outside. Meaningful for closed meshes only.
  double enclosedVolume = 0.0;
  // Closed, consistently wound, and enclosing a clearly negative volume: every triangle is wound
  // clockwise seen from outside, so its face normals point inwards.
  bool insideOut = false;
  // Closed and consistently wound, but its closed parts disagree: some are inside out (a part
  // enclosing a negative volume and lying inside no other part; a cavity, inside another part,
  // rightly encloses a negative one) and some are not, whatever the sign of the total
  // (adjacency.h, closedPartWinding). insideOut is then false.
  bool mixedWinding = false;

  Aabb bounds;  // object space
};

// The triangles as one flat index list, three per triangle, as draw calls take them, read in
// place: a glm::uvec3 is three uint32_t without padding (glm::value_ptr's view of a vector).
inline std::span<const uint32_t> triangleIndices(const Mesh& mesh) {
  static_assert(sizeof(glm::uvec3) == 3 * sizeof(uint32_t));
  if (mesh.triangles.empty()) return {};
  return {glm::value_ptr(mesh.triangles.front()), 3 * mesh.triangles.size()};
}

}  // namespace shadowref
