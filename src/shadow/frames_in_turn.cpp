#include "shadow/frames_in_turn.h"

#include <chrono>
#include <stdexcept>

#include "exec/thread_pool.h"

namespace shadowref {

namespace {
// Keeps a pool's workers awake for as long as it lives.
class AwakePool {
 public:
  explicit AwakePool(ThreadPool& pool) : pool_(pool) { pool_.keepAwake(true); }
  ~AwakePool() { pool_.keepAwake(false); }
  AwakePool(const AwakePool&) = delete;
  AwakePool& operator=(const AwakePool&) = delete;

 private:
  ThreadPool& pool_;
};
}  // namespace

void renderFramesInTurn(const Scene& scene, FrameOptions options, const FramesInTurn& turn,
                        const std::function<void(int threads, const FrameResult& frame, double ms)>& onFrame) {
  if (turn.threads < 2) throw std::invalid_argument("frames in turn need 2 or more threads against one");
  // The pool renderFrame's renderers take at turn.threads on this thread.
  const AwakePool awake(*threadPoolForThisThread(turn.threads));
  for (int w = 0; w < turn.warmUp; ++w)
    for (const int t : {turn.threads, 1}) {
      options.threads = t;
      renderFrame(scene, options);
    }
  for (int i = 0; i < 2 * turn.frames; ++i) {
    options.threads = i % 2 == 0 ? turn.threads : 1;
    const auto start = std::chrono::steady_clock::now();
    const FrameResult frame = renderFrame(scene, options);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    onFrame(options.threads, frame, ms);
  }
}

}  // namespace shadowref
