#include "gl/reference_pipeline.h"

#include "gl/per_fragment.h"

namespace shadowref {

void ReferencePipeline::clear(const ClearRequest& request) {
  // The pixel history sees a clear of the watched pixel with what its buffers held before and after.
  const bool watched = watch_.observer && watch_.x >= 0 && watch_.y >= 0 && watch_.x < fb_.width() &&
                       watch_.y < fb_.height();
  ClearEvent event;
  const size_t at = watched ? fb_.index(watch_.x, watch_.y) : 0;
  if (watched) {
    event.x = watch_.x;
    event.y = watch_.y;
    event.color = request.color.has_value();
    if (request.stencil && fb_.hasStencil()) event.stencilBefore = fb_.stencil()[at];
    if (request.depth && fb_.hasDepth()) event.depthBefore = fb_.depthCodec().decode(fb_.depthCodes()[at]);
  }
  shadowref::clear(fb_, request);
  if (!watched) return;
  const Rect region = clearRegion(fb_, request.state);
  if (watch_.x < region.x || watch_.x >= region.x + region.width || watch_.y < region.y ||
      watch_.y >= region.y + region.height)
    return;
  if (request.stencil) {
    if (!event.stencilBefore) event.stencilBefore = 0;  // a buffer this clear makes held nothing: 0
    event.stencilAfter = fb_.stencil()[at];
  }
  if (request.depth) {
    if (!event.depthBefore) event.depthBefore = 1.0;  // likewise: the far end
    event.depthAfter = fb_.depthCodec().decode(fb_.depthCodes()[at]);
  }
  watch_.observer->onClear(event);
}

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
