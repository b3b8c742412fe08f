// The reference pipeline: GL 2.1 semantics, scalar, one thread, every draw rendered at once in the
// order it was made. It defines every byte the fast executor (src/exec) must reproduce. Read the
// stages in the order a triangle meets them:
//   vertex_stage.h        clip coordinates (done by the caller: a draw is given in clip space)
//   primitive_assembly.h  indices -> triangles, clipping (clipper.h), facing, culling, the fan
//   triangle_setup.h      viewport, snapping, edge functions and the top-left rule, depth plane
//   coverage.h            which pixel centres a triangle covers
//   fragment_stage.h      depth and varyings at the centre, shading
//   per_fragment.h        scissor, stencil, depth, stencil update, blend, masked writes in order
//                         (each operation one function of fragment_ops.h)
//   clear.h, accumulation.h  glClear and glAccum
#pragma once

#include <vector>

#include "gl/coverage.h"
#include "gl/fragment_observer.h"
#include "gl/pipeline.h"
#include "gl/primitive_assembly.h"

namespace shadowref {

class ReferencePipeline final : public Pipeline {
 public:
  explicit ReferencePipeline(Framebuffer& fb) : fb_(fb) {}

  PipelineKind kind() const override { return PipelineKind::Reference; }
  int threads() const override { return 1; }

  void clear(const ClearRequest& request) override;
  void draw(const DrawCall& call) override;
  void accumulate(const RenderState& state, AccumOp op, float value) override;
  void endPass() override {}  // every draw is done when draw() returns
  Framebuffer& framebuffer() override { return fb_; }

  const RasterStats& stats() const override { return stats_; }
  void resetStats() override { stats_ = {}; }
  void watchPixel(int x, int y, FragmentObserver* observer) override;
  void forEachIndependent(int count, const std::function<void(int)>& task) override;
  std::unique_ptr<Pipeline> forFramebuffer(Framebuffer& fb) const override;

 private:
  Framebuffer& fb_;
  RasterStats stats_;
  PixelWatch watch_;
  uint64_t drawCount_ = 0;  // the pixel history's draw index: this pipeline's draws so far
  // Scratch kept from draw to draw so that a draw does not allocate per triangle.
  AssemblyScratch scratch_;
  std::vector<TriangleSetup> setups_;
  std::vector<CoveredPixel> covered_;
};

}  // namespace shadowref
