// The fast executor behind the Pipeline interface (gl/pipeline.h): every pass is recorded and
// rendered when it ends, on the executor's threads (Renderer, DeferredDraws). It has no GL
// semantics of its own; the bytes are the reference pipeline's.
#pragma once

#include <memory>
#include <optional>

#include "exec/renderer.h"
#include "gl/pipeline.h"

namespace shadowref {

class FastPipeline final : public Pipeline {
 public:
  // With a pool of its own of `threads` threads (0: all cores).
  FastPipeline(Framebuffer& fb, int threads);
  // With `pool`'s threads (nullptr: one thread), shared with the pipelines that made it or that it
  // makes (forFramebuffer, FastPipelineMaker).
  FastPipeline(Framebuffer& fb, std::shared_ptr<ThreadPool> pool);
  ~FastPipeline() override;

  PipelineKind kind() const override { return PipelineKind::Fast; }
  int threads() const override { return renderer_.threads(); }

  void clear(const ClearRequest& request) override;
  void draw(const DrawCall& call) override;
  void accumulate(const RenderState& state, AccumOp op, float value) override;
  void endPass() override;
  Framebuffer& framebuffer() override;

  const RasterStats& stats() const override { return renderer_.stats(); }
  void resetStats() override { renderer_.resetStats(); }
  void watchPixel(int x, int y, FragmentObserver* observer) override;
  void forEachIndependent(int count, const std::function<void(int)>& task) override;
  std::unique_ptr<Pipeline> forFramebuffer(Framebuffer& fb) const override;

  // The renderer underneath, for the executor's own tests.
  Renderer& renderer() { return renderer_; }

 private:
  void beginPass();

  Renderer renderer_;
  // Open from a pass's first draw or clear to its end: the draws borrow their geometry until then
  // (the draw contract), so they are assembled and rasterized together when it ends.
  std::optional<DeferredDraws> pass_;
};

// The fast executor's PipelineMaker: its pipelines share the pool it owns.
class FastPipelineMaker final : public PipelineMaker {
 public:
  explicit FastPipelineMaker(int threads);
  PipelineKind kind() const override { return PipelineKind::Fast; }
  int threads() const override { return pool_ ? pool_->threadCount() : 1; }
  std::unique_ptr<Pipeline> make(Framebuffer& fb) const override;
  // The pool its pipelines render with (nullptr: one thread), for watching its runs (bench).
  ThreadPool* pool() const { return pool_.get(); }

 private:
  std::shared_ptr<ThreadPool> pool_;
};

}  // namespace shadowref
