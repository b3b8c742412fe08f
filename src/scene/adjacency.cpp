#include "scene/adjacency.h"

#include <cmath>
#include <cstring>
#include <unordered_map>

namespace shadowref {

namespace {

// The bit pattern of a position, with -0.0 turned into +0.0 so the two zeros weld.
struct PositionKey {
  uint64_t bits[3];
  bool operator==(const PositionKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};

PositionKey keyOf(const glm::dvec3& p) {
  PositionKey k{};
  for (int i = 0; i < 3; ++i) {
    double c = p[i] == 0.0 ? 0.0 : p[i];
    std::memcpy(&k.bits[i], &c, sizeof c);
  }
  return k;
}

struct PositionKeyHash {
  size_t operator()(const PositionKey& k) const {
    uint64_t h = 1469598103934665603ull;
    for (uint64_t b : k.bits) h = (h ^ b) * 1099511628211ull ^ (h >> 29);
    return static_cast<size_t>(h);
  }
};

// Welds by exact position. The map is only looked up, never iterated, so the welded order is the
// order of first appearance among the render vertices: deterministic.
void weld(Mesh& mesh) {
  std::unordered_map<PositionKey, uint32_t, PositionKeyHash> index;
  index.reserve(mesh.positions.size());
  mesh.weldIndex.resize(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    auto [it, inserted] =
        index.try_emplace(keyOf(mesh.positions[i]), static_cast<uint32_t>(mesh.weldedPositions.size()));
    if (inserted) {
      glm::dvec3 p = mesh.positions[i];
      for (int c = 0; c < 3; ++c)
        if (p[c] == 0.0) p[c] = 0.0;
      mesh.weldedPositions.push_back(p);
    }
    mesh.weldIndex[i] = it->second;
  }
}

glm::dvec3 areaVector(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return glm::cross(b - a, c - a);
}

// Drops triangles that have no area in the welded view, from both views alike.
void dropDegenerate(Mesh& mesh, std::vector<std::string>* warnings) {
  size_t kept = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3 r = mesh.triangles[t];
    const glm::uvec3 w(mesh.weldIndex[r.x], mesh.weldIndex[r.y], mesh.weldIndex[r.z]);
    const auto& P = mesh.weldedPositions;
    const bool repeated = w.x == w.y || w.y == w.z || w.z == w.x;
    const bool flat = !repeated && areaVector(P[w.x], P[w.y], P[w.z]) == glm::dvec3(0.0);
    if (repeated || flat) {
      if (warnings)
        warnings->push_back((mesh.name.empty() ? std::string("mesh") : mesh.name) + ": triangle " +
                            std::to_string(t) + " is degenerate (" +
                            (repeated ? "two corners at the same position" : "zero area") +
                            "), dropped");
      continue;
    }
    mesh.triangles[kept] = r;
    mesh.weldedTriangles.push_back(w);
    ++kept;
  }
  mesh.triangles.resize(kept);
}

// [Kuhn 2016, §4.3.5, Algorithm 1] "createEdgeList", with the list search replaced by a hash map
// keyed by the unordered vertex pair: O(n) instead of O(n²).
void buildEdges(Mesh& mesh) {
  std::unordered_map<uint64_t, uint32_t> edgeOf;
  edgeOf.reserve(mesh.weldedTriangles.size() * 2);
  for (uint32_t t = 0; t < mesh.weldedTriangles.size(); ++t) {
    const glm::uvec3 tri = mesh.weldedTriangles[t];
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = tri[i], b = tri[(i + 1) % 3];
      const uint64_t key = (uint64_t{std::min(a, b)} << 32) | std::max(a, b);
      auto [it, inserted] = edgeOf.try_emplace(key, static_cast<uint32_t>(mesh.edges.size()));
      if (inserted) {
        mesh.edges.push_back(Edge{a, b, t, kNoTriangle, 1});
        continue;
      }
      Edge& e = mesh.edges[it->second];
      if (++e.triangleCount == 2) {
        e.t1 = t;
        if (e.v0 == a) ++mesh.inconsistentEdges;  // the neighbour runs it the same way
      }
    }
  }
}

void classify(Mesh& mesh) {
  for (const Edge& e : mesh.edges) {
    if (e.triangleCount == 1) ++mesh.openEdges;
    if (e.triangleCount >= 3) ++mesh.nonManifoldEdges;
  }
  mesh.topology = mesh.nonManifoldEdges ? Topology::NonManifold
                  : mesh.openEdges      ? Topology::Open
                                        : Topology::Closed;
}

}  // namespace

void buildAdjacency(Mesh& mesh, std::vector<std::string>* warnings) {
  mesh.weldedPositions.clear();
  mesh.weldedTriangles.clear();
  mesh.weldIndex.clear();
  mesh.edges.clear();
  mesh.faceNormals.clear();
  mesh.openEdges = mesh.nonManifoldEdges = mesh.inconsistentEdges = 0;
  mesh.bounds = Aabb{};

  weld(mesh);
  dropDegenerate(mesh, warnings);
  buildEdges(mesh);
  classify(mesh);

  const auto& P = mesh.weldedPositions;
  mesh.faceNormals.reserve(mesh.weldedTriangles.size());
  for (const glm::uvec3& w : mesh.weldedTriangles)
    mesh.faceNormals.push_back(glm::normalize(areaVector(P[w.x], P[w.y], P[w.z])));
  for (const glm::uvec3& w : mesh.weldedTriangles)
    for (int i = 0; i < 3; ++i) mesh.bounds.add(P[w[i]]);  // only what the triangles use
}

void computeFlatNormals(Mesh& mesh) {
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec3> normals;
  positions.reserve(mesh.triangles.size() * 3);
  normals.reserve(mesh.triangles.size() * 3);
  for (glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
    glm::dvec3 n = areaVector(a, b, c);
    n = glm::length(n) > 0.0 ? glm::normalize(n) : glm::dvec3(0.0, 1.0, 0.0);
    const uint32_t base = static_cast<uint32_t>(positions.size());
    for (const glm::dvec3& p : {a, b, c}) {
      positions.push_back(p);
      normals.push_back(n);
    }
    t = glm::uvec3(base, base + 1, base + 2);
  }
  mesh.positions = std::move(positions);
  mesh.normals = std::move(normals);
}

void computeSmoothNormals(Mesh& mesh) {
  std::unordered_map<PositionKey, glm::dvec3, PositionKeyHash> sum;
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 n =
        areaVector(mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]);
    for (int i = 0; i < 3; ++i) sum[keyOf(mesh.positions[t[i]])] += n;
  }
  mesh.normals.assign(mesh.positions.size(), glm::dvec3(0.0, 1.0, 0.0));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    auto it = sum.find(keyOf(mesh.positions[i]));
    if (it != sum.end() && glm::length(it->second) > 0.0) mesh.normals[i] = glm::normalize(it->second);
  }
}

void computeCreaseNormals(Mesh& mesh, double creaseDegrees) {
  const double cosCrease = std::cos(glm::radians(creaseDegrees));
  const size_t triangleCount = mesh.triangles.size();
  std::vector<glm::dvec3> area(triangleCount), unit(triangleCount);
  // Triangles around each distinct position, in triangle order.
  std::unordered_map<PositionKey, uint32_t, PositionKeyHash> positionId;
  std::vector<std::vector<uint32_t>> around;
  std::vector<glm::uvec3> cornerIds(triangleCount);
  for (size_t t = 0; t < triangleCount; ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    area[t] = areaVector(mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z]);
    unit[t] = glm::length(area[t]) > 0.0 ? glm::normalize(area[t]) : glm::dvec3(0.0);
    for (int i = 0; i < 3; ++i) {
      auto [it, inserted] =
          positionId.try_emplace(keyOf(mesh.positions[tri[i]]), static_cast<uint32_t>(around.size()));
      if (inserted) around.emplace_back();
      around[it->second].push_back(static_cast<uint32_t>(t));
      cornerIds[t][i] = it->second;
    }
  }
  // New render vertices: one per (position, normal) pair, found through a map keyed by both.
  struct VertexKey {
    PositionKey p, n;
    bool operator==(const VertexKey& o) const { return p == o.p && n == o.n; }
  };
  struct VertexKeyHash {
    size_t operator()(const VertexKey& k) const {
      return PositionKeyHash{}(k.p) * 31 ^ PositionKeyHash{}(k.n);
    }
  };
  std::unordered_map<VertexKey, uint32_t, VertexKeyHash> vertexOf;
  std::vector<glm::dvec3> positions, normals;
  for (size_t t = 0; t < triangleCount; ++t) {
    glm::uvec3& tri = mesh.triangles[t];
    glm::uvec3 out;
    for (int i = 0; i < 3; ++i) {
      glm::dvec3 n(0.0);
      for (uint32_t u : around[cornerIds[t][i]])
        if (glm::dot(unit[u], unit[t]) >= cosCrease) n += area[u];
      n = glm::length(n) > 0.0 ? glm::normalize(n) : glm::dvec3(0.0, 1.0, 0.0);
      const glm::dvec3 p = mesh.positions[tri[i]];
      auto [it, inserted] =
          vertexOf.try_emplace(VertexKey{keyOf(p), keyOf(n)}, static_cast<uint32_t>(positions.size()));
      if (inserted) {
        positions.push_back(p);
        normals.push_back(n);
      }
      out[i] = it->second;
    }
    tri = out;
  }
  mesh.positions = std::move(positions);
  mesh.normals = std::move(normals);
}

double signedVolume(const Mesh& mesh) {
  // Sum of signed tetrahedra (origin, a, b, c): the divergence theorem for a closed surface.
  double sixTimes = 0.0;
  for (const glm::uvec3& w : mesh.weldedTriangles) {
    const glm::dvec3 a = mesh.weldedPositions[w.x], b = mesh.weldedPositions[w.y],
                     c = mesh.weldedPositions[w.z];
    sixTimes += glm::dot(a, glm::cross(b, c));
  }
  return sixTimes / 6.0;
}

}  // namespace shadowref
