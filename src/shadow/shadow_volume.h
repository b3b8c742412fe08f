// The shadow volume of one mesh for one light ([Kuhn 2016, §3.4, §4.3.3]): facing, silhouette,
// extruded sides and, for z-fail, the caps — as indexed triangles over homogeneous OBJECT-space
// vertices.
//
// Why object space: the front cap must produce bit-equal depths to the scene pass, or LESS
// would not fail on it and z-fail would miscount. The scene pass transforms each render vertex
// (P, 1) with the instance's modelView and the projection (vertex_stage.h); the volume's first n
// vertices are exactly those positions (the welded positions are the render positions, mesh.h), so
// drawing the volume with the SAME VertexTransform gives the same clip coordinates. Bring the light
// into object space instead (lightInObjectSpace in facing.h).
//
// Caveat for the caller: a world matrix with negative determinant (a mirror) turns the volume
// inside out in window space, as it does the mesh; flip the front face for such instances.
//
// A mesh that is not a closed, consistently wound, outward surface gets the volume of
// volume_casting.h: its winding reversed (inside out), or one volume per triangle turned towards
// the light (open, non-manifold, inconsistently wound). Such a volume has its front cap also when
// built without caps, because z-pass must count it (volume_casting.h says why).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/mesh.h"
#include "scene/scene.h"
#include "shadow/extrusion.h"
#include "shadow/silhouette.h"
#include "shadow/volume_casting.h"

namespace shadowref {

enum class VolumePart : uint8_t { Side, FrontCap, BackCap };

// What --stats prints per object and light.
struct ShadowVolumeStats {
  size_t facingTriangles = 0;
  size_t silhouetteEdges = 0;  // = side quads
  size_t sideTriangles = 0;    // 2 per quad, 1 for a directional light (D = C)
  size_t frontCapTriangles = 0;
  size_t backCapTriangles = 0;
};

struct ShadowVolume {
  // [0, n): the mesh's welded vertices with w = 1; then the points at infinity (w = 0), placed as
  // `infinite` says: n of them for a point light, one for a directional light.
  std::vector<glm::dvec4> positions;
  InfiniteIndexing infinite;
  std::vector<SilhouetteEdge> silhouette;  // as found, oriented in the light-facing triangle
  std::vector<glm::uvec3> sides;           // counter-clockwise seen from outside the volume
  std::vector<glm::uvec3> frontCap;        // empty unless built with caps or frontCapInZPass()
  std::vector<glm::uvec3> backCap;         // empty unless built with caps and L_w != 0
  ShadowVolumeStats stats;
  VolumeCasting casting = VolumeCasting::Silhouette;

  // Whether z-pass draws the front cap of this volume too (volume_casting.h): for every mesh the
  // volumes do not cast as it is written.
  bool frontCapInZPass() const { return casting != VolumeCasting::Silhouette; }

  const std::vector<glm::uvec3>& part(VolumePart p) const {
    return p == VolumePart::Side ? sides : p == VolumePart::FrontCap ? frontCap : backCap;
  }
  size_t triangleCount() const { return sides.size() + frontCap.size() + backCap.size(); }
};

// Scratch reused between calls (facing flags and the silhouette algorithms' buffers).
struct ShadowVolumeWorkspace {
  std::vector<uint8_t> facing;
  SilhouetteWorkspace silhouette;
  // Reversed and two-sided casting: each triangle's orientation towards the light (+1 as wound,
  // -1 turned round, 0 not casting), and per edge the signed count of the oriented triangles that
  // run it v0 -> v1, with the last triangle that ran it each way.
  std::vector<int8_t> orientation;
  std::vector<int32_t> edgeCount;
  std::vector<glm::uvec2> edgeTriangle;
};

// The orientation of every triangle towards `light` as `casting` takes it: Silhouette +1 for a
// light-facing triangle; Reversed -1 for a triangle whose inward normal faces the light;
// TwoSided +1 or -1, whichever side faces the light. 0 when it does not cast (the light in its
// plane, or facing its other side). `orientation` is resized.
void orientTowardsLight(const Mesh& mesh, const glm::dvec4& light, VolumeCasting casting,
                        std::vector<int8_t>& orientation);

// `light` in the mesh's object space: (position, 1) or (direction towards the light, 0).
// withCaps: also the front and back caps (z-fail); without them the sides alone (z-pass).
// Reusing `out` and `workspace` avoids allocation once their buffers have grown.
void buildShadowVolume(const Mesh& mesh, const glm::dvec4& light, SilhouetteAlgorithm algorithm, bool withCaps,
                       ShadowVolume& out, ShadowVolumeWorkspace* workspace = nullptr);
ShadowVolume buildShadowVolume(const Mesh& mesh, const glm::dvec4& light,
                               SilhouetteAlgorithm algorithm = SilhouetteAlgorithm::Kuhn, bool withCaps = true);

// The union of one small volume per light-facing triangle (its three edges extruded, the
// triangle as front cap, the triangle at infinity reversed as back cap), the triangles oriented
// as orientTowardsLight does for the mesh's casting. Counting through it gives the same per-pixel
// stencil as the silhouette volume, because interior sides come in pairs of opposite orientation
// that cancel: an invariant for tests and a teaching view of why the silhouette suffices.
ShadowVolume buildTriangleVolumes(const Mesh& mesh, const glm::dvec4& light, bool withCaps = true);

}  // namespace shadowref
