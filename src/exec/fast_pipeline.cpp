#include "exec/fast_pipeline.h"

namespace shadowref {

FastPipeline::FastPipeline(Framebuffer& fb, int threads) : renderer_(fb, threads) {}

FastPipeline::~FastPipeline() { endPass(); }

void FastPipeline::beginPass() {
  if (!pass_) pass_.emplace(renderer_, DeferredDraws::Geometry::Kept);
}

void FastPipeline::clear(const ClearRequest& request) {
  beginPass();
  renderer_.clear(request);
}

void FastPipeline::draw(const DrawCall& call) {
  beginPass();
  renderer_.draw(call);
}

void FastPipeline::accumulate(const RenderState& state, AccumOp op, float value) {
  shadowref::accumulate(framebuffer(), state, op, value);
}

void FastPipeline::endPass() { pass_.reset(); }

Framebuffer& FastPipeline::framebuffer() {
  endPass();
  return renderer_.framebuffer();
}

void FastPipeline::forEachIndependent(int count, const std::function<void(int)>& task) {
  renderer_.parallelFor(count, task);
}

std::unique_ptr<Pipeline> FastPipeline::forFramebuffer(Framebuffer& fb) const {
  return std::make_unique<FastPipeline>(fb, threads());
}

}  // namespace shadowref
