// Shared helpers of the shadow-volume tests: meshes under seeded random rotations, random lights,
// edge sets in a comparable form, and the closedness / orientation invariants.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/adjacency.h"
#include "scene/mesh.h"
#include "scene/primitives.h"
#include "shadow/shadow_volume.h"
#include "shadow/silhouette.h"

namespace shadowref::testing {

// The closed test meshes of the silhouette tests.
inline std::vector<Mesh> closedTestMeshes() {
  std::vector<Mesh> meshes;
  meshes.push_back(makeBox({2.0, 1.0, 3.0}));
  meshes.push_back(makeSphere(1.0, 16, 10));
  meshes.push_back(makeTorus(1.0, 0.35, 20, 10));
  meshes.push_back(makeCylinder(0.8, 2.0, 14));
  meshes.push_back(makeCone(1.0, 1.5, 12));
  return meshes;
}

// A rotation about a uniformly random axis by a random angle.
inline glm::dmat4 randomRotation(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  glm::dvec3 axis;
  do axis = {u(rng), u(rng), u(rng)};
  while (glm::length(axis) < 0.1 || glm::length(axis) > 1.0);
  return glm::rotate(glm::dmat4(1.0), 3.14159265358979 * u(rng), glm::normalize(axis));
}

// The mesh with every render position and normal transformed, adjacency rebuilt.
inline Mesh transformed(const Mesh& m, const glm::dmat4& rotation) {
  Mesh r;
  r.name = m.name;
  r.triangles = m.triangles;
  for (const glm::dvec3& p : m.positions) r.positions.push_back(glm::dvec3(rotation * glm::dvec4(p, 1.0)));
  for (const glm::dvec3& n : m.normals) r.normals.push_back(glm::dvec3(rotation * glm::dvec4(n, 0.0)));
  buildAdjacency(r);
  return r;
}

// A point light at distance 2 .. 8 from the origin, or a directional light.
inline glm::dvec4 randomLight(std::mt19937_64& rng, bool directional) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), distance(2.0, 8.0);
  glm::dvec3 d;
  do d = {u(rng), u(rng), u(rng)};
  while (glm::length(d) < 0.1 || glm::length(d) > 1.0);
  d = glm::normalize(d);
  return directional ? glm::dvec4(d, 0.0) : glm::dvec4(d * distance(rng), 1.0);
}

using EdgeKey = std::tuple<uint32_t, uint32_t, uint32_t>;  // a, b, facing triangle

inline std::vector<EdgeKey> sortedEdges(const std::vector<SilhouetteEdge>& edges) {
  std::vector<EdgeKey> keys;
  for (const SilhouetteEdge& e : edges) keys.emplace_back(e.a, e.b, e.facingTriangle);
  std::sort(keys.begin(), keys.end());
  return keys;
}

// Every triangle list together; directed edge i -> j counted.
inline std::map<std::pair<uint32_t, uint32_t>, int> directedEdgeCounts(
    const std::vector<const std::vector<glm::uvec3>*>& parts) {
  std::map<std::pair<uint32_t, uint32_t>, int> count;
  for (const auto* part : parts)
    for (const glm::uvec3& t : *part)
      for (int i = 0; i < 3; ++i) ++count[{t[i], t[(i + 1) % 3]}];
  return count;
}

// Closed 2-manifold with consistent orientation: every directed edge once, its reverse once.
inline bool everyEdgeOnceEachWay(const std::map<std::pair<uint32_t, uint32_t>, int>& count) {
  for (const auto& [edge, n] : count) {
    if (n != 1) return false;
    auto reverse = count.find({edge.second, edge.first});
    if (reverse == count.end() || reverse->second != 1) return false;
  }
  return true;
}

// A finite stand-in for a point light's volume: each point at infinity V∞ = (V − L, 0) replaced by
// V + reach · (V − L), so the back cap becomes the averted triangles scaled about the light.
inline glm::dvec3 finitePoint(const ShadowVolume& v, uint32_t index, double reach) {
  const glm::dvec4 p = v.positions[index];
  if (p.w != 0.0) return glm::dvec3(p) / p.w;
  const uint32_t source = index - v.infinite.base;  // point light: one per vertex
  return glm::dvec3(v.positions[source]) + reach * glm::dvec3(p);
}

// Signed volume (divergence theorem) of the volume truncated at `reach`.
inline double truncatedSignedVolume(const ShadowVolume& v, double reach) {
  double sixTimes = 0.0;
  for (const auto* part : {&v.sides, &v.frontCap, &v.backCap})
    for (const glm::uvec3& t : *part) {
      const glm::dvec3 a = finitePoint(v, t.x, reach), b = finitePoint(v, t.y, reach),
                       c = finitePoint(v, t.z, reach);
      sixTimes += glm::dot(a, glm::cross(b, c));
    }
  return sixTimes / 6.0;
}

}  // namespace shadowref::testing
