#include "gl/primitive_assembly.h"

#include <algorithm>
#include <stdexcept>

namespace shadowref {

double guardBandFor(const Viewport& vp) {
  const double extent = double(std::max({vp.width, vp.height, 1}));
  return std::max(1.0, double(1 << 20) / extent);
}

ClipPlanes clipPlanesFor(const RenderState& state) {
  ClipPlanes planes;
  planes.nearPlane = !state.depthClamp;
  planes.farPlane = state.clipFar && !state.depthClamp;
  planes.guardBand = guardBandFor(state.viewport);
  return planes;
}

Rect drawRegion(const RenderState& state, const Framebuffer& fb) {
  int x0 = std::max({0, state.viewport.x});
  int y0 = std::max({0, state.viewport.y});
  int x1 = std::min(fb.width(), state.viewport.x + state.viewport.width);
  int y1 = std::min(fb.height(), state.viewport.y + state.viewport.height);
  if (state.scissorTest) {
    x0 = std::max(x0, state.scissor.x);
    y0 = std::max(y0, state.scissor.y);
    x1 = std::min(x1, state.scissor.x + state.scissor.width);
    y1 = std::min(y1, state.scissor.y + state.scissor.height);
  }
  return Rect{x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

void ensureBuffersFor(Framebuffer& fb, const DrawCall& call) {
  const RenderState& state = *call.state;
  const bool anyColor = state.colorMask[0] || state.colorMask[1] || state.colorMask[2] || state.colorMask[3];
  if (call.shader && anyColor) fb.ensureColor();
  if (state.depthTest) fb.ensureDepth();
  if (state.stencilTest) fb.ensureStencil();
}

size_t trianglesOf(const DrawCall& call) {
  return call.indices.empty() ? call.vertices.size() / 3 : call.indices.size() / 3;
}

void checkIndices(const DrawCall& call) {
  // The largest index, in a loop without an exit: it vectorises (a large pass has hundreds of
  // thousands of indices).
  uint32_t largest = 0;
  for (const uint32_t index : call.indices) largest = std::max(largest, index);
  if (!call.indices.empty() && largest >= call.vertices.size()) throw std::out_of_range("draw: vertex index out of range");
}

void triangleVertices(const DrawCall& call, size_t i, const ClipVertex* out[3]) {
  for (size_t k = 0; k < 3; ++k) {
    const size_t index = call.indices.empty() ? 3 * i + k : call.indices[3 * i + k];
    out[k] = &call.vertices[index];
  }
}

namespace {
bool lexicographicallyLess(const glm::dvec4& a, const glm::dvec4& b) {
  for (int i = 0; i < 4; ++i) {
    if (a[i] < b[i]) return true;
    if (a[i] > b[i]) return false;
  }
  return false;
}
}  // namespace

void canonicalRotation(const ClipVertex*& a, const ClipVertex*& b, const ClipVertex*& c) {
  const ClipVertex* v[3] = {a, b, c};
  int m = 0;
  if (lexicographicallyLess(v[1]->position, v[m]->position)) m = 1;
  if (lexicographicallyLess(v[2]->position, v[m]->position)) m = 2;
  a = v[m];
  b = v[(m + 1) % 3];
  c = v[(m + 2) % 3];
}

namespace {
// Appends the setup of window triangle (a, b, c) when it has pixels to give (setupTriangle).
void addSetup(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c, Facing facing,
              const RenderState& state, const DepthCodec& codec, std::vector<TriangleSetup>& setups,
              RasterStats& stats) {
  TriangleSetup t;
  if (!setupTriangle(a, b, c, facing, state, codec, t)) return;
  setups.push_back(t);
  ++stats.trianglesRasterized;
}
}  // namespace

void assembleTriangle(const ClipVertex* a, const ClipVertex* b, const ClipVertex* c, const RenderState& state,
                      const ClipPlanes& planes, int varyingCount, const DepthCodec& codec, AssemblyScratch& scratch,
                      std::vector<TriangleSetup>& setups, RasterStats& stats) {
  setups.clear();
  canonicalRotation(a, b, c);
  const ClipVertex* tri[3] = {a, b, c};
  bool inside = true;
  for (const ClipVertex* v : tri) inside = inside && insideAllPlanes(v, 1, planes);

  if (inside) {  // the common case: the triangle as it is
    const WindowVertex wa = toWindow(*a, state.viewport), wb = toWindow(*b, state.viewport),
                       wc = toWindow(*c, state.viewport);
    const int64_t area2 = signedArea2(wa, wb, wc);
    const Facing facing = facingOf(area2, state.frontFace);
    if (area2 == 0 || isCulled(facing, state.cull)) {
      ++stats.trianglesCulled;
      return;
    }
    addSetup(wa, wb, wc, facing, state, codec, setups, stats);
    return;
  }

  ++stats.trianglesClipped;
  scratch.polygon.assign({*a, *b, *c});
  clipPolygon(scratch.polygon, planes, varyingCount, scratch.clipped, scratch.clipScratch);
  if (scratch.clipped.size() < 3) return;  // clipped away whole
  scratch.window.clear();
  for (const ClipVertex& v : scratch.clipped) scratch.window.push_back(toWindow(v, state.viewport));
  // Facing of the polygon as a whole: the sum of its fan's signed areas, in fixed point.
  int64_t area2 = 0;
  for (size_t i = 1; i + 1 < scratch.window.size(); ++i)
    area2 += signedArea2(scratch.window[0], scratch.window[i], scratch.window[i + 1]);
  const Facing facing = facingOf(area2, state.frontFace);
  if (area2 == 0 || isCulled(facing, state.cull)) {
    ++stats.trianglesCulled;
    return;
  }
  for (size_t i = 1; i + 1 < scratch.window.size(); ++i)
    addSetup(scratch.window[0], scratch.window[i], scratch.window[i + 1], facing, state, codec, setups, stats);
}

}  // namespace shadowref
