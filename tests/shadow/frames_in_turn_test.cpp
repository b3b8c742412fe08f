// renderFramesInTurn (shadow/frames_in_turn.h): frames at more threads and at one in turn, as
// `shadowref bench --alternate` and bench/vs-mesa time them.
#include <catch2/catch.hpp>

#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "exec/thread_pool.h"
#include "shadow/frames_in_turn.h"
#include "support/frame_compare.h"
#include "support/generated_scene.h"

using namespace shadowref;
using shadowref::testing::requireIdenticalFrames;

TEST_CASE("frames in turn alternate the thread counts, each frame the one-thread frame's bytes", "[determinism]") {
  const Scene scene = shadowref::testing::generatedScene("room", "zfail", 160, 128);
  FrameOptions options;
  options.threads = 1;
  const FrameResult reference = renderFrame(scene, options);
  std::vector<int> threads;
  renderFramesInTurn(scene, options, {.threads = 3, .warmUp = 2, .frames = 3},
                     [&](int t, const FrameResult& frame, double ms) {
                       threads.push_back(t);
                       CHECK(ms > 0.0);
                       requireIdenticalFrames(reference, frame);
                     });
  // Only the timed frames are reported: the warm-up's four are not.
  CHECK(threads == std::vector<int>{3, 1, 3, 1, 3, 1});
}

TEST_CASE("frames in turn keep the workers awake, and release them after", "[determinism]") {
  const Scene scene = shadowref::testing::generatedScene("room", "zfail", 64, 48);
  ThreadPool& pool = *threadPoolForThisThread(2);
  renderFramesInTurn(scene, FrameOptions{}, {.threads = 2, .warmUp = 0, .frames = 2}, [&](int t, const FrameResult&, double) {
    if (t != 1) return;
    // A one-thread frame has just run without the pool: its worker kept spinning through it.
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // longer than a worker's spin
    CHECK(pool.sleepingWorkers() == 0);
  });
  // Released: the worker falls asleep after its spin (3 ms).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (pool.sleepingWorkers() == 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  CHECK(pool.sleepingWorkers() == 1);
}

TEST_CASE("frames in turn need two or more threads against one", "[determinism]") {
  const Scene scene = shadowref::testing::generatedScene("room", "zfail", 64, 48);
  int frames = 0;
  CHECK_THROWS_AS(renderFramesInTurn(scene, FrameOptions{}, {.threads = 1}, [&](int, const FrameResult&, double) { ++frames; }),
                  std::invalid_argument);
  CHECK(frames == 0);
}
