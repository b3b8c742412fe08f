// frames_in_turn.h: frames at more threads and at one in turn, as thread_profile --alternate and
// vs_mesa time them.
#include "frames_in_turn.h"

#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "identical_frames.h"
#include "scene/scene_loader.h"

namespace shadowref::bench {
namespace {

Scene smallRoom() {
  LoadOptions options;
  options.overrides = {"shadow.method=zfail", "image.width=160", "image.height=128"};
  return loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/room.yaml", options);
}

TEST_CASE("frames in turn alternate the thread counts, each frame the one-thread frame's bytes", "[bench]") {
  const Scene scene = smallRoom();
  FrameOptions options;
  options.threads = 1;
  const FrameResult reference = renderFrame(scene, options);
  std::vector<int> threads;
  renderFramesInTurn(scene, options, {.threads = 3, .warmUp = 2, .frames = 3},
                     [&](int t, const FrameResult& frame, double ms) {
                       threads.push_back(t);
                       CHECK(ms > 0.0);
                       CHECK(identicalFrames(reference.framebuffer, frame.framebuffer));
                     });
  // Only the timed frames are reported: the warm-up's four are not.
  CHECK(threads == std::vector<int>{3, 1, 3, 1, 3, 1});
}

TEST_CASE("frames in turn need two or more threads against one", "[bench]") {
  const Scene scene = smallRoom();
  int frames = 0;
  CHECK_THROWS_AS(renderFramesInTurn(scene, FrameOptions{}, {.threads = 1}, [&](int, const FrameResult&, double) { ++frames; }),
                  std::invalid_argument);
  CHECK(frames == 0);
}

}  // namespace
}  // namespace shadowref::bench
