#include "raster/fragment_processor.h"

#include <algorithm>

#include "raster/fragment_ops.h"

namespace shadowref {

FragmentProcessor::FragmentProcessor(Framebuffer& fb, const RenderState& state,
                                     const FragmentShader* shader, RasterStats& stats,
                                     const PixelWatch* watch)
    : fb_(fb), state_(state), shader_(shader), stats_(stats), watch_(watch) {
  const bool anyColorChannel = state.colorMask[0] || state.colorMask[1] || state.colorMask[2] || state.colorMask[3];
  writesColor_ = shader != nullptr && anyColorChannel && fb.hasColor();
  // GL: with the depth test disabled (or no depth buffer) the test passes and nothing is written.
  usesDepth_ = state.depthTest && fb.hasDepth();
  writesDepth_ = usesDepth_ && state.depthWrite;
  usesStencil_ = state.stencilTest && fb.hasStencil();
  varyingCount_ = shader ? shader->varyingCount() : 0;
  depthLo_ = std::min(state.viewport.nearVal, state.viewport.farVal);
  depthHi_ = std::max(state.viewport.nearVal, state.viewport.farVal);
}

double FragmentProcessor::fragmentDepth(const TriangleSetup& t, int x, int y) const {
  double z = planeDepthAt(t, x, y) + t.depthOffset;
  if (state_.depthClamp) z = std::clamp(z, depthLo_, depthHi_);
  return z;  // the depth codec clamps to [0, 1] when it converts
}

void FragmentProcessor::interpolateVaryings(const TriangleSetup& t, int64_t e0, int64_t e1, int64_t e2,
                                            double* out) const {
  // Perspective-correct: weights lambda_i / w_i, normalised (GL 2.1 §3.5.1, eq. 3.6).
  const double b0 = double(e0) * t.v[0].invW;
  const double b1 = double(e1) * t.v[1].invW;
  const double b2 = double(e2) * t.v[2].invW;
  const double inv = 1.0 / (b0 + b1 + b2);
  const double* a0 = t.v[0].source->varyings.data();
  const double* a1 = t.v[1].source->varyings.data();
  const double* a2 = t.v[2].source->varyings.data();
  for (int k = 0; k < varyingCount_; ++k) out[k] = (b0 * a0[k] + b1 * a1[k] + b2 * a2[k]) * inv;
}

glm::dvec4 FragmentProcessor::shade(const TriangleSetup& t, int x, int y, double z, int64_t e0, int64_t e1,
                                    int64_t e2) const {
  double varyings[kMaxVaryings];
  interpolateVaryings(t, e0, e1, e2, varyings);
  FragmentInput in;
  in.x = x;
  in.y = y;
  in.depth = z;
  in.facing = t.facing;
  in.varyings = varyings;
  return shader_->shade(in);
}

template <bool watched>
void FragmentProcessor::processImpl(const TriangleSetup& t, int x, int y, int64_t e0, int64_t e1, int64_t e2) {
  if (!scissorTest(state_, x, y)) return;
  ++stats_.fragments;
  const size_t at = fb_.index(x, y);
  FragmentEvent event;
  if constexpr (watched) {
    event.x = x;
    event.y = y;
    event.drawIndex = watch_->drawIndex;
    event.drawTag = watch_->drawTag;
    event.facing = t.facing;
    if (fb_.hasStencil()) event.stencilBefore = event.stencilAfter = fb_.stencil()[at];
    if (fb_.hasDepth()) event.storedDepth = fb_.depthCodec().decode(fb_.depthCodes()[at]);
    if (fb_.hasColor()) event.colorBefore = event.colorAfter = fb_.color()[at];
  }

  const double z = fragmentDepth(t, x, y);
  const uint32_t zCode = fb_.depthCodec().encode(z);
  if constexpr (watched) event.depth = fb_.depthCodec().decode(zCode);

  // Stencil test, then the depth test, then the stencil update (GL 2.1 §4.1.5, §4.1.6).
  const StencilFaceState& sface = state_.stencil[t.facing];
  uint8_t* stencil = usesStencil_ ? &fb_.stencil()[at] : nullptr;
  if (stencil && !stencilTest(sface, *stencil)) {
    ++stats_.stencilFailed;
    const uint8_t next = writeStencil(*stencil, applyStencilOp(sface.sfail, *stencil, sface.ref), sface.writeMask);
    stats_.stencilWrites += next != *stencil;
    *stencil = next;
    if constexpr (watched) {
      event.stencilPassed = false;
      event.depthPassed = false;
      event.stencilAfter = next;
      watch_->observer->onFragment(event);
    }
    return;
  }

  bool depthPassed = true;
  if (usesDepth_) depthPassed = depthTest(state_.depthFunc, zCode, fb_.depthCodes()[at]);
  if (stencil) {
    const StencilOp op = depthPassed ? sface.dppass : sface.dpfail;
    const uint8_t next = writeStencil(*stencil, applyStencilOp(op, *stencil, sface.ref), sface.writeMask);
    stats_.stencilWrites += next != *stencil;
    *stencil = next;
    if constexpr (watched) event.stencilAfter = next;
  }
  if (!depthPassed) {
    ++stats_.depthFailed;
    if constexpr (watched) {
      event.depthPassed = false;
      watch_->observer->onFragment(event);
    }
    return;
  }
  if (writesDepth_) fb_.depthCodes()[at] = zCode;

  if (writesColor_) {
    glm::vec4& dst = fb_.color()[at];
    const glm::dvec4 src = shade(t, x, y, fb_.depthCodec().decode(zCode), e0, e1, e2);
    dst = writeColor(dst, blend(state_.blend, src, glm::dvec4(dst)), state_.colorMask);
    ++stats_.colorWrites;
    if constexpr (watched) event.colorAfter = dst;
  }
  if constexpr (watched) watch_->observer->onFragment(event);
}

template void FragmentProcessor::processImpl<false>(const TriangleSetup&, int, int, int64_t, int64_t, int64_t);
template void FragmentProcessor::processImpl<true>(const TriangleSetup&, int, int, int64_t, int64_t, int64_t);

}  // namespace shadowref
