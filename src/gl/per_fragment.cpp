#include "gl/per_fragment.h"

#include "gl/fragment_ops.h"
#include "gl/fragment_stage.h"

namespace shadowref {

BufferUse bufferUse(const Framebuffer& fb, const RenderState& state, const FragmentShader* shader) {
  const bool anyColorChannel = state.colorMask[0] || state.colorMask[1] || state.colorMask[2] || state.colorMask[3];
  BufferUse u;
  u.writesColor = shader != nullptr && anyColorChannel && fb.hasColor();
  u.usesDepth = state.depthTest && fb.hasDepth();
  u.writesDepth = u.usesDepth && state.depthWrite;
  u.usesStencil = state.stencilTest && fb.hasStencil();
  return u;
}

void processFragment(Framebuffer& fb, const RenderState& state, const FragmentShader* shader, const BufferUse& use,
                     const TriangleSetup& t, const CoveredPixel& p, RasterStats& stats, const PixelWatch* watch) {
  const int x = p.x, y = p.y;
  if (!scissorTest(state, x, y)) return;  // [GL 2.1, §4.1.2] (drawRegion already leaves it out)
  ++stats.fragments;
  const size_t at = fb.index(x, y);
  const bool watched = watch && watch->observer && x == watch->x && y == watch->y;
  FragmentEvent event;
  if (watched) {
    event.x = x;
    event.y = y;
    event.drawIndex = watch->drawIndex;
    event.drawTag = watch->drawTag;
    event.facing = t.facing;
    if (watch->hasStencil) event.stencilBefore = event.stencilAfter = fb.stencil()[at];
    if (watch->hasDepth) event.storedDepth = fb.depthCodec().decode(fb.depthCodes()[at]);
    if (watch->hasColor) event.colorBefore = event.colorAfter = fb.color()[at];
  }

  // The fragment's depth in the buffer's format: the depth test compares codes ([GL 2.1, §4.1.6]).
  const double z = fragmentDepth(t, x, y, state);
  const uint32_t zCode = fb.depthCodec().encode(z);
  if (watched) event.depth = fb.depthCodec().decode(zCode);

  // Stencil test with the face's state (two-sided stencil); a failing fragment takes the sfail op
  // and is discarded before the depth test ([GL 2.1, §4.1.5]).
  const StencilFaceState& face = state.stencil[t.facing];
  uint8_t* stencil = use.usesStencil ? &fb.stencil()[at] : nullptr;
  if (stencil && !stencilTest(face, *stencil)) {
    ++stats.stencilFailed;
    const uint8_t next = writeStencil(*stencil, applyStencilOp(face.sfail, *stencil, face.ref), face.writeMask);
    stats.stencilWrites += next != *stencil;
    *stencil = next;
    if (watched) {
      event.stencilPassed = false;
      event.depthPassed = false;
      event.stencilAfter = next;
      watch->observer->onFragment(event);
    }
    return;
  }

  // Depth test; then the stencil update by its outcome, dpfail or dppass, in either case
  // ([GL 2.1, §4.1.5, §4.1.6]).
  const bool depthPassed = !use.usesDepth || depthTest(state.depthFunc, zCode, fb.depthCodes()[at]);
  if (stencil) {
    const StencilOp op = depthPassed ? face.dppass : face.dpfail;
    const uint8_t next = writeStencil(*stencil, applyStencilOp(op, *stencil, face.ref), face.writeMask);
    stats.stencilWrites += next != *stencil;
    *stencil = next;
    if (watched) event.stencilAfter = next;
  }
  if (!depthPassed) {
    ++stats.depthFailed;
    if (watched) {
      event.depthPassed = false;
      watch->observer->onFragment(event);
    }
    return;
  }
  if (use.writesDepth) fb.depthCodes()[at] = zCode;  // glDepthMask

  // Shading, blending with the stored colour, and the write through the colour mask
  // ([GL 2.1, §4.1.8, §4.2.2]).
  if (use.writesColor) {
    glm::vec4& dst = fb.color()[at];
    const glm::dvec4 src = shadeFragment(*shader, t, x, y, fb.depthCodec().decode(zCode), p.e[0], p.e[1], p.e[2]);
    dst = writeColor(dst, blend(state.blend, src, glm::dvec4(dst)), state.colorMask);
    ++stats.colorWrites;
    if (watched) {
      event.colorAfter = dst;
      if (shader->varyingCount() >= 3) {
        double varyings[kMaxVaryings];
        interpolateVaryings(t, p.e[0], p.e[1], p.e[2], shader->varyingCount(), varyings);
        event.varyingCount = 3;
        event.varyings = {varyings[0], varyings[1], varyings[2]};
        for (int i = 0; i < 3; ++i) {
          const double* v = t.v[i].source->varyings.data();
          event.triangleVaryings[size_t(i)] = {v[0], v[1], v[2]};
        }
      }
    }
  }
  if (watched) watch->observer->onFragment(event);
}

}  // namespace shadowref
