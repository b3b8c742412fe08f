// Determinism: the same scene gives the same bytes in every buffer, on every run and
// for any thread count.
#include <catch2/catch.hpp>

#include "shadow/frame_renderer.h"
#include "support/frame_compare.h"
#include "support/generated_scene.h"

using namespace shadowref;
using shadowref::testing::requireIdenticalFrames;

namespace {

Scene smallScene(const std::string& generator, const std::string& method) {
#if defined(__SANITIZE_ADDRESS__)
  return shadowref::testing::generatedScene(generator, method, 160, 128);
#else
  return shadowref::testing::generatedScene(generator, method, 320, 256);
#endif
}

FrameResult render(const Scene& scene, int threads) {
  FrameOptions options;
  options.threads = threads;
  options.keepStencil = true;
  return renderFrame(scene, options);
}

}  // namespace

TEST_CASE("every buffer is byte-identical for 1, 2 and 8 threads and on a second run", "[determinism]") {
  const auto [generator, method] = GENERATE(table<std::string, std::string>({
      {"room", "zfail"}, {"room", "zpass"}, {"pumpkins", "auto"}, {"city", "zfail"}, {"outdoor", "shadowmap"},
      {"outdoor", "tsm"}, {"room", "none"}}));
  INFO(generator << " with " << method);
  const Scene scene = smallScene(generator, method);
  const FrameResult one = render(scene, 1);
  REQUIRE(one.framebuffer.hasColor());
  requireIdenticalFrames(one, render(scene, 1));
  requireIdenticalFrames(one, render(scene, 2));
  requireIdenticalFrames(one, render(scene, 8));
}
