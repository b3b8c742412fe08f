#include "exec/setup_reuse.h"

#include <cstring>

namespace shadowref {

bool setsUpAlike(const RenderState& a, const RenderState& b) {
  const Viewport& u = a.viewport;
  const Viewport& v = b.viewport;
  return u.x == v.x && u.y == v.y && u.width == v.width && u.height == v.height && u.nearVal == v.nearVal &&
         u.farVal == v.farVal && a.frontFace == b.frontFace && a.cull == b.cull &&
         a.polygonOffset.enabled == b.polygonOffset.enabled && a.polygonOffset.factor == b.polygonOffset.factor &&
         a.polygonOffset.units == b.polygonOffset.units && a.depthClamp == b.depthClamp && a.clipFar == b.clipFar;
}

bool SetupReuse::sameContents(std::span<const ClipVertex> vertices, std::span<const uint32_t> indices) const {
  if (vertices.size() != positions_.size() || indices.size() != indices_.size()) return false;
  if (!indices.empty() && std::memcmp(indices.data(), indices_.data(), indices.size_bytes()) != 0) return false;
  static_assert(sizeof(glm::dvec4) == 4 * sizeof(double));
  for (size_t i = 0; i < vertices.size(); ++i)
    if (std::memcmp(&vertices[i].position, &positions_[i], sizeof(glm::dvec4)) != 0) return false;
  return true;
}

void SetupReuse::keepContents(std::span<const ClipVertex> vertices, std::span<const uint32_t> indices) {
  positions_.resize(vertices.size());
  for (size_t i = 0; i < vertices.size(); ++i) std::memcpy(&positions_[i], &vertices[i].position, sizeof(glm::dvec4));
  indices_.assign(indices.begin(), indices.end());
}

}  // namespace shadowref
