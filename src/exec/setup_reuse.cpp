#include "exec/setup_reuse.h"

#include <algorithm>
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

// The positions' bits compared as 64-bit words, their differences or-ed together over a run of
// vertices (no branch per vertex: the loop vectorises), a run at a time.
bool SetupReuse::sameContents(std::span<const ClipVertex> vertices, std::span<const uint32_t> indices) const {
  if (vertices.size() != positions_.size() || indices.size() != indices_.size()) return false;
  if (!indices.empty() && std::memcmp(indices.data(), indices_.data(), indices.size_bytes()) != 0) return false;
  static_assert(sizeof(glm::dvec4) == 4 * sizeof(uint64_t));
  constexpr size_t kRun = 256;
  for (size_t first = 0; first < vertices.size(); first += kRun) {
    const size_t last = std::min(vertices.size(), first + kRun);
    uint64_t differ = 0;
    for (size_t i = first; i < last; ++i) {
      uint64_t a[4], b[4];
      std::memcpy(a, &vertices[i].position, sizeof a);
      std::memcpy(b, &positions_[i], sizeof b);
      differ |= (a[0] ^ b[0]) | (a[1] ^ b[1]) | (a[2] ^ b[2]) | (a[3] ^ b[3]);
    }
    if (differ != 0) return false;
  }
  return true;
}

void SetupReuse::keepContents(std::span<const ClipVertex> vertices, std::span<const uint32_t> indices) {
  positions_.resize(vertices.size());
  for (size_t i = 0; i < vertices.size(); ++i) std::memcpy(&positions_[i], &vertices[i].position, sizeof(glm::dvec4));
  indices_.assign(indices.begin(), indices.end());
}

}  // namespace shadowref
