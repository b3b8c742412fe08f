#include "exec/setup_reuse.h"

namespace shadowref {

bool setsUpAlike(const RenderState& a, const RenderState& b) {
  const Viewport& u = a.viewport;
  const Viewport& v = b.viewport;
  return u.x == v.x && u.y == v.y && u.width == v.width && u.height == v.height && u.nearVal == v.nearVal &&
         u.farVal == v.farVal && a.frontFace == b.frontFace && a.cull == b.cull &&
         a.polygonOffset.enabled == b.polygonOffset.enabled && a.polygonOffset.factor == b.polygonOffset.factor &&
         a.polygonOffset.units == b.polygonOffset.units && a.depthClamp == b.depthClamp && a.clipFar == b.clipFar;
}

}  // namespace shadowref
