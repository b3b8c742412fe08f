#include "shadow/caps.h"

namespace shadowref {

void appendFrontCap(const Mesh& mesh, const std::vector<uint8_t>& facing, std::vector<glm::uvec3>& out) {
  for (size_t t = 0; t < mesh.weldedTriangles.size(); ++t)
    if (facing[t]) out.push_back(mesh.weldedTriangles[t]);
}

void appendBackCap(const Mesh& mesh, const std::vector<uint8_t>& facing, const InfiniteIndexing& infinite,
                   std::vector<glm::uvec3>& out) {
  if (infinite.shared) return;
  for (size_t t = 0; t < mesh.weldedTriangles.size(); ++t) {
    if (facing[t]) continue;
    const glm::uvec3 tri = mesh.weldedTriangles[t];
    out.push_back({infinite(tri.x), infinite(tri.y), infinite(tri.z)});
  }
}

}  // namespace shadowref
