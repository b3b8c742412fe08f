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

}  // namespace

void buildShadowVolume(const Mesh& mesh, const glm::dvec4& light, SilhouetteAlgorithm algorithm, bool withCaps,
                       ShadowVolume& out, ShadowVolumeWorkspace* workspace) {
  ShadowVolumeWorkspace local;
  ShadowVolumeWorkspace& ws = workspace ? *workspace : local;
  clearParts(out);
  fillPositions(mesh, light, out);

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
  std::vector<uint8_t> facing;
  computeFacing(mesh, light, facing);
  for (uint32_t t = 0; t < mesh.weldedTriangles.size(); ++t) {
    if (!facing[t]) continue;
    ++out.stats.facingTriangles;
    const glm::uvec3 tri = mesh.weldedTriangles[t];
    for (int i = 0; i < 3; ++i) {
      const SilhouetteEdge e{tri[i], tri[(i + 1) % 3], t};
      out.silhouette.push_back(e);
      appendSideTriangles(e, out.infinite, out.sides);
    }
    if (!withCaps) continue;
    out.frontCap.push_back(tri);
    // The triangle itself faces the light, so at infinity it must be turned round to face out.
    if (!out.infinite.shared) out.backCap.push_back({out.infinite(tri.x), out.infinite(tri.z), out.infinite(tri.y)});
  }
  out.stats.silhouetteEdges = out.silhouette.size();
  countParts(out);
  return out;
}

}  // namespace shadowref
