// makePipeline (gl/pipeline.h): the one place that knows both pipelines' types, so that the
// algorithms and the command include neither.
#include "exec/fast_pipeline.h"
#include "exec/thread_pool.h"
#include "gl/pipeline.h"
#include "gl/reference_pipeline.h"

namespace shadowref {

const char* name(PipelineKind kind) { return kind == PipelineKind::Reference ? "reference" : "fast"; }

namespace {
class ReferencePipelineMaker final : public PipelineMaker {
 public:
  PipelineKind kind() const override { return PipelineKind::Reference; }
  int threads() const override { return 1; }
  std::unique_ptr<Pipeline> make(Framebuffer& fb) const override { return std::make_unique<ReferencePipeline>(fb); }
};
}  // namespace

std::unique_ptr<PipelineMaker> makePipelineMaker(PipelineKind kind, int threads) {
  switch (kind) {
    case PipelineKind::Fast:
      return std::make_unique<FastPipelineMaker>(threads);
    case PipelineKind::Reference:
      return std::make_unique<ReferencePipelineMaker>();
  }
  return nullptr;
}

std::unique_ptr<Pipeline> makePipeline(PipelineKind kind, Framebuffer& fb, int threads) {
  switch (kind) {
    case PipelineKind::Fast:
      return std::make_unique<FastPipeline>(fb, threads);
    case PipelineKind::Reference:
      return std::make_unique<ReferencePipeline>(fb);
  }
  return nullptr;
}

int pipelineThreads(PipelineKind kind, int threads) {
  if (kind == PipelineKind::Reference) return 1;
  return threads > 0 ? threads : defaultThreadCount();
}

}  // namespace shadowref
