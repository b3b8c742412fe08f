// Frames of one scene at one thread and at more, in turn in one process: how shadowref's own
// speed-up from more threads is measured (`shadowref bench --alternate`, bench/vs-mesa). Timed in
// separate processes minutes apart, two thread counts meet different hosts (a shared host's speed
// drifts within minutes); frame by frame in one process they meet the same.
#pragma once

#include <functional>

#include "shadow/frame_renderer.h"

namespace shadowref {

struct FramesInTurn {
  int threads = 2;     // the count set against one thread: 2 or more
  int warmUp = 1;      // untimed frames at each count first: buffers and code paged in
  int frames = 10;     // timed frames at each count
};

// Renders `warmUp` frames at turn.threads and at one thread, then frame k at turn.threads for even
// k and at one thread for odd k, 2 * frames in all, calling onFrame(threads, frame, wall ms) after
// each timed one. The pool's workers stay awake through the one-thread frames, as they do in a
// stream of frames at turn.threads: asleep, the first frames after each switch would time their
// waking, and an awake worker does not slow the one-thread frames. One frame is alive at a time.
// Throws std::invalid_argument for threads < 2.
void renderFramesInTurn(const Scene& scene, FrameOptions options, const FramesInTurn& turn,
                        const std::function<void(int threads, const FrameResult& frame, double ms)>& onFrame);

}  // namespace shadowref
