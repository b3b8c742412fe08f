// The one boundary between the shadow algorithms and a pipeline that renders their draws. Two
// pipelines stand behind it: the reference (reference_pipeline.h, this folder: scalar, one
// thread, one function per GL operation), which defines every byte, and the fast executor
// (src/exec), which must reproduce those bytes for any thread count. The algorithms, the command
// and the tests of algorithms see only this header; they pick a pipeline by its kind.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include "gl/accumulation.h"
#include "gl/clear.h"
#include "gl/fragment_observer.h"
#include "gl/fragment_shader.h"
#include "gl/framebuffer.h"
#include "gl/raster_stats.h"
#include "gl/render_state.h"
#include "gl/vertex.h"

namespace shadowref {

enum class PipelineKind : uint8_t { Reference, Fast };
const char* name(PipelineKind kind);

// One glDrawElements of triangles given in clip space ([GL 2.1, §2.8, §2.11]).
struct DrawCall {
  const RenderState* state = nullptr;
  std::span<const ClipVertex> vertices;
  // Three indices per triangle; empty means vertices [3i, 3i+1, 3i+2] form triangle i.
  std::span<const uint32_t> indices;
  // nullptr draws no colour at all (stencil/depth-only passes).
  const FragmentShader* shader = nullptr;
  uint32_t tag = 0;  // reported in the pixel history
};

// The draw contract. A pass is what is drawn between two ends of a pass: endPass(),
// framebuffer(), accumulate(), or the pipeline's destruction end it.
//  - A draw borrows its state, vertices, indices and shader until the end of its pass: the caller
//    neither changes nor frees them before. The pipeline may render the draw at once or at the
//    end of the pass; the bytes are the same.
//  - Clears and draws take effect in the order they were made.
//  - The framebuffer is read or written by other means only through framebuffer(), which ends
//    the pass first.
//  - stats() counts every draw of the passes ended so far.
class Pipeline {
 public:
  virtual ~Pipeline() = default;

  virtual PipelineKind kind() const = 0;
  // The threads it renders with (the reference: always 1).
  virtual int threads() const = 0;

  // glClear (clear.h), in its place among the draws.
  virtual void clear(const ClearRequest& request) = 0;
  virtual void draw(const DrawCall& call) = 0;
  // glAccum (accumulation.h) with the scissor box of `state`; ends the pass first.
  virtual void accumulate(const RenderState& state, AccumOp op, float value) = 0;
  // Every draw and clear made so far has reached the framebuffer; what they borrowed is free.
  virtual void endPass() = 0;
  // Ends the pass and gives the buffers.
  virtual Framebuffer& framebuffer() = 0;

  virtual const RasterStats& stats() const = 0;
  virtual void resetStats() = 0;
  // Reports every fragment at pixel (x, y) to the observer from the next draw on (nullptr stops).
  virtual void watchPixel(int x, int y, FragmentObserver* observer) = 0;

  // Runs task(i) for every i in [0, count) and returns when all are done: independent work between
  // draws (each caster's volume). The tasks must not draw; the reference runs them in order.
  virtual void forEachIndependent(int count, const std::function<void(int)>& task) = 0;

  // A pipeline of the same kind and thread count drawing into another framebuffer (a shadow map).
  virtual std::unique_ptr<Pipeline> forFramebuffer(Framebuffer& fb) const = 0;
};

// Makes pipelines of one kind and thread count, framebuffer after framebuffer. What the pipelines
// run on belongs to the maker and to the pipelines it made (the fast executor's thread pool, shared
// by them): a program rendering frame after frame from one maker starts its threads once, not per
// frame. Its pipelines are used from one thread, one pass at a time (a frame's passes and its
// shadow maps' interleave but never run at once).
class PipelineMaker {
 public:
  virtual ~PipelineMaker() = default;
  virtual PipelineKind kind() const = 0;
  virtual int threads() const = 0;
  virtual std::unique_ptr<Pipeline> make(Framebuffer& fb) const = 0;
};

// The maker of pipelines of that kind (threads: the fast executor's, 0 for every core; the
// reference ignores it).
std::unique_ptr<PipelineMaker> makePipelineMaker(PipelineKind kind, int threads = 1);
// One pipeline of that kind drawing into `fb`, with threads of its own (makePipelineMaker's).
std::unique_ptr<Pipeline> makePipeline(PipelineKind kind, Framebuffer& fb, int threads = 1);
// The threads() of a pipeline that makePipeline(kind, fb, threads) makes, without making one.
int pipelineThreads(PipelineKind kind, int threads);

}  // namespace shadowref
