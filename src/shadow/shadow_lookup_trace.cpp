#include "shadow/shadow_lookup_trace.h"

#include <algorithm>

namespace shadowref {

namespace {

bool compare(CompareFunc func, float r, float d) {
  switch (func) {
    case CompareFunc::Never: return false;
    case CompareFunc::Less: return r < d;
    case CompareFunc::Equal: return r == d;
    case CompareFunc::LEqual: return r <= d;
    case CompareFunc::Greater: return r > d;
    case CompareFunc::NotEqual: return r != d;
    case CompareFunc::GEqual: return r >= d;
    case CompareFunc::Always: return true;
  }
  return false;
}

}  // namespace

ShadowLookupTrace traceShadowLookup(const LightShadow& shadow, const glm::dvec3& p, const glm::dvec4& receiverPlane) {
  ShadowLookupTrace trace;
  const ShadowLookup* lookup = &shadow.lookup;
  if (shadow.cube) {
    const CubeFace face = cubeFaceFor(p - shadow.cubeLookup.lightPosition);
    trace.face = int(face);
    lookup = &shadow.cubeLookup.faces[size_t(face)];
  }
  trace.pcf = lookup->pcf;
  trace.strq = withConstantBias(shadowCoordinates(lookup->textureMatrix, p), lookup->constantBias);
  trace.s = trace.strq.x / trace.strq.w;
  trace.t = trace.strq.y / trace.strq.w;
  trace.r = trace.strq.z / trace.strq.w;
  const DepthTexture* texture = lookup->sampler.texture;
  if (texture && texture->width > 0 && texture->height > 0) {
    trace.mapWidth = texture->width;
    trace.mapHeight = texture->height;
    trace.texelX = nearestTexel(trace.s, texture->width);
    trace.texelY = nearestTexel(trace.t, texture->height);
    trace.stored = texture->at(trace.texelX, trace.texelY);
    trace.compared = float(std::clamp(trace.r, 0.0, 1.0));  // NaN stays NaN and fails
    trace.passed = compare(lookup->sampler.func, trace.compared, trace.stored);
  }
  trace.behindLight = !(trace.strq.w > 0.0);
  if (shadow.trapezoidal && !shadow.cube)
    trace.behindLight =
        trace.behindLight || !((shadow.views[0].projection * (shadow.views[0].view * glm::dvec4(p, 1.0))).w > 0.0);
  trace.outsideMap = !trace.behindLight && lookup->outsideLit &&
                     (trace.s < 0.0 || trace.s > 1.0 || trace.t < 0.0 || trace.t > 1.0);
  trace.result = shadow.factor(p, receiverPlane);
  return trace;
}

}  // namespace shadowref
