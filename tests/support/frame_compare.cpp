#include "support/frame_compare.h"

#include <cstring>

#include <catch2/catch.hpp>

namespace shadowref::testing {

namespace {
bool sameBytes(const PixelVector<glm::vec4>& a, const PixelVector<glm::vec4>& b) {
  if (a.size() != b.size()) return false;
  return a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0;
}
}  // namespace

void requireIdenticalFrames(const FrameResult& a, const FrameResult& b) {
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
  CHECK(a.stats.stencilFailed == b.stats.stencilFailed);
  CHECK(a.stats.depthFailed == b.stats.depthFailed);
  CHECK(a.stats.colorWrites == b.stats.colorWrites);
}

}  // namespace shadowref::testing
