// The shadow volumes of a scene for one light, in world space, as the oracle counts them.
//
// Built with the project's buildShadowVolume (what is being checked is the RASTERIZED COUNT of
// these polygons), per instance that casts shadows (its shadowMesh: the mesh or its proxy)
// and lies within the light's range ([Kuhn 2016, §4.3.1]), with the light brought into object space
// and the homogeneous vertices taken to world space by the instance's world matrix (w = 0 stays w =
// 0: directions transform without translation). A mirroring world matrix (negative determinant)
// turns the winding inside out; `orientation` undoes that, so "outside" is always the outside.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "shadow/shadow_volume.h"
#include "oracle/projective_crossing.h"

namespace shadowref::oracle {

struct VolumeTriangle {
  ProjectiveTriangle triangle;
  int instance = -1;           // index into Scene::instances()
  int volume = -1;             // index of the volume in WorldVolumes::volumeInstances
  VolumePart part = VolumePart::Side;
  bool countedByZPass = true;  // drawn by z-pass: a side, or the front cap of a volume whose frontCapInZPass()
  double orientation = 1.0;    // -1 for a mirroring world matrix
  std::array<uint32_t, 3> index{};        // vertex indices within the volume (for adjacency)

  // > 0 when the homogeneous point lies on the volume's outside of this triangle's plane.
  double outside(const glm::dvec4& x) const { return -orientation * glm::dot(triangle.plane, x); }
};

struct WorldVolumes {
  std::vector<VolumeTriangle> triangles;
  std::vector<int> volumeInstances;  // the instance of each volume
};

// Instances of `instances` that cast a shadow for `light`.
bool castsShadowFor(const Instance& instance, const Light& light, bool respectRange);

WorldVolumes buildWorldVolumes(const std::vector<Instance>& instances, const Light& light,
                               SilhouetteAlgorithm algorithm, bool respectRange);

// The edges of the volumes across which the count seen from `eye` can change: edges whose two
// triangles face the eye differently (the volume's contour from the eye), and edges that do not
// have exactly two triangles. Interior edges between triangles facing the same way are left out:
// watertight rasterization must count across them without a seam, which is what the comparison
// checks. Homogeneous world-space end points.
std::vector<std::pair<glm::dvec4, glm::dvec4>> volumeContourEdges(const WorldVolumes& volumes, const glm::dvec3& eye);

}  // namespace shadowref::oracle
