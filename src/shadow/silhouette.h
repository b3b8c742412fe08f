// Silhouette edges of a mesh seen from a light ([Kuhn 2016, §3.5]; [SV slides]; [DSS article]): the
// edges between a light-facing and a light-averted triangle, plus open edges whose one triangle
// faces the light.
//
// Four algorithms from the documents, selectable by SilhouetteAlgorithm. All of them read the same
// facing flags (facing.h) and report each edge oriented as it runs in its light-facing triangle,
// so on closed and on open manifold meshes they return the same set of oriented edges; only the
// ORDER of the list differs. Extrusion (extrusion.h) relies on that orientation.
//
//  - Kuhn ([Kuhn 2016, §3.5, §4.3.3]; the default): one pass over the edge list of
//    [Kuhn 2016, §4.3.5], whose edges know both triangles.
//  - Yen Kwoon ([Kuhn 2016, §3.5 Algorithm 1]): the edges of every light-facing triangle are
//    toggled in a list; an edge seen twice cancels, the silhouette remains.
//  - Kilgard ([Kuhn 2016, §3.5 Algorithm 2]): per light-facing triangle, each edge whose neighbour
//    does not face the light (or has no neighbour).
//  - Lengyel ([Kuhn 2016, §3.5]): two passes over the triangles build an edge list of their own
//    (first pass creates every edge where i1 < i2, second pass attaches the neighbour of every edge
//    where i1 > i2), then the edges are tested.
//
// Note: the pseudocode of [Kuhn 2016, §3.5] for Yen Kwoon and Kilgard walks the triangles that do
// NOT face the light, while its prose (and [SV slides]) walks the light-facing ones. On a closed
// mesh the two give the same edges (reversed); only the light-facing walk also finds open edges
// ([SV slides], [DSS article]), so it is the one implemented.
//
// Non-manifold edges (three or more triangles) are outside what the documents define: the edge
// list keeps only two of their triangles, and the algorithms may then disagree.
//
// Cost: O(triangles + edges) per call. Pass a SilhouetteWorkspace to reuse its buffers; after the
// first call with a mesh of a given size, no call allocates apart from growing `out`.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "scene/mesh.h"
#include "scene/scene.h"

namespace shadowref {

// A silhouette edge a -> b (welded vertex indices), as it runs (counter-clockwise) in the
// light-facing triangle `facingTriangle`.
struct SilhouetteEdge {
  uint32_t a = 0, b = 0;
  uint32_t facingTriangle = kNoTriangle;
  bool operator==(const SilhouetteEdge&) const = default;
};

// Scratch buffers of the algorithms that need more than the mesh's edge list.
struct SilhouetteWorkspace {
  // Yen Kwoon: open-addressing table keyed by the unordered vertex pair, and the insertion order.
  // A slot belongs to the current call when its stamp matches `toggleStamp`, so the table is never
  // cleared between calls (only when it grows, or once every 2^31 calls).
  struct ToggleSlot {
    uint64_t key = 0;
    uint32_t triangle = 0;  // the light-facing triangle that last added the edge
    uint32_t state = 0;     // stamp * 2 + (1 when the edge is in the list)
  };
  std::vector<ToggleSlot> toggleSlots;
  std::vector<uint32_t> toggleOrder;
  uint32_t toggleStamp = 0;
  // Kilgard: neighbour of each triangle across its edge i (corner i -> corner i+1).
  std::vector<std::array<uint32_t, 3>> neighbours;
  // Lengyel: its own edge list, and per vertex the first edge starting there (a linked list).
  struct LengyelEdge {
    uint32_t v0 = 0, v1 = 0, t0 = kNoTriangle, t1 = kNoTriangle;
    uint32_t next = kNoTriangle;  // next edge with the same smaller vertex
  };
  std::vector<LengyelEdge> lengyelEdges;
  std::vector<uint32_t> firstEdgeOf;
};

// Each appends nothing: `out` is cleared first, then filled.
void kuhnSilhouette(const Mesh& mesh, const std::vector<uint8_t>& facing, std::vector<SilhouetteEdge>& out);
void yenKwoonSilhouette(const Mesh& mesh, const std::vector<uint8_t>& facing, std::vector<SilhouetteEdge>& out,
                        SilhouetteWorkspace& workspace);
void kilgardSilhouette(const Mesh& mesh, const std::vector<uint8_t>& facing, std::vector<SilhouetteEdge>& out,
                       SilhouetteWorkspace& workspace);
void lengyelSilhouette(const Mesh& mesh, const std::vector<uint8_t>& facing, std::vector<SilhouetteEdge>& out,
                       SilhouetteWorkspace& workspace);

// The algorithm chosen by the scene (ShadowSettings::silhouette).
void findSilhouette(const Mesh& mesh, const std::vector<uint8_t>& facing, SilhouetteAlgorithm algorithm,
                    std::vector<SilhouetteEdge>& out, SilhouetteWorkspace* workspace = nullptr);

const char* name(SilhouetteAlgorithm algorithm);

}  // namespace shadowref
