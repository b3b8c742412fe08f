#include "exec/fast_pipeline.h"

namespace shadowref {

FastPipeline::FastPipeline(Framebuffer& fb, int threads) : renderer_(fb, threads) {}

FastPipeline::FastPipeline(Framebuffer& fb, std::shared_ptr<ThreadPool> pool) : renderer_(fb, std::move(pool)) {}

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

// Ends the pass first: the bands render a pass's draws at once, each band on its thread, so the
// draws watching one pixel and those watching another would report from two threads at once and
// out of draw order; within a pass, every watched fragment is in the one band of its pixel.
void FastPipeline::watchPixel(int x, int y, FragmentObserver* observer) {
  endPass();
  renderer_.watchPixel(x, y, observer);
}

void FastPipeline::forEachIndependent(int count, const std::function<void(int)>& task) {
  renderer_.parallelFor(count, task);
}

// The shadow maps' pipelines share the frame's pool: they run between its passes, never with them.
std::unique_ptr<Pipeline> FastPipeline::forFramebuffer(Framebuffer& fb) const {
  return std::make_unique<FastPipeline>(fb, renderer_.pool());
}

FastPipelineMaker::FastPipelineMaker(int threads) : pool_(makeThreadPool(threads > 0 ? threads : defaultThreadCount())) {}

std::unique_ptr<Pipeline> FastPipelineMaker::make(Framebuffer& fb) const {
  return std::make_unique<FastPipeline>(fb, pool_);
}

}  // namespace shadowref
