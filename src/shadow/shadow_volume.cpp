#include "shadow/shadow_volume.h"

#include "shadow/caps.h"
#include "shadow/facing.h"

namespace shadowref {

namespace {

// The vertex list shared by both volume builders: the welded vertices, then their points at
// infinity (extrusion.h).
void fillPositions(const Mesh& mesh, const glm::dvec4& light, ShadowVolume& out) {
  const size_t n = mesh.weldedPositions.size();
  const bool directional = light.w == 0.0;
  out.infinite = InfiniteIndexing{static_cast<uint32_t>(n), directional};
  out.positions.clear();
  out.positions.reserve(n + (directional ? 1 : n));
  for (const glm::dvec3& p : mesh.weldedPositions) out.positions.emplace_back(p, 1.0);
  if (directional) {
    out.positions.push_back(extrudeToInfinity(glm::dvec3(0.0), light));
  } else {
    for (const glm::dvec3& p : mesh.weldedPositions) out.positions.push_back(extrudeToInfinity(p, light));
  }
}

void clearParts(ShadowVolume& out) {
  out.silhouette.clear();
  out.sides.clear();
  out.frontCap.clear();
  out.backCap.clear();
  out.stats = {};
}

void countParts(ShadowVolume& out) {
  out.stats.sideTriangles = out.sides.size();
  out.stats.frontCapTriangles = out.frontCap.size();
  out.stats.backCapTriangles = out.backCap.size();
}

// Triangle `tri` turned towards the light when `orientation` < 0. The first corner stays first:
// triangle set-up keeps the first vertex and swaps the other two of a clockwise triangle
// (gl/triangle_setup.cpp), so (a, c, b) is set up exactly as (a, b, c) and the front cap's depths
// are bit for bit those of the scene pass either way ("Bit-equal front caps" in
// docs/shadow-volumes.md).
glm::uvec3 oriented(const glm::uvec3& tri, int orientation) {
  return orientation > 0 ? tri : glm::uvec3(tri.x, tri.z, tri.y);
}

// The caps of one oriented triangle: itself as front cap; its image at infinity, turned round so
// that it faces out of the volume, as back cap (none for a shared point at infinity).
void appendTriangleCaps(const glm::uvec3& front, const InfiniteIndexing& infinite, bool backCap, ShadowVolume& out) {
  out.frontCap.push_back(front);
  if (backCap && !infinite.shared)
    out.backCap.push_back({infinite(front.x), infinite(front.z), infinite(front.y)});
}

// Reversed and two-sided casting (volume_casting.h): the per-triangle volumes of the oriented
// triangles, with every pair of opposite sides left out. Each oriented triangle adds +1 to the
// edges it runs v0 -> v1 and -1 to those it runs v1 -> v0; an edge whose sum is c != 0 is the side
// of |c| per-triangle volumes that nothing cancels, run v0 -> v1 when c > 0. Those sides are
// emitted |c| times, each as the per-triangle volume of the last triangle that ran it that way
// would (appendSideTriangles cuts a quad along the same diagonal whichever volume it belongs
// to), so the count at every pixel is the per-triangle volumes' count. O(triangles + edges).
void buildOrientedVolume(const Mesh& mesh, const glm::dvec4& light, VolumeCasting casting, bool withCaps,
                         ShadowVolume& out, ShadowVolumeWorkspace& ws) {
  orientTowardsLight(mesh, light, casting, ws.orientation);
  ws.edgeCount.assign(mesh.edges.size(), 0);
  ws.edgeTriangle.assign(mesh.edges.size(), glm::uvec2(kNoTriangle));
  for (uint32_t t = 0; t < mesh.weldedTriangles.size(); ++t) {
    const int s = ws.orientation[t];
    if (s == 0) continue;
    ++out.stats.facingTriangles;
    const glm::uvec3 tri = mesh.weldedTriangles[t];
    for (int i = 0; i < 3; ++i) {
      const uint32_t k = mesh.triangleEdges[t][i];
      const int along = (tri[i] == mesh.edges[k].v0 ? 1 : -1) * s;  // +1: the oriented triangle runs v0 -> v1
      ws.edgeCount[k] += along;
      ws.edgeTriangle[k][along > 0 ? 0 : 1] = t;
    }
    // Front cap always: z-pass counts it for these meshes (ShadowVolume::frontCapInZPass).
    appendTriangleCaps(oriented(tri, s), out.infinite, withCaps, out);
  }
  for (uint32_t k = 0; k < mesh.edges.size(); ++k) {
    const int c = ws.edgeCount[k];
    if (c == 0) continue;
    const Edge& e = mesh.edges[k];
    const SilhouetteEdge side = c > 0 ? SilhouetteEdge{e.v0, e.v1, ws.edgeTriangle[k][0]}
                                      : SilhouetteEdge{e.v1, e.v0, ws.edgeTriangle[k][1]};
    for (int n = 0; n < (c > 0 ? c : -c); ++n) {
      out.silhouette.push_back(side);
      appendSideTriangles(side, out.infinite, out.sides);
    }
  }
}

}  // namespace

void orientTowardsLight(const Mesh& mesh, const glm::dvec4& light, VolumeCasting casting,
                        std::vector<int8_t>& orientation) {
  const size_t count = mesh.weldedTriangles.size();
  orientation.resize(count);
  for (size_t t = 0; t < count; ++t) {
    const glm::dvec3& a = mesh.weldedPositions[mesh.weldedTriangles[t].x];
    const glm::dvec3& n = mesh.faceNormals[t];
    const bool front = casting != VolumeCasting::Reversed && facesLight(n, a, light);
    const bool back = casting != VolumeCasting::Silhouette && facesLight(-n, a, light);
    orientation[t] = front ? 1 : back ? -1 : 0;
  }
}

void buildShadowVolume(const Mesh& mesh, const glm::dvec4& light, SilhouetteAlgorithm algorithm, bool withCaps,
                       ShadowVolume& out, ShadowVolumeWorkspace* workspace) {
  ShadowVolumeWorkspace local;
  ShadowVolumeWorkspace& ws = workspace ? *workspace : local;
  clearParts(out);
  fillPositions(mesh, light, out);
  out.casting = volumeCastingOf(mesh);
  if (out.casting != VolumeCasting::Silhouette) {
    buildOrientedVolume(mesh, light, out.casting, withCaps, out, ws);
    out.stats.silhouetteEdges = out.silhouette.size();
    countParts(out);
    return;
  }

  computeFacing(mesh, light, ws.facing);
  findSilhouette(mesh, ws.facing, algorithm, out.silhouette, &ws.silhouette);
  for (const SilhouetteEdge& e : out.silhouette) appendSideTriangles(e, out.infinite, out.sides);
  if (withCaps) {
    appendFrontCap(mesh, ws.facing, out.frontCap);
    appendBackCap(mesh, ws.facing, out.infinite, out.backCap);
  }

  for (uint8_t f : ws.facing) out.stats.facingTriangles += f;
  out.stats.silhouetteEdges = out.silhouette.size();
  countParts(out);
}

ShadowVolume buildShadowVolume(const Mesh& mesh, const glm::dvec4& light, SilhouetteAlgorithm algorithm,
                               bool withCaps) {
  ShadowVolume v;
  buildShadowVolume(mesh, light, algorithm, withCaps, v);
  return v;
}

ShadowVolume buildTriangleVolumes(const Mesh& mesh, const glm::dvec4& light, bool withCaps) {
  ShadowVolume out;
  fillPositions(mesh, light, out);
  out.casting = volumeCastingOf(mesh);
  std::vector<int8_t> orientation;
  orientTowardsLight(mesh, light, out.casting, orientation);
  for (uint32_t t = 0; t < mesh.weldedTriangles.size(); ++t) {
    if (!orientation[t]) continue;
    ++out.stats.facingTriangles;
    const glm::uvec3 tri = oriented(mesh.weldedTriangles[t], orientation[t]);
    for (int i = 0; i < 3; ++i) {
      const SilhouetteEdge e{tri[i], tri[(i + 1) % 3], t};
      out.silhouette.push_back(e);
      appendSideTriangles(e, out.infinite, out.sides);
    }
    // The triangle faces the light, so at infinity it is turned round to face out.
    if (withCaps || out.frontCapInZPass()) appendTriangleCaps(tri, out.infinite, withCaps, out);
  }
  out.stats.silhouetteEdges = out.silhouette.size();
  countParts(out);
  return out;
}

}  // namespace shadowref
