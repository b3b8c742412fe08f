#include "gl/reference_pipeline.h"

#include "gl/per_fragment.h"

namespace shadowref {

void ReferencePipeline::clear(const ClearRequest& request) { shadowref::clear(fb_, request); }

void ReferencePipeline::draw(const DrawCall& call) {
  const RenderState& state = *call.state;
  ensureBuffersFor(fb_, call);

  ++stats_.drawCalls;
  watch_.drawIndex = drawCount_++;
  watch_.drawTag = call.tag;
  watch_.hasColor = fb_.hasColor();
  watch_.hasDepth = fb_.hasDepth();
  watch_.hasStencil = fb_.hasStencil();
  const size_t triangles = trianglesOf(call);
  stats_.trianglesIn += triangles;
  checkIndices(call);  // throws before any triangle of the draw is drawn

  const ClipPlanes planes = clipPlanesFor(state);
  const int varyingCount = call.shader ? call.shader->varyingCount() : 0;
  const Rect region = drawRegion(state, fb_);
  const BufferUse use = bufferUse(fb_, state, call.shader);
  // Triangle after triangle, each whole before the next ([GL 2.1, §2.6]: primitives are drawn in
  // the order given); a clipped triangle's fan pieces in fan order.
  for (size_t i = 0; i < triangles; ++i) {
    const ClipVertex* v[3];
    triangleVertices(call, i, v);
    assembleTriangle(v[0], v[1], v[2], state, planes, varyingCount, fb_.depthCodec(), scratch_, setups_, stats_);
    for (const TriangleSetup& t : setups_) {
      coveredPixels(t, region, covered_);
      for (const CoveredPixel& p : covered_) processFragment(fb_, state, call.shader, use, t, p, stats_, &watch_);
    }
  }
}

void ReferencePipeline::accumulate(const RenderState& state, AccumOp op, float value) {
  shadowref::accumulate(fb_, state, op, value);
}

void ReferencePipeline::watchPixel(int x, int y, FragmentObserver* observer) {
  watch_.x = x;
  watch_.y = y;
  watch_.observer = observer;
}

void ReferencePipeline::forEachIndependent(int count, const std::function<void(int)>& task) {
  for (int i = 0; i < count; ++i) task(i);
}

std::unique_ptr<Pipeline> ReferencePipeline::forFramebuffer(Framebuffer& fb) const {
  return std::make_unique<ReferencePipeline>(fb);
}

}  // namespace shadowref
