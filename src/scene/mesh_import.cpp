#include "scene/mesh_import.h"

#include <cmath>

#include "scene/adjacency.h"
#include "scene/scene_error.h"

namespace shadowref {

Mesh finishImportedMesh(Mesh mesh, bool haveNormals, const std::string& path, std::vector<std::string>* warnings) {
  auto fail = [&](const std::string& message) { throw SceneError(SourceLocation{path, 0, 0}, message); };
  if (mesh.triangles.empty()) fail("mesh has no triangles");
  for (const glm::dvec3& p : mesh.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail("vertex coordinate is NaN or infinite");
  if (haveNormals)
    for (glm::dvec3& n : mesh.normals) {
      const double length = glm::length(n);
      if (!(length > 0.0) || !std::isfinite(length)) {
        haveNormals = false;
        break;
      }
      n /= length;
    }
  if (!haveNormals) computeCreaseNormals(mesh);
  buildAdjacency(mesh, warnings);
  if (mesh.triangles.empty()) fail("mesh has no triangles that are not degenerate");
  return mesh;
}

}  // namespace shadowref
