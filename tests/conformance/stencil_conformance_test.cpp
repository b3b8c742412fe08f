// Stencil test and stencil update against Mesa: every func with ref/mask, every op on each of
// sfail / dpfail / dppass (saturation and wrap at 0 and 255), write mask, two-sided stencil, and
// triangle soups counted with INCR_WRAP.
#include "conformance/case_builder.h"

using namespace shadowref;
using namespace shadowref::conformance;

namespace {

constexpr int kSize = 64;
// Stored values that sit at the interesting places: 0 and 255 (wrap and saturation), 1 and 254
// next to them, and patterns that split under the masks used below.
constexpr int kStripeValues[8] = {0x00, 0x01, 0x0F, 0x7F, 0x80, 0xF0, 0xFE, 0xFF};

// Vertical stripes 4 pixels wide cycling through kStripeValues, by scissored clears.
void addStencilStripes(Scenario& sc) {
  for (int x = 0, i = 0; x < sc.width; x += 4, ++i) {
    ClearStep c;
    c.state = fullViewportState(sc.width, sc.height);
    c.state.scissorTest = true;
    c.state.scissor = Rect{x, 0, 4, sc.height};
    c.stencil = true;
    c.stencilValue = kStripeValues[i % 8];
    sc.steps.push_back(c);
  }
}

// Depth 0.5 on the left half, 1 elsewhere: a triangle at NDC z = 0.2 (window 0.6) fails the LESS
// test on the left and passes on the right, so dpfail and dppass both happen.
void addDepthSplit(Scenario& sc) {
  ClearStep c;
  c.state = fullViewportState(sc.width, sc.height);
  c.state.scissorTest = true;
  c.state.scissor = Rect{0, 0, sc.width / 2, sc.height};
  c.depth = true;
  c.depthValue = 0.5;
  sc.steps.push_back(c);
}

// Three overlapping triangles in the viewport, counter-clockwise, so ops apply up to three times.
void addOverlappingTriangles(DrawStep& d) {
  const Viewport& vp = d.state.viewport;
  const double x0 = vp.x, y0 = vp.y, w = vp.width, h = vp.height;
  addTriangle(d, {x0 + 0.1 * w, y0 + 0.1 * h, 0.2}, {x0 + 0.9 * w, y0 + 0.2 * h, 0.2}, {x0 + 0.5 * w, y0 + 0.9 * h, 0.2},
              {1, 0, 0, 1});
  addTriangle(d, {x0 + 0.05 * w, y0 + 0.6 * h, 0.2}, {x0 + 0.7 * w, y0 + 0.05 * h, 0.2},
              {x0 + 0.95 * w, y0 + 0.95 * h, 0.2}, {0, 1, 0, 1});
  addTriangle(d, {x0 + 0.3 * w, y0 + 0.02 * h, 0.2}, {x0 + 0.98 * w, y0 + 0.5 * h, 0.2},
              {x0 + 0.02 * w, y0 + 0.98 * h, 0.2}, {0, 0, 1, 1});
}

DrawStep quadrantDraw(int quadrant) {
  DrawStep d;
  d.state = fullViewportState(kSize, kSize);
  d.state.viewport = Viewport{(quadrant % 2) * kSize / 2, (quadrant / 2) * kSize / 2, kSize / 2, kSize / 2, 0.0, 1.0};
  return d;
}

const CompareFunc kFuncs[8] = {CompareFunc::Never,    CompareFunc::Less,    CompareFunc::Equal,
                               CompareFunc::LEqual,   CompareFunc::Greater, CompareFunc::NotEqual,
                               CompareFunc::GEqual,   CompareFunc::Always};
const StencilOp kOps[8] = {StencilOp::Keep,   StencilOp::Zero,   StencilOp::Replace,  StencilOp::Incr,
                           StencilOp::Decr,   StencilOp::Invert, StencilOp::IncrWrap, StencilOp::DecrWrap};

}  // namespace

TEST_CASE("each stencil func compares (ref & mask) with (stored & mask) as Mesa does, ref clamped to [0, 255]",
          "[conformance][stencil]") {
  // Quadrants: (ref, mask) = (0x0F, 0xFF), (0x80, 0xF0), (300 -> 255, 0x0F), (-5 -> 0, 0xFF).
  const int refs[4] = {0x0F, 0x80, 300, -5};
  const uint8_t masks[4] = {0xFF, 0xF0, 0x0F, 0xFF};
  for (CompareFunc func : kFuncs) {
    Scenario sc;
    sc.name = std::string("stencil func ") + name(func);
    sc.width = sc.height = kSize;
    addStencilStripes(sc);
    for (int q = 0; q < 4; ++q) {
      DrawStep d = quadrantDraw(q);
      d.state.stencilTest = true;
      for (StencilFaceState& s : d.state.stencil) {
        s.func = func;
        s.ref = refs[q];
        s.mask = masks[q];
        s.sfail = StencilOp::DecrWrap;  // pass and fail both leave a mark
        s.dppass = StencilOp::IncrWrap;
      }
      addOverlappingTriangles(d);
      sc.steps.push_back(d);
    }
    checkAgreement(runCase(sc));
  }
}

TEST_CASE("each stencil op on sfail, dpfail and dppass saturates and wraps at 0 and 255 as Mesa does",
          "[conformance][stencil]") {
  for (StencilOp op : kOps) {
    Scenario sc;
    sc.name = std::string("stencil op ") + name(op);
    sc.width = sc.height = kSize;
    addStencilStripes(sc);
    addDepthSplit(sc);
    // Quadrant 0: op on sfail (func LEQUAL 0x7F fails on stored < 0x7F); 1: op on dpfail;
    // 2: op on dppass; 3: op on all three.
    for (int q = 0; q < 4; ++q) {
      DrawStep d = quadrantDraw(q);
      d.state.stencilTest = true;
      d.state.depthTest = true;
      d.state.depthWrite = false;  // keep the split, so every triangle sees the same depth result
      for (StencilFaceState& s : d.state.stencil) {
        s.func = CompareFunc::LEqual;
        s.ref = 0x7F;
        s.mask = 0xFF;
        s.sfail = (q == 0 || q == 3) ? op : StencilOp::Keep;
        s.dpfail = (q == 1 || q == 3) ? op : StencilOp::Keep;
        s.dppass = (q == 2 || q == 3) ? op : StencilOp::Keep;
        s.ref = q == 3 ? 0x5A : 0x7F;  // REPLACE then writes a value the stripes do not contain
      }
      addOverlappingTriangles(d);
      sc.steps.push_back(d);
    }
    checkAgreement(runCase(sc));
  }
}

TEST_CASE("the stencil write mask limits draws and clears to its bits as in Mesa", "[conformance][stencil]") {
  Scenario sc;
  sc.name = "stencil write mask";
  sc.width = sc.height = kSize;
  addStencilStripes(sc);
  const uint8_t writeMasks[4] = {0x0F, 0xF0, 0x3C, 0x00};
  const StencilOp ops[4] = {StencilOp::IncrWrap, StencilOp::Invert, StencilOp::Replace, StencilOp::Zero};
  for (int q = 0; q < 4; ++q) {
    DrawStep d = quadrantDraw(q);
    d.state.stencilTest = true;
    for (StencilFaceState& s : d.state.stencil) {
      s.ref = 0xA5;
      s.writeMask = writeMasks[q];
      s.dppass = ops[q];
    }
    addOverlappingTriangles(d);
    sc.steps.push_back(d);
  }
  // A clear through the (front) write mask over the middle.
  ClearStep c;
  c.state = fullViewportState(kSize, kSize);
  c.state.scissorTest = true;
  c.state.scissor = Rect{16, 16, 32, 32};
  c.state.stencil[FrontFacing].writeMask = 0x33;
  c.state.stencil[BackFacing].writeMask = 0xFF;  // ignored by glClear
  c.stencil = true;
  c.stencilValue = 0xFF;
  sc.steps.push_back(c);
  checkAgreement(runCase(sc));
}

TEST_CASE("two-sided stencil applies the front or back state by window-space facing as Mesa does",
          "[conformance][stencil]") {
  for (FrontFace frontFace : {FrontFace::CCW, FrontFace::CW}) {
    Scenario sc;
    sc.name = std::string("two-sided stencil, front face ") + (frontFace == FrontFace::CCW ? "CCW" : "CW");
    sc.width = sc.height = kSize;
    addStencilStripes(sc);
    addDepthSplit(sc);
    DrawStep d;
    d.state = fullViewportState(kSize, kSize);
    d.state.frontFace = frontFace;
    d.state.stencilTest = true;
    d.state.depthTest = true;
    d.state.depthWrite = false;
    d.state.stencil[FrontFacing] = {CompareFunc::Always, 0, 0xFF, 0xFF, StencilOp::Keep, StencilOp::IncrWrap,
                                    StencilOp::Incr};
    sc.minStencilAgreement = 0.99;
    sc.note = "integer vertices: edges through pixel centres (fill-rule ties, §Ties)";
    d.state.stencil[BackFacing] = {CompareFunc::NotEqual, 0x80, 0xFF, 0xFF, StencilOp::Invert, StencilOp::DecrWrap,
                                   StencilOp::Decr};
    // Counter-clockwise and clockwise triangles overlapping (a shadow volume's front and back).
    addTriangle(d, {4, 4, 0.2}, {60, 10, 0.2}, {30, 60, 0.2}, {1, 0, 0, 1});
    addTriangle(d, {2, 40, 0.2}, {62, 58, 0.2}, {44, 2, 0.2}, {0, 1, 0, 1});
    addTriangle(d, {10, 30, 0.2}, {54, 28, 0.2}, {30, 63, 0.2}, {0, 0, 1, 1});
    addTriangle(d, {20, 2, 0.2}, {8, 62, 0.2}, {58, 36, 0.2}, {1, 1, 0, 1});
    sc.steps.push_back(d);
    checkAgreement(runCase(sc));
  }
}

namespace {

struct SoupKind {
  const char* name;
  bool onGrid;
  double margin;  // pixels beyond the viewport the vertices may lie
  double minStencilAgreement;
  const char* note;
};

}  // namespace

TEST_CASE("triangle soups counted with INCR_WRAP give Mesa's stencil counts except at fill-rule ties",
          "[conformance][stencil][soup]") {
  const SoupKind kinds[] = {
      {"vertices on 1/256 grid, crossing the viewport", true, 8.0, 0.999, ""},
      {"arbitrary vertices inside the viewport", false, 0.0, 0.99, "softpipe: float edge arithmetic (§Softpipe)"},
      {"arbitrary vertices, crossing the viewport", false, 8.0, 0.99,
       "Mesa clips at the viewport and snaps the new vertices (§Clipping)"},
  };
  uint32_t seed = 2024;
  for (const SoupKind& kind : kinds) {
    Scenario sc;
    sc.name = std::string("INCR_WRAP soup, 300 triangles, ") + kind.name;
    sc.width = 128;
    sc.height = 96;
    sc.minStencilAgreement = kind.minStencilAgreement;
    sc.note = kind.note;
    DrawStep d;
    d.state = fullViewportState(sc.width, sc.height);
    d.state.stencilTest = true;
    for (StencilFaceState& s : d.state.stencil) s.dppass = StencilOp::IncrWrap;
    d.vertices = triangleSoup(d.state.viewport, 300, seed++, kind.onGrid, kind.margin);
    sc.steps.push_back(d);
    checkAgreement(runCase(sc));
  }
}
