#include "shadow/silhouette.h"

#include <algorithm>
#include <bit>

namespace shadowref {

namespace {

// The test shared by Kuhn and Lengyel once an edge knows its triangles: silhouette when exactly
// one side faces the light, or when an open edge's only triangle does ([SV slides], [DSS article]).
// The edge is reported as it runs in the facing triangle: v0 -> v1 in t0, v1 -> v0 in t1
// ([Kuhn 2016, §4.3.3] lines 9-15: "if the first triangle faces away, swap A and B").
void testEdge(uint32_t v0, uint32_t v1, uint32_t t0, uint32_t t1, const std::vector<uint8_t>& facing,
              std::vector<SilhouetteEdge>& out) {
  const bool front0 = facing[t0] != 0;
  if (t1 == kNoTriangle) {
    if (front0) out.push_back({v0, v1, t0});
    return;
  }
  const bool front1 = facing[t1] != 0;
  if (front0 == front1) return;
  if (front0)
    out.push_back({v0, v1, t0});
  else
    out.push_back({v1, v0, t1});
}

uint64_t pairKey(uint32_t a, uint32_t b) { return (uint64_t{std::min(a, b)} << 32) | std::max(a, b); }

// Index i of the edge a -> b in triangle `tri` (corner i -> corner i+1), or -1.
int cornerOfEdge(const glm::uvec3& tri, uint32_t a, uint32_t b) {
  for (int i = 0; i < 3; ++i)
    if (tri[i] == a && tri[(i + 1) % 3] == b) return i;
  return -1;
}

}  // namespace

// [Kuhn 2016, §3.5 (last paragraph), §4.3.3]: one pass over the edges, each knowing both triangles.
void kuhnSilhouette(const Mesh& mesh, const std::vector<uint8_t>& facing, std::vector<SilhouetteEdge>& out) {
  out.clear();
  for (const Edge& e : mesh.edges) testEdge(e.v0, e.v1, e.t0, e.t1, facing, out);
}

// [Kuhn 2016, §3.5, Algorithm 1] (Yen Kwoon [Yen Kwoon 2002]): every edge of a light-facing
// triangle is added to the list, or removed when it (or its reverse) is already there. The thesis
// notes the list search makes this slow on large meshes; here the "list" is a hash table keyed by
// the unordered vertex pair plus the order of first insertion, so a toggle costs O(1) and the
// output order is deterministic.
void yenKwoonSilhouette(const Mesh& mesh, const std::vector<uint8_t>& facing, std::vector<SilhouetteEdge>& out,
                        SilhouetteWorkspace& ws) {
  out.clear();
  ws.toggleOrder.clear();
  size_t lit = 0;
  for (uint8_t f : facing) lit += f;
  // 3 edges per lit triangle at most; keep the table at most half full.
  const size_t needed = std::bit_ceil(std::max<size_t>(16, 6 * lit));
  if (ws.toggleSlots.size() < needed || ws.toggleStamp >= 0x7FFFFFFFu) {
    ws.toggleSlots.assign(std::max(needed, ws.toggleSlots.size()), SilhouetteWorkspace::ToggleSlot{});
    ws.toggleStamp = 0;
  }
  const uint32_t stamp = ++ws.toggleStamp;
  const uint32_t absent = stamp * 2, present = stamp * 2 + 1;
  const size_t capacity = ws.toggleSlots.size();
  const int shift = 64 - std::countr_zero(capacity);
  const size_t mask = capacity - 1;

  const auto& tris = mesh.weldedTriangles;
  for (uint32_t t = 0; t < tris.size(); ++t) {
    if (!facing[t]) continue;
    for (int i = 0; i < 3; ++i) {
      const uint64_t key = pairKey(tris[t][i], tris[t][(i + 1) % 3]);
      size_t slot = static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift);
      while (ws.toggleSlots[slot].state / 2 == stamp && ws.toggleSlots[slot].key != key) slot = (slot + 1) & mask;
      SilhouetteWorkspace::ToggleSlot& s = ws.toggleSlots[slot];
      if (s.state / 2 != stamp) {
        s.key = key;
        ws.toggleOrder.push_back(static_cast<uint32_t>(slot));
      } else if (s.state == present) {
        s.state = absent;  // seen twice: an interior edge of the lit region
        continue;
      }
      s.state = present;
      s.triangle = t;
    }
  }
  // The edge as it runs in the triangle that put it in the list.
  for (uint32_t slot : ws.toggleOrder) {
    const SilhouetteWorkspace::ToggleSlot& s = ws.toggleSlots[slot];
    if (s.state != present) continue;
    const uint32_t lo = static_cast<uint32_t>(s.key >> 32), hi = static_cast<uint32_t>(s.key);
    const bool ascending = cornerOfEdge(tris[s.triangle], lo, hi) >= 0;
    out.push_back(ascending ? SilhouetteEdge{lo, hi, s.triangle} : SilhouetteEdge{hi, lo, s.triangle});
  }
}

// [Kuhn 2016, §3.5, Algorithm 2] (Kilgard [Everitt & Kilgard 2002]): every triangle knows its
// neighbours; for each light-facing triangle, an edge whose neighbour does not face the light (or
// that has none) is a silhouette edge. The neighbour table is derived from the edge list
// (O(edges)); Kilgard keeps it with the mesh.
void kilgardSilhouette(const Mesh& mesh, const std::vector<uint8_t>& facing, std::vector<SilhouetteEdge>& out,
                       SilhouetteWorkspace& ws) {
  out.clear();
  const auto& tris = mesh.weldedTriangles;
  ws.neighbours.assign(tris.size(), {kNoTriangle, kNoTriangle, kNoTriangle});
  for (const Edge& e : mesh.edges) {
    if (e.t1 == kNoTriangle) continue;
    const int i0 = cornerOfEdge(tris[e.t0], e.v0, e.v1);
    int i1 = cornerOfEdge(tris[e.t1], e.v1, e.v0);
    if (i1 < 0) i1 = cornerOfEdge(tris[e.t1], e.v0, e.v1);  // inconsistently wound neighbour
    if (i0 >= 0) ws.neighbours[e.t0][i0] = e.t1;
    if (i1 >= 0) ws.neighbours[e.t1][i1] = e.t0;
  }
  for (uint32_t t = 0; t < tris.size(); ++t) {
    if (!facing[t]) continue;
    for (int i = 0; i < 3; ++i) {
      const uint32_t n = ws.neighbours[t][i];
      if (n == kNoTriangle || !facing[n]) out.push_back({tris[t][i], tris[t][(i + 1) % 3], t});
    }
  }
}

// [Kuhn 2016, §3.5] (Lengyel [Lengyel 2002], "The Mechanics of Robust Stencil Shadows"): from the
// triangle list alone. Pass 1 creates an edge for every triangle edge i1 -> i2 with i1 < i2 and
// records its triangle; pass 2 finds, for every triangle edge i1 -> i2 with i1 > i2, the edge i2 ->
// i1 and records the triangle as its neighbour. Per-vertex linked lists keep the search local,
// O(edges) for meshes of bounded vertex degree. An i1 > i2 edge without a partner is an open edge.
// Then the edges are tested as in Kuhn.
void lengyelSilhouette(const Mesh& mesh, const std::vector<uint8_t>& facing, std::vector<SilhouetteEdge>& out,
                       SilhouetteWorkspace& ws) {
  out.clear();
  const auto& tris = mesh.weldedTriangles;
  ws.lengyelEdges.clear();
  ws.firstEdgeOf.assign(mesh.weldedPositions.size(), kNoTriangle);

  for (uint32_t t = 0; t < tris.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const uint32_t i1 = tris[t][i], i2 = tris[t][(i + 1) % 3];
      if (i1 >= i2) continue;
      ws.lengyelEdges.push_back({i1, i2, t, kNoTriangle, ws.firstEdgeOf[i1]});
      ws.firstEdgeOf[i1] = static_cast<uint32_t>(ws.lengyelEdges.size() - 1);
    }
  for (uint32_t t = 0; t < tris.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const uint32_t i1 = tris[t][i], i2 = tris[t][(i + 1) % 3];
      if (i1 <= i2) continue;
      bool matched = false;
      for (uint32_t k = ws.firstEdgeOf[i2]; k != kNoTriangle; k = ws.lengyelEdges[k].next) {
        SilhouetteWorkspace::LengyelEdge& e = ws.lengyelEdges[k];
        if (e.v1 == i1 && e.t1 == kNoTriangle) {
          e.t1 = t;
          matched = true;
          break;
        }
      }
      if (!matched) ws.lengyelEdges.push_back({i1, i2, t, kNoTriangle, kNoTriangle});
    }

  for (const SilhouetteWorkspace::LengyelEdge& e : ws.lengyelEdges) testEdge(e.v0, e.v1, e.t0, e.t1, facing, out);
}

void findSilhouette(const Mesh& mesh, const std::vector<uint8_t>& facing, SilhouetteAlgorithm algorithm,
                    std::vector<SilhouetteEdge>& out, SilhouetteWorkspace* workspace) {
  SilhouetteWorkspace local;
  SilhouetteWorkspace& ws = workspace ? *workspace : local;
  switch (algorithm) {
    case SilhouetteAlgorithm::Kuhn: kuhnSilhouette(mesh, facing, out); return;
    case SilhouetteAlgorithm::YenKwoon: yenKwoonSilhouette(mesh, facing, out, ws); return;
    case SilhouetteAlgorithm::Kilgard: kilgardSilhouette(mesh, facing, out, ws); return;
    case SilhouetteAlgorithm::Lengyel: lengyelSilhouette(mesh, facing, out, ws); return;
  }
}

const char* name(SilhouetteAlgorithm algorithm) {
  switch (algorithm) {
    case SilhouetteAlgorithm::Kuhn: return "kuhn";
    case SilhouetteAlgorithm::YenKwoon: return "yen_kwoon";
    case SilhouetteAlgorithm::Kilgard: return "kilgard";
    case SilhouetteAlgorithm::Lengyel: return "lengyel";
  }
  return "?";
}

}  // namespace shadowref
