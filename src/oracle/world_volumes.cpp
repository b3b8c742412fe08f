#include "oracle/world_volumes.h"

#include <algorithm>
#include <tuple>

#include "shadow/facing.h"
#include "shadow/scene_passes.h"

namespace shadowref::oracle {

namespace {

void appendPart(const ShadowVolume& volume, VolumePart part, const std::vector<glm::dvec4>& world, int instance,
                int volumeIndex, double orientation, WorldVolumes& out) {
  const std::vector<glm::uvec3>& tris = volume.part(part);
  for (size_t i = 0; i < tris.size(); ++i) {
    const glm::uvec3 t = tris[i];
    VolumeTriangle v;
    v.triangle = makeProjectiveTriangle(world[t[0]], world[t[1]], world[t[2]]);
    v.instance = instance;
    v.volume = volumeIndex;
    v.part = part;
    v.countedByZPass = part == VolumePart::Side || (part == VolumePart::FrontCap && volume.frontCapInZPass());
    v.orientation = orientation;
    v.index = {t[0], t[1], t[2]};
    out.triangles.push_back(v);
  }
}

}  // namespace

bool castsShadowFor(const Instance& instance, const Light& light, bool respectRange) {
  if (!instance.shadowMesh) return false;
  return !respectRange || withinRange(light, instance.worldBounds);
}

WorldVolumes buildWorldVolumes(const std::vector<Instance>& instances, const Light& light,
                               SilhouetteAlgorithm algorithm, bool respectRange) {
  WorldVolumes out;
  ShadowVolume volume;
  ShadowVolumeWorkspace workspace;
  std::vector<glm::dvec4> world;
  for (size_t i = 0; i < instances.size(); ++i) {
    const Instance& inst = instances[i];
    if (!castsShadowFor(inst, light, respectRange)) continue;
    const glm::dvec4 objectLight = lightInObjectSpace(inst.world, light.homogeneous());
    buildShadowVolume(*inst.shadowMesh, objectLight, algorithm, true, volume, &workspace);
    world.clear();
    for (const glm::dvec4& p : volume.positions) world.push_back(inst.world * p);
    const double orientation = glm::determinant(inst.world) < 0.0 ? -1.0 : 1.0;
    const int volumeIndex = static_cast<int>(out.volumeInstances.size());
    out.volumeInstances.push_back(static_cast<int>(i));
    appendPart(volume, VolumePart::Side, world, static_cast<int>(i), volumeIndex, orientation, out);
    appendPart(volume, VolumePart::FrontCap, world, static_cast<int>(i), volumeIndex, orientation, out);
    appendPart(volume, VolumePart::BackCap, world, static_cast<int>(i), volumeIndex, orientation, out);
  }
  return out;
}

std::vector<std::pair<glm::dvec4, glm::dvec4>> volumeContourEdges(const WorldVolumes& volumes, const glm::dvec3& eye) {
  // (volume, low vertex, high vertex, triangle): sorted, each run is one edge with its triangles.
  std::vector<std::tuple<int, uint32_t, uint32_t, uint32_t, int>> edges;
  edges.reserve(volumes.triangles.size() * 3);
  for (uint32_t t = 0; t < volumes.triangles.size(); ++t) {
    const VolumeTriangle& v = volumes.triangles[t];
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = v.index[i], b = v.index[(i + 1) % 3];
      edges.emplace_back(v.volume, std::min(a, b), std::max(a, b), t, i);
    }
  }
  std::sort(edges.begin(), edges.end());
  const glm::dvec4 eyeH(eye, 1.0);
  std::vector<std::pair<glm::dvec4, glm::dvec4>> out;
  for (size_t begin = 0; begin < edges.size();) {
    size_t end = begin + 1;
    while (end < edges.size() && std::get<0>(edges[end]) == std::get<0>(edges[begin]) &&
           std::get<1>(edges[end]) == std::get<1>(edges[begin]) && std::get<2>(edges[end]) == std::get<2>(edges[begin]))
      ++end;
    bool contour = end - begin != 2;
    if (!contour) {
      const bool f0 = volumes.triangles[std::get<3>(edges[begin])].outside(eyeH) > 0.0;
      const bool f1 = volumes.triangles[std::get<3>(edges[begin + 1])].outside(eyeH) > 0.0;
      contour = f0 != f1;
    }
    if (contour) {
      const VolumeTriangle& v = volumes.triangles[std::get<3>(edges[begin])];
      const int i = std::get<4>(edges[begin]);
      out.emplace_back(v.triangle.v[i], v.triangle.v[(i + 1) % 3]);
    }
    begin = end;
  }
  return out;
}

}  // namespace shadowref::oracle
