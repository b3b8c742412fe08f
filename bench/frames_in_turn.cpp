#include "frames_in_turn.h"

#include <chrono>
#include <stdexcept>

#include "exec/fast_pipeline.h"
#include "exec/thread_pool.h"
#include "pool_runs.h"

namespace shadowref::bench {

void renderFramesInTurn(const Scene& scene, FrameOptions options, const FramesInTurn& turn,
                        const std::function<void(int threads, const FrameResult& frame, double ms)>& onFrame) {
  if (turn.threads < 2) throw std::invalid_argument("frames in turn need 2 or more threads against one");
  // The pipelines at turn.threads share one pool, kept from frame to frame.
  const FastPipelineMaker many(turn.threads), one(1);
  ThreadPool& pool = *many.pool();
  const auto render = [&](int threads) {
    options.threads = threads;
    options.pipelines = threads > 1 ? &many : &one;
    if (threads > 1) wakeWorkers(pool);
    return renderFrame(scene, options);
  };
  for (int w = 0; w < turn.warmUp; ++w)
    for (const int t : {turn.threads, 1}) render(t);
  for (int i = 0; i < 2 * turn.frames; ++i) {
    const int threads = i % 2 == 0 ? turn.threads : 1;
    options.threads = threads;
    options.pipelines = threads > 1 ? &many : &one;
    if (threads > 1) wakeWorkers(pool);
    const auto start = std::chrono::steady_clock::now();
    const FrameResult frame = renderFrame(scene, options);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    onFrame(threads, frame, ms);
  }
}

}  // namespace shadowref::bench
