// Determinism (SPEC.md §1): the same scene gives the same bytes in every buffer, on every run and
// for any thread count.
#include <catch2/catch.hpp>

#include <cstring>

#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"

using namespace shadowref;

namespace {

Scene smallScene(const std::string& generator, const std::string& method) {
  LoadOptions options;
#if defined(__SANITIZE_ADDRESS__)
  options.overrides = {"image.width=160", "image.height=128", "shadow.method=" + method};
#else
  options.overrides = {"image.width=320", "image.height=256", "shadow.method=" + method};
#endif
  return loadSceneFromString("generator: {type: " + generator + "}\n", "<determinism>", options);
}

FrameResult render(const Scene& scene, int threads) {
  FrameOptions options;
  options.threads = threads;
  options.keepStencil = true;
  return renderFrame(scene, options);
}

bool sameBytes(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
  if (a.size() != b.size()) return false;
  return a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0;
}

// Compares every buffer byte for byte (floats by their bits, not their values).
void requireIdentical(const FrameResult& a, const FrameResult& b) {
  const Framebuffer& fa = a.framebuffer;
  const Framebuffer& fb = b.framebuffer;
  REQUIRE(fa.hasColor() == fb.hasColor());
  REQUIRE(fa.hasDepth() == fb.hasDepth());
  REQUIRE(fa.hasStencil() == fb.hasStencil());
  REQUIRE(fa.hasAccum() == fb.hasAccum());
  CHECK(sameBytes(fa.color(), fb.color()));
  CHECK(fa.depthCodes() == fb.depthCodes());
  CHECK(fa.stencil() == fb.stencil());
  CHECK(sameBytes(fa.accum(), fb.accum()));
  CHECK(a.stencilPerLight == b.stencilPerLight);
  CHECK(a.stats.fragments == b.stats.fragments);
  CHECK(a.stats.stencilWrites == b.stats.stencilWrites);
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
  requireIdentical(one, render(scene, 1));
  requireIdentical(one, render(scene, 2));
  requireIdentical(one, render(scene, 8));
}
