// Frames of one scene at one thread and at more, in turn in one process: how shadowref's own
// speed-up from more threads is measured (thread_profile --alternate, vs_mesa). Timed in separate
// processes minutes apart, two thread counts meet different hosts (a shared host's speed drifts
// within minutes); frame by frame in one process they meet the same.
#pragma once

#include <functional>

#include "shadow/frame_renderer.h"

namespace shadowref::bench {

struct FramesInTurn {
  int threads = 2;     // the count set against one thread: 2 or more
  int warmUp = 1;      // untimed frames at each count first: buffers and code paged in
  int frames = 10;     // timed frames at each count
};

// Renders `warmUp` frames at turn.threads and at one thread, then frame k at turn.threads for even
// k and at one thread for odd k, 2 * frames in all, calling onFrame(threads, frame, wall ms) after
// each timed one. Before each frame at turn.threads, untimed, the pool's workers are woken
// (wakeWorkers), as they are awake in a stream of frames at turn.threads: asleep after a frame at
// one thread, the frame would time their waking. One frame is alive at a time.
// Throws std::invalid_argument for threads < 2.
void renderFramesInTurn(const Scene& scene, FrameOptions options, const FramesInTurn& turn,
                        const std::function<void(int threads, const FrameResult& frame, double ms)>& onFrame);

}  // namespace shadowref::bench
