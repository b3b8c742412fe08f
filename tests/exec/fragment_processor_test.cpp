// The fragment path of a draw: GL order of the tests, the face-dependent stencil state, what a
// disabled test does, and perspective-correct varyings at the pixel centre.
#include <array>
#include <map>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/clear.h"
#include "gl/projection.h"
#include "exec/renderer.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

std::vector<ClipVertex> reversed(std::vector<ClipVertex> triangles) {
  for (size_t i = 0; i + 2 < triangles.size(); i += 3) std::swap(triangles[i + 1], triangles[i + 2]);
  return triangles;
}

// Left half of an 8x2 framebuffer drawn counter-clockwise, right half clockwise, in one draw.
std::string twoSidedPicture(FrontFace frontFace, const StencilFaceState& front, const StencilFaceState& back) {
  Framebuffer fb(8, 2);
  RenderState s = fullViewportState(fb);
  s.stencilTest = true;
  s.frontFace = frontFace;
  s.stencil[FrontFacing] = front;
  s.stencil[BackFacing] = back;
  clearStencil(fb, s, 4);
  std::vector<ClipVertex> v = windowRect(s.viewport, 0, 0, 4, 2);
  const std::vector<ClipVertex> cw = reversed(windowRect(s.viewport, 4, 0, 8, 2));
  v.insert(v.end(), cw.begin(), cw.end());
  Renderer r(fb);
  draw(r, s, v);
  return stencilPicture(fb);
}

}  // namespace

TEST_CASE("two-sided stencil: counter-clockwise triangles use the front state when front face is CCW",
          "[raster][stencil]") {
  StencilFaceState front, back;
  front.dppass = StencilOp::Incr;  // 4 -> 5
  back.dppass = StencilOp::Decr;   // 4 -> 3
  CHECK(twoSidedPicture(FrontFace::CCW, front, back) == rows({"55553333", "55553333"}));
}

TEST_CASE("two-sided stencil: with front face CW the clockwise triangles use the front state",
          "[raster][stencil]") {
  StencilFaceState front, back;
  front.dppass = StencilOp::Incr;
  back.dppass = StencilOp::Decr;
  CHECK(twoSidedPicture(FrontFace::CW, front, back) == rows({"33335555", "33335555"}));
}

TEST_CASE("two-sided stencil: func, ref, masks and every path come from the facing's state", "[raster][stencil]") {
  // Stored 4 everywhere. Front: test NEVER, sfail REPLACE with the front ref 7.
  const StencilFaceState front{CompareFunc::Never, 7, 0xFF, 0xFF, StencilOp::Replace, StencilOp::Keep,
                               StencilOp::Keep};
  // Back: ref 0x19 through mask 0x0F is 9 >= 4, so GEQUAL passes; dppass REPLACE writes 0x19 through
  // write mask 0x0F: (4 & 0xF0) | (0x19 & 0x0F) = 9.
  const StencilFaceState back{CompareFunc::GEqual, 0x19, 0x0F, 0x0F, StencilOp::Keep, StencilOp::Keep,
                              StencilOp::Replace};
  CHECK(twoSidedPicture(FrontFace::CCW, front, back) == rows({"77779999", "77779999"}));
  CHECK(twoSidedPicture(FrontFace::CW, front, back) == rows({"99997777", "99997777"}));
}

TEST_CASE("stencil test disabled: the stencil buffer is neither tested nor updated", "[raster][stencil]") {
  Framebuffer fb(4, 1);
  RenderState s = fullViewportState(fb);
  clearStencil(fb, s, 5);
  s.stencilTest = false;
  s.stencil[FrontFacing] = {CompareFunc::Never, 1, 0xFF, 0xFF, StencilOp::Zero, StencilOp::Zero, StencilOp::Zero};
  Renderer r(fb);
  const ConstantColorShader white({1.0, 1.0, 1.0, 1.0});
  draw(r, s, windowRect(s.viewport, 0, 0, 4, 1), &white);
  CHECK(stencilPicture(fb) == "5555");
  CHECK(fb.colorAt(3, 0) == glm::vec4(1.0f));  // NEVER was not applied either
}

TEST_CASE("depth test disabled: the dppass op applies and depth is not written", "[raster][depth]") {
  Framebuffer fb(4, 1);
  RenderState s = fullViewportState(fb);
  clearDepth(fb, s, 0.25);
  s.stencilTest = true;
  s.stencil[FrontFacing] = {CompareFunc::Always, 3, 0xFF, 0xFF, StencilOp::Keep, StencilOp::Zero, StencilOp::Replace};
  s.depthTest = false;
  s.depthFunc = CompareFunc::Never;  // would fail every fragment if it were consulted
  Renderer r(fb);
  draw(r, s, windowRect(s.viewport, 0, 0, 4, 1, 0.75));
  CHECK(stencilPicture(fb) == "3333");
  for (int x = 0; x < 4; ++x) CHECK(fb.depthAt(x, 0) == 0.25);
}

TEST_CASE("a stencil-failed fragment is not depth tested and does not write depth or colour", "[raster][stencil]") {
  Framebuffer fb(2, 1);
  RenderState s = fullViewportState(fb);
  clearDepth(fb, s, 1.0);
  clearColor(fb, s, glm::vec4(0.0f));
  s.stencilTest = true;
  s.stencil[FrontFacing] = {CompareFunc::Never, 0, 0xFF, 0xFF, StencilOp::Incr, StencilOp::Replace, StencilOp::Replace};
  s.depthTest = true;
  s.depthFunc = CompareFunc::Always;
  Renderer r(fb);
  const ConstantColorShader white({1.0, 1.0, 1.0, 1.0});
  draw(r, s, windowRect(s.viewport, 0, 0, 2, 1, 0.5), &white);
  CHECK(stencilPicture(fb) == "11");
  CHECK(fb.depthAt(0, 0) == 1.0);
  CHECK(fb.colorAt(0, 0) == glm::vec4(0.0f));
}

// ---------------------------------------------------------------------------------------------
// Perspective-correct varyings ([GL 2.1, §3.5.1, eq. 3.6]).

namespace {

class VaryingCapture final : public FragmentShader {
 public:
  int varyingCount() const override { return 3; }
  glm::dvec4 shade(const FragmentInput& in) const override {
    captured[{in.x, in.y}] = {in.varyings[0], in.varyings[1], in.varyings[2]};
    return glm::dvec4(1.0);
  }
  mutable std::map<std::pair<int, int>, std::array<double, 3>> captured;
};

}  // namespace

TEST_CASE("varyings on a slanted quad equal the analytic perspective-correct values", "[raster][interpolation]") {
  // Eye space, glFrustum(-1, 1, -1, 1, 1, 100): clip x = x_eye, y = y_eye, w = -z_eye.
  // The quad P0 (-0.5, -0.5, -1), P1 (0.5, -0.5, -1), P2 (2, 2, -4), P3 (-2, 2, -4) lies in the plane
  // y = -0.5 - (5/6)(z + 1) and projects to the window square [8, 24]^2 of a 32x32 viewport.
  // Varyings are affine functions of the eye position, as texture coordinates of a planar mapping
  // are: u = (x + 2) / 4, v = (-z - 1) / 3, and x itself.
  Framebuffer fb(32, 32);
  RenderState s = fullViewportState(fb);
  const glm::dmat4 projection = frustum(-1, 1, -1, 1, 1, 100);
  const glm::dvec3 eye[4] = {{-0.5, -0.5, -1}, {0.5, -0.5, -1}, {2, 2, -4}, {-2, 2, -4}};
  std::vector<ClipVertex> quad(4);
  for (int i = 0; i < 4; ++i) {
    quad[i].position = projection * glm::dvec4(eye[i], 1.0);
    quad[i].varyings[0] = (eye[i].x + 2.0) / 4.0;
    quad[i].varyings[1] = (-eye[i].z - 1.0) / 3.0;
    quad[i].varyings[2] = eye[i].x;
  }
  const std::vector<ClipVertex> triangles{quad[0], quad[1], quad[2], quad[0], quad[2], quad[3]};
  VaryingCapture capture;
  Renderer r(fb);
  draw(r, s, triangles, &capture);

  REQUIRE(capture.captured.size() == 16 * 16);
  for (int py = 8; py < 24; ++py) {
    for (int px = 8; px < 24; ++px) {
      // The eye ray through the pixel centre, (xn, yn, -1) t, meets the plane at
      // t = (4/3) / (5/6 - yn), the eye point (t xn, t yn, -t).
      const double xn = (px + 0.5) / 16.0 - 1.0, yn = (py + 0.5) / 16.0 - 1.0;
      const double t = (4.0 / 3.0) / (5.0 / 6.0 - yn);
      const std::array<double, 3> expected{(t * xn + 2.0) / 4.0, (t - 1.0) / 3.0, t * xn};
      const std::array<double, 3>& got = capture.captured.at({px, py});
      INFO("pixel " << px << "," << py);
      for (int k = 0; k < 3; ++k) CHECK(got[k] == Approx(expected[k]).margin(1e-9).epsilon(0));
    }
  }
}
