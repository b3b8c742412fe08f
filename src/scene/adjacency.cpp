#include "scene/adjacency.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>
#include <unordered_map>
#include <utility>

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
  mesh.triangleEdges.resize(mesh.weldedTriangles.size());
  for (uint32_t t = 0; t < mesh.weldedTriangles.size(); ++t) {
    const glm::uvec3 tri = mesh.weldedTriangles[t];
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = tri[i], b = tri[(i + 1) % 3];
      const uint64_t key = (uint64_t{std::min(a, b)} << 32) | std::max(a, b);
      auto [it, inserted] = edgeOf.try_emplace(key, static_cast<uint32_t>(mesh.edges.size()));
      mesh.triangleEdges[t][i] = it->second;
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

// The enclosed volume and whether a closed, consistently wound mesh is inside out. The sign is
// trusted only when the sum is clearly away from 0 relative to the sum of the magnitudes of its
// terms: a closed surface enclosing nothing (a quad and its reverse, back to back) sums to a few
// rounding errors of either sign and is not inside out.
void classifyWinding(Mesh& mesh) {
  double sixTimes = 0.0, magnitude = 0.0;
  for (const glm::uvec3& w : mesh.weldedTriangles) {
    const double term = glm::dot(mesh.weldedPositions[w.x], glm::cross(mesh.weldedPositions[w.y], mesh.weldedPositions[w.z]));
    sixTimes += term;
    magnitude += std::abs(term);
  }
  mesh.enclosedVolume = sixTimes / 6.0;
  mesh.mixedWinding = false;
  mesh.insideOut = mesh.topology == Topology::Closed && mesh.inconsistentEdges == 0 && sixTimes < -1e-9 * magnitude;
  if (mesh.topology != Topology::Closed || mesh.inconsistentEdges != 0) return;
  const ClosedPartWinding parts = closedPartWinding(mesh);
  if (parts.insideOut > 0 && parts.insideOut < parts.parts) {
    mesh.mixedWinding = true;
    mesh.insideOut = false;
  }
}

// Union-find over triangles, with path halving.
uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t t) {
  while (parent[t] != t) t = parent[t] = parent[parent[t]];
  return t;
}

// The solid angle of triangle abc seen from the origin, signed by its winding
// ([Van Oosterom & Strackee 1983]).
double solidAngle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double numerator = glm::dot(a, glm::cross(b, c));
  const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  return 2.0 * std::atan2(numerator, denominator);
}

}  // namespace

void buildAdjacency(Mesh& mesh, std::vector<std::string>* warnings) {
  mesh.weldedPositions.clear();
  mesh.weldedTriangles.clear();
  mesh.weldIndex.clear();
  mesh.edges.clear();
  mesh.triangleEdges.clear();
  mesh.faceNormals.clear();
  mesh.openEdges = mesh.nonManifoldEdges = mesh.inconsistentEdges = 0;
  mesh.bounds = Aabb{};

  weld(mesh);
  dropDegenerate(mesh, warnings);
  buildEdges(mesh);
  classify(mesh);
  classifyWinding(mesh);

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

namespace {

// The bits of a vector exactly as they are (-0.0 and +0.0 apart): two triangles whose unit normals
// have the same key get bit-identical crease sums.
PositionKey rawKeyOf(const glm::dvec3& v) {
  PositionKey k{};
  std::memcpy(k.bits, &v, sizeof k.bits);
  return k;
}

// The octahedral direction bin (about 15 degrees wide) of a unit vector, for the binned sums.
constexpr int kDirectionBins = 12;
int directionBin(const glm::dvec3& u) {
  const double l1 = std::abs(u.x) + std::abs(u.y) + std::abs(u.z);
  if (!(l1 > 0.0)) return kDirectionBins * kDirectionBins;  // the zero normal of a degenerate triangle
  double x = u.x / l1, y = u.y / l1;
  if (u.z < 0.0) {
    const double fx = (1.0 - std::abs(y)) * (x < 0.0 ? -1.0 : 1.0), fy = (1.0 - std::abs(x)) * (y < 0.0 ? -1.0 : 1.0);
    x = fx, y = fy;
  }
  auto cell = [](double c) { return std::clamp(static_cast<int>((c * 0.5 + 0.5) * kDirectionBins), 0, kDirectionBins - 1); };
  return cell(x) * kDirectionBins + cell(y);
}

}  // namespace

void computeCreaseNormals(Mesh& mesh, double creaseDegrees) {
  const double cosCrease = std::cos(glm::radians(creaseDegrees));
  const size_t triangleCount = mesh.triangles.size();
  std::vector<glm::dvec3> area(triangleCount), unit(triangleCount);
  // Corners grouped by position, each group's corners in triangle order (counting sort: linear).
  std::unordered_map<PositionKey, uint32_t, PositionKeyHash> positionId;
  std::vector<uint32_t> cornerGroup(3 * triangleCount), groupStart;
  for (size_t t = 0; t < triangleCount; ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    area[t] = areaVector(mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z]);
    unit[t] = glm::length(area[t]) > 0.0 ? glm::normalize(area[t]) : glm::dvec3(0.0);
    for (int i = 0; i < 3; ++i) {
      auto [it, inserted] =
          positionId.try_emplace(keyOf(mesh.positions[tri[i]]), static_cast<uint32_t>(groupStart.size()));
      if (inserted) groupStart.push_back(0);
      ++groupStart[it->second];
      cornerGroup[3 * t + i] = it->second;
    }
  }
  positionId = {};
  uint32_t running = 0;
  for (uint32_t& start : groupStart) running += std::exchange(start, running);
  groupStart.push_back(running);
  std::vector<uint32_t> members(3 * triangleCount), fill(groupStart.begin(), groupStart.end() - 1);
  for (uint32_t c = 0; c < 3 * triangleCount; ++c) members[fill[cornerGroup[c]]++] = c;
  fill = {};
  cornerGroup = {};

  // The normal of a corner of triangle t depends only on its group and on unit[t]: the sum of
  // area[u] over the group's triangles u with dot(unit[u], unit[t]) >= cos(crease), in triangle
  // order. It is computed once per distinct unit normal in the group. When that exact rule would
  // cost more than kExactWork steps for one group (a cone's apex with a million sides), the group's
  // triangles are summed per direction bin instead, and each bin takes the bins whose mean normals
  // lie within the crease angle of its own: bounded work, smooth where the exact rule is smooth.
  constexpr uint64_t kExactWork = uint64_t{1} << 20;
  constexpr size_t kExactDistinct = 16;
  std::vector<glm::dvec3> cornerNormal(3 * triangleCount);
  std::vector<uint32_t> slotOfMember;
  std::vector<glm::dvec3> slotUnit, slotSum;
  for (size_t g = 0; g + 1 < groupStart.size(); ++g) {
    const std::span<const uint32_t> group(members.data() + groupStart[g], groupStart[g + 1] - groupStart[g]);
    slotUnit.clear();
    slotOfMember.resize(group.size());
    // Distinct unit normals in order of first appearance: a short scan for the usual handful of
    // corners, a map of the group's own size beyond (clearing one map shared by all groups would
    // cost its largest bucket count for every group).
    constexpr size_t kScan = 32;
    std::unordered_map<PositionKey, uint32_t, PositionKeyHash> slotOf;
    for (size_t j = 0; j < group.size(); ++j) {
      const glm::dvec3& u = unit[group[j] / 3];
      const PositionKey key = rawKeyOf(u);
      uint32_t slot = static_cast<uint32_t>(slotUnit.size());
      if (group.size() <= kScan) {
        for (uint32_t s = 0; s < slotUnit.size(); ++s)
          if (rawKeyOf(slotUnit[s]) == key) slot = s;
      } else {
        slot = slotOf.try_emplace(key, slot).first->second;
      }
      if (slot == slotUnit.size()) slotUnit.push_back(u);
      slotOfMember[j] = slot;
    }
    slotSum.assign(slotUnit.size(), glm::dvec3(0.0));
    if (slotUnit.size() <= kExactDistinct || uint64_t{group.size()} * slotUnit.size() <= kExactWork) {
      for (size_t s = 0; s < slotUnit.size(); ++s)
        for (uint32_t c : group)
          if (glm::dot(unit[c / 3], slotUnit[s]) >= cosCrease) slotSum[s] += area[c / 3];
    } else {
      constexpr int kBins = kDirectionBins * kDirectionBins + 1;
      std::vector<glm::dvec3> binArea(kBins, glm::dvec3(0.0)), binMean(kBins, glm::dvec3(0.0)),
          binSum(kBins, glm::dvec3(0.0));
      std::vector<bool> used(kBins, false);
      for (uint32_t c : group) {
        const int b = directionBin(unit[c / 3]);
        binArea[b] += area[c / 3];
        if (!used[b]) binMean[b] = unit[c / 3];
        used[b] = true;
      }
      for (int b = 0; b < kBins; ++b)
        if (glm::length(binArea[b]) > 0.0) binMean[b] = glm::normalize(binArea[b]);
      for (int b = 0; b < kBins; ++b)
        for (int o = 0; o < kBins; ++o)
          if (used[b] && used[o] && glm::dot(binMean[o], binMean[b]) >= cosCrease) binSum[b] += binArea[o];
      for (size_t s = 0; s < slotUnit.size(); ++s) slotSum[s] = binSum[directionBin(slotUnit[s])];
    }
    for (glm::dvec3& n : slotSum) n = glm::length(n) > 0.0 ? glm::normalize(n) : glm::dvec3(0.0, 1.0, 0.0);
    for (size_t j = 0; j < group.size(); ++j) cornerNormal[group[j]] = slotSum[slotOfMember[j]];
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
      const glm::dvec3 n = cornerNormal[3 * t + i];
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

ClosedPartWinding closedPartWinding(const Mesh& mesh) {
  ClosedPartWinding result;
  const size_t count = mesh.weldedTriangles.size();
  if (count == 0) return result;
  std::vector<uint32_t> parent(count);
  for (uint32_t t = 0; t < count; ++t) parent[t] = t;
  for (const Edge& e : mesh.edges)
    if (e.t0 != kNoTriangle && e.t1 != kNoTriangle) parent[findRoot(parent, e.t0)] = findRoot(parent, e.t1);
  // Per part (indexed by its root): six times its signed volume and the sum of the terms' sizes.
  std::vector<uint32_t> part(count), index(count, kNoTriangle);  // index: root -> part
  std::vector<double> sixTimes, magnitude;
  std::vector<uint32_t> first;
  const auto& P = mesh.weldedPositions;
  for (uint32_t t = 0; t < count; ++t) {
    uint32_t& p = index[findRoot(parent, t)];
    if (p == kNoTriangle) {
      p = uint32_t(sixTimes.size());
      sixTimes.push_back(0.0), magnitude.push_back(0.0), first.push_back(t);
    }
    part[t] = p;
    const glm::uvec3 w = mesh.weldedTriangles[t];
    const double term = glm::dot(P[w.x], glm::cross(P[w.y], P[w.z]));
    sixTimes[part[t]] += term;
    magnitude[part[t]] += std::abs(term);
  }
  result.parts = sixTimes.size();
  size_t tested = 0;
  for (uint32_t p = 0; p < result.parts; ++p) {
    if (!(sixTimes[p] < -1e-9 * magnitude[p])) continue;
    if (tested++ >= kMaxEnclosureTests) {  // the rest are counted inside out, unseen
      result.insideOut += 1;
      continue;
    }
    const glm::uvec3 w = mesh.weldedTriangles[first[p]];
    const glm::dvec3 x = (P[w.x] + P[w.y] + P[w.z]) / 3.0;
    std::vector<double> angle(result.parts, 0.0);  // 4π · each other part's winding number at x
    for (uint32_t t = 0; t < count; ++t) {
      if (part[t] == p) continue;
      const glm::uvec3 v = mesh.weldedTriangles[t];
      angle[part[t]] += solidAngle(P[v.x] - x, P[v.y] - x, P[v.z] - x);
    }
    size_t enclosing = 0;
    for (const double a : angle) enclosing += std::abs(a) > 2.0 * M_PI;
    result.insideOut += enclosing % 2 == 0;
  }
  return result;
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
