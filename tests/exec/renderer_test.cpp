// The draw call as a whole: scissor, the canonical vertex rotation that makes equal triangles give
// bit-equal depths (the shadow-volume front cap), determinism, pixel history.
#include <bit>
#include <cstring>
#include <functional>
#include <optional>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/clear.h"
#include "gl/projection.h"
#include "exec/renderer.h"
#include "gl/vertex_stage.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

TEST_CASE("scissor: only pixels inside the scissor box are drawn", "[raster][scissor]") {
  Framebuffer fb(8, 4);
  RenderState s = coverageCountingState(fb);
  s.scissorTest = true;
  s.scissor = {2, 1, 3, 2};
  Renderer r(fb);
  draw(r, s, windowRect(s.viewport, 0, 0, 8, 4));
  CHECK(stencilPicture(fb) == rows({"........",
                                    "..111...",
                                    "..111...",
                                    "........"}));
  // A box reaching outside the framebuffer is cut to it.
  Framebuffer fb2(8, 4);
  s.scissor = {-2, -1, 4, 3};
  Renderer r2(fb2);
  draw(r2, s, windowRect(s.viewport, 0, 0, 8, 4));
  CHECK(stencilPicture(fb2) == rows({"........",
                                     "........",
                                     "11......",
                                     "11......"}));
  // Scissor test off: the box is ignored.
  Framebuffer fb3(8, 4);
  s.scissorTest = false;
  Renderer r3(fb3);
  draw(r3, s, windowRect(s.viewport, 0, 0, 8, 4));
  CHECK(stencilPicture(fb3) == rows({"11111111", "11111111", "11111111", "11111111"}));
}

// ---------------------------------------------------------------------------------------------
// Canonical rotation: (a, b, c), (b, c, a), (c, a, b) are the same triangle.

namespace {

struct Triangle {
  ClipVertex v[3];
};

// Random world triangles in front of (and some crossing the near plane of) a perspective camera,
// transformed as the scene pass does (vertex_stage.h). Coordinates are far from dyadic so rounding
// differences would show.
std::vector<Triangle> randomCameraTriangles(uint64_t seed, int count) {
  TestRandom rng(seed);
  VertexTransform xf;
  xf.projection = perspective(53.0, 1.0, 0.37, 91.0);
  xf.modelView = lookAt({0.31, 0.77, 4.13}, {0.05, -0.11, 0.0}, {0.0, 1.0, 0.0});
  std::vector<Triangle> out;
  for (int i = 0; i < count; ++i) {
    const glm::dvec3 centre(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(-2.0, 2.0));
    Triangle t;
    for (ClipVertex& v : t.v) {
      const glm::dvec3 p = centre + glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      v.position = xf.toClip(glm::dvec4(p, 1.0));
    }
    out.push_back(t);
  }
  // Two triangles reaching behind the camera (eye at z = 4.13): the near plane cuts them.
  for (int i = 0; i < 2; ++i) {
    Triangle t;
    t.v[0].position = xf.toClip({-0.7 + i * 0.3, -0.4, 1.0, 1.0});
    t.v[1].position = xf.toClip({0.9, -0.3 + i * 0.2, 0.5, 1.0});
    t.v[2].position = xf.toClip({0.1, 0.6, 6.0, 1.0});  // behind the eye
    out.push_back(t);
  }
  return out;
}

std::vector<ClipVertex> rotation(const Triangle& t, int k) {
  return {t.v[k % 3], t.v[(k + 1) % 3], t.v[(k + 2) % 3]};
}

}  // namespace

TEST_CASE("canonical rotation: a triangle in any rotation gives bit-identical depth codes", "[raster][rotation]") {
  const std::vector<Triangle> triangles = randomCameraTriangles(11, 30);
  for (DepthFormat format : {DepthFormat::Float32, DepthFormat::Unorm24}) {
    for (size_t i = 0; i < triangles.size(); ++i) {
      INFO("triangle " << i << (format == DepthFormat::Float32 ? " float32" : " unorm24"));
      std::vector<uint32_t> depth[3];
      std::vector<uint8_t> coverage[3];
      for (int k = 0; k < 3; ++k) {
        Framebuffer fb(48, 48, format);
        RenderState s = coverageCountingState(fb);
        s.depthTest = true;
        s.depthFunc = CompareFunc::Always;
        Renderer r(fb);
        draw(r, s, rotation(triangles[i], k));
        depth[k].assign(fb.depthCodes().begin(), fb.depthCodes().end());
        coverage[k].assign(fb.stencil().begin(), fb.stencil().end());
      }
      CHECK(depth[1] == depth[0]);
      CHECK(depth[2] == depth[0]);
      CHECK(coverage[1] == coverage[0]);
      CHECK(coverage[2] == coverage[0]);
    }
  }
}

TEST_CASE("front-cap property: redrawing a triangle in another rotation fails LESS and passes EQUAL everywhere",
          "[raster][rotation]") {
  const std::vector<Triangle> triangles = randomCameraTriangles(23, 30);
  int pixelsChecked = 0;
  for (DepthFormat format : {DepthFormat::Float32, DepthFormat::Unorm24}) {
    for (size_t i = 0; i < triangles.size(); ++i) {
      INFO("triangle " << i << (format == DepthFormat::Float32 ? " float32" : " unorm24"));
      Framebuffer fb(48, 48, format);
      RenderState scene = coverageCountingState(fb);  // the scene pass: depth LESS, written
      scene.depthTest = true;
      scene.depthFunc = CompareFunc::Less;
      Renderer r(fb);
      draw(r, scene, rotation(triangles[i], 0));
      const PixelVector<uint8_t> covered = fb.stencil();
      for (uint8_t c : covered) pixelsChecked += c;

      RenderState volume = scene;  // the volume pass: depth not written, count where depth passes
      volume.depthWrite = false;
      for (StencilFaceState& f : volume.stencil) f.dpfail = StencilOp::Keep;
      for (int k = 1; k < 3; ++k) {
        clearStencil(fb, volume, 0);
        volume.depthFunc = CompareFunc::Less;
        draw(r, volume, rotation(triangles[i], k));
        CHECK(stencilPicture(fb) == picture(48, 48, [](int, int) { return '.'; }));
        clearStencil(fb, volume, 0);
        volume.depthFunc = CompareFunc::Equal;
        draw(r, volume, rotation(triangles[i], k));
        CHECK(fb.stencil() == covered);
      }
    }
  }
  CHECK(pixelsChecked > 1000);
}

// ---------------------------------------------------------------------------------------------

namespace {

// Random depth and stencil tests, functions and operations.
void randomTests(TestRandom& rng, RenderState& s) {
  s.depthTest = rng.below(4) != 0;
  s.depthFunc = CompareFunc(rng.below(8));
  s.depthWrite = rng.below(3) != 0;
  s.stencilTest = rng.below(2) != 0;
  for (StencilFaceState& f : s.stencil) {
    f.func = CompareFunc(rng.below(8));
    f.ref = rng.below(256);
    f.sfail = StencilOp(rng.below(8));
    f.dpfail = StencilOp(rng.below(8));
    f.dppass = StencilOp(rng.below(8));
  }
}

// A frame of random draws: random triangles (some crossing the near plane), colours, and state.
void renderRandomFrame(Framebuffer& fb, uint64_t seed) {
  TestRandom rng(seed);
  Renderer r(fb);
  RenderState s = fullViewportState(fb);
  clearColor(fb, s, {0.1f, 0.2f, 0.3f, 0.4f});
  clearDepth(fb, s, 1.0);
  clearStencil(fb, s, 0);
  const glm::dmat4 p = perspective(70.0, 1.25, 0.5, 50.0);
  const ColorVaryingShader shader;
  for (int d = 0; d < 40; ++d) {
    randomTests(rng, s);
    s.cull = CullMode(rng.below(3));
    s.blend = {rng.below(2) != 0, BlendFactor(rng.below(10)), BlendFactor(rng.below(10))};
    s.polygonOffset = {rng.below(4) == 0, rng.uniform(-2, 2), rng.uniform(-4, 4)};
    std::vector<ClipVertex> v(3 * 10);
    for (ClipVertex& cv : v) {
      cv.position = p * glm::dvec4(rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(-12, 1), 1.0);
      for (int k = 0; k < 4; ++k) cv.varyings[k] = rng.uniform(-0.2, 1.2);
    }
    draw(r, s, v, &shader);
  }
}

template <class T>
bool sameBytes(const PixelVector<T>& a, const PixelVector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

}  // namespace

TEST_CASE("determinism: the same random frame rendered twice is byte-identical in every buffer",
          "[raster][determinism]") {
  for (uint64_t seed : {5u, 6u, 7u}) {
    INFO("seed " << seed);
    Framebuffer a(96, 64), b(96, 64);
    renderRandomFrame(a, seed);
    renderRandomFrame(b, seed);
    CHECK(sameBytes(a.color(), b.color()));
    CHECK(sameBytes(a.depthCodes(), b.depthCodes()));
    CHECK(sameBytes(a.stencil(), b.stencil()));
    // Not a vacuous comparison: a different seed gives a different frame.
    Framebuffer c(96, 64);
    renderRandomFrame(c, seed + 100);
    CHECK_FALSE(sameBytes(a.color(), c.color()));
  }
}

// ---------------------------------------------------------------------------------------------
// Pixel history (FragmentObserver through Renderer::watchPixel).

namespace {

class Recorder final : public FragmentObserver {
 public:
  void onFragment(const FragmentEvent& e) override { events.push_back(e); }
  std::vector<FragmentEvent> events;
};

}  // namespace

TEST_CASE("pixel history records each fragment at the watched pixel with tests and stencil before/after",
          "[raster][history]") {
  Framebuffer fb(16, 16);
  RenderState s = fullViewportState(fb);
  s.depthTest = true;
  s.depthFunc = CompareFunc::Less;
  s.stencilTest = true;
  for (StencilFaceState& f : s.stencil) f = {CompareFunc::Always, 7, 0xFF, 0xFF, StencilOp::Zero, StencilOp::Replace, StencilOp::Incr};
  Renderer r(fb);
  Recorder history;
  r.watchPixel(8, 8, &history);
  const Viewport& vp = s.viewport;

  // 0: a rectangle at depth 0.5: both tests pass, INCR 0 -> 1, depth 1 -> 0.5.
  draw(r, s, windowRect(vp, 0, 0, 16, 16, 0.5), nullptr, 10);
  // 1: a triangle behind it (0.75): the depth test fails, dpfail REPLACE 1 -> 7.
  draw(r, s, windowTriangles(vp, {{2, 2, 0.75}, {15, 3, 0.75}, {6, 14, 0.75}}), nullptr, 11);
  // 2: a clockwise (back-facing) triangle in front (0.25), stencil EQUAL 7: passes, INCR 7 -> 8.
  RenderState equal7 = s;
  for (StencilFaceState& f : equal7.stencil) f.func = CompareFunc::Equal;
  draw(r, equal7, windowTriangles(vp, {{1, 1, 0.25}, {9, 15, 0.25}, {15, 1, 0.25}}), nullptr, 12);
  // 3: a triangle that misses the pixel: no event.
  draw(r, s, windowTriangles(vp, {{0, 0, 0.1}, {4, 0, 0.1}, {0, 4, 0.1}}), nullptr, 13);
  // 4: a triangle whose stencil test fails (NEVER): sfail ZERO 8 -> 0, depth not tested.
  RenderState never = s;
  for (StencilFaceState& f : never.stencil) f.func = CompareFunc::Never;
  draw(r, never, windowTriangles(vp, {{3, 3, 0.1}, {14, 6, 0.1}, {7, 13, 0.1}}), nullptr, 14);
  r.watchPixel(-1, -1, nullptr);
  draw(r, s, windowRect(vp, 0, 0, 16, 16, 0.0), nullptr, 15);  // not watched any more

  REQUIRE(history.events.size() == 4);
  const FragmentEvent* e = history.events.data();
  CHECK(e[0].drawIndex == 0);
  CHECK(e[0].drawTag == 10);
  CHECK(e[0].x == 8);
  CHECK(e[0].y == 8);
  CHECK(e[0].facing == FrontFacing);
  CHECK(e[0].stencilPassed);
  CHECK(e[0].depthPassed);
  CHECK(e[0].depth == 0.5);
  CHECK(e[0].storedDepth == 1.0);
  CHECK(int(e[0].stencilBefore) == 0);
  CHECK(int(e[0].stencilAfter) == 1);

  CHECK(e[1].drawIndex == 1);
  CHECK(e[1].drawTag == 11);
  CHECK(e[1].stencilPassed);
  CHECK_FALSE(e[1].depthPassed);
  CHECK(e[1].depth == 0.75);
  CHECK(e[1].storedDepth == 0.5);
  CHECK(int(e[1].stencilBefore) == 1);
  CHECK(int(e[1].stencilAfter) == 7);

  CHECK(e[2].drawIndex == 2);
  CHECK(e[2].drawTag == 12);
  CHECK(e[2].facing == BackFacing);
  CHECK(e[2].stencilPassed);
  CHECK(e[2].depthPassed);
  CHECK(e[2].storedDepth == 0.5);
  CHECK(int(e[2].stencilBefore) == 7);
  CHECK(int(e[2].stencilAfter) == 8);

  CHECK(e[3].drawIndex == 4);
  CHECK(e[3].drawTag == 14);
  CHECK_FALSE(e[3].stencilPassed);
  CHECK(e[3].storedDepth == 0.25);
  CHECK(int(e[3].stencilBefore) == 8);
  CHECK(int(e[3].stencilAfter) == 0);

  CHECK(fb.stencilAt(8, 8) == 1);  // the unwatched draw 5 still ran: INCR 0 -> 1
}

// ---------------------------------------------------------------------------------------------
// Renderer::clear: a clear waits for the flush and is done band by band with the draws around it.

namespace {

// Ten random triangles over the whole frame with colour varyings, in a random state.
std::vector<ClipVertex> randomBatch(TestRandom& rng, const Viewport& vp, RenderState& s) {
  randomTests(rng, s);
  std::vector<ClipVertex> v;
  for (int t = 0; t < 10; ++t)
    for (int k = 0; k < 3; ++k) {
      ClipVertex cv = windowVertex(vp, rng.uniform(-50.0, vp.width + 50.0), rng.uniform(-50.0, vp.height + 50.0),
                                   rng.uniform(0.0, 1.0));
      for (int c = 0; c < 4; ++c) cv.varyings[size_t(c)] = rng.uniform(0.0, 1.0);
      v.push_back(cv);
    }
  return v;
}

// The same sequence — draw, a scissored depth and stencil clear whose rows reach past the
// draws', draw, a colour clear, draw — done at once (clears of clear.h, no DeferredDraws) or with
// the renderer's clears inside one DeferredDraws on `threads` threads.
Framebuffer clearsBetweenDraws(bool throughRenderer, int threads, uint64_t seed) {
  Framebuffer fb(512, 384);  // 4 MB of colour, depth and stencil: the clears ask for cache bands
  TestRandom rng(seed);
  RenderState s = fullViewportState(fb);
  RenderState scissored = s;
  scissored.scissorTest = true;
  scissored.scissor = {37, 11, 300, 350};
  const ColorVaryingShader shader;
  std::vector<std::vector<ClipVertex>> batches;
  std::vector<RenderState> states;
  for (int b = 0; b < 3; ++b) {
    states.push_back(s);
    batches.push_back(randomBatch(rng, s.viewport, states.back()));
  }
  // The draws stay inside rows 100 .. 299, so the clears' other rows are the clears' alone.
  for (RenderState& st : states) {
    st.scissorTest = true;
    st.scissor = {0, 100, 512, 200};
  }
  Renderer r(fb, threads);
  auto clearAll = [&](const ClearRequest& c) {
    if (throughRenderer) r.clear(c);
    else clear(fb, c);
  };
  {
    std::optional<DeferredDraws> deferred;
    if (throughRenderer) deferred.emplace(r);
    clearAll({.state = s, .color = glm::vec4(0.1f, 0.2f, 0.3f, 0.4f), .depth = 1.0, .stencil = 0});
    draw(r, states[0], batches[0], &shader);
    clearAll({.state = scissored, .depth = 0.75, .stencil = 3});
    draw(r, states[1], batches[1], &shader);
    clearAll({.state = scissored, .color = glm::vec4(0.9f, 0.8f, 0.7f, 0.6f)});
    draw(r, states[2], batches[2], &shader);
  }
  return fb;
}

}  // namespace

TEST_CASE("renderer clears between deferred draws give the bytes of clearing and drawing one after another",
          "[raster][clear][threads]") {
  for (uint64_t seed : {3u, 4u}) {
    const Framebuffer reference = clearsBetweenDraws(false, 1, seed);
    for (int threads : {1, 2, 8}) {
      INFO("seed " << seed << ", " << threads << " threads");
      const Framebuffer banded = clearsBetweenDraws(true, threads, seed);
      CHECK(sameBytes(reference.color(), banded.color()));
      CHECK(sameBytes(reference.depthCodes(), banded.depthCodes()));
      CHECK(sameBytes(reference.stencil(), banded.stencil()));
    }
    // Not vacuous: the draws changed the cleared buffers, and the scissored clears left their mark.
    CHECK(reference.stencilAt(40, 20) == 3);
    CHECK(reference.colorAt(40, 20) == glm::vec4(0.9f, 0.8f, 0.7f, 0.6f));
    CHECK(reference.colorAt(5, 5) == glm::vec4(0.1f, 0.2f, 0.3f, 0.4f));
    size_t drawn = 0;
    for (int y = 100; y < 300; ++y)
      for (int x = 0; x < 512; ++x) drawn += reference.colorAt(x, y) != reference.colorAt(5, 5) &&
                                            reference.colorAt(x, y) != glm::vec4(0.9f, 0.8f, 0.7f, 0.6f);
    CHECK(drawn > 10000);
  }
}

TEST_CASE("a renderer clear with no draw after it is done when the framebuffer is asked for, or at the end",
          "[raster][clear]") {
  Framebuffer fb(64, 64);
  const RenderState s = fullViewportState(fb);
  {
    Renderer r(fb);
    r.clear({.state = s, .depth = 0.5});
    CHECK(fb.hasDepth());  // made at once
    CHECK(r.framebuffer().depthAt(10, 10) == 0.5);
    r.clear({.state = s, .depth = 0.25, .stencil = 7});
  }
  CHECK(fb.depthAt(63, 63) == 0.25);
  CHECK(fb.stencilAt(0, 0) == 7);
}

// ---------------------------------------------------------------------------------------------
// Queued assembly (DeferredDraws with Geometry::Kept): the pass's triangles are cut into groups
// of shrinking length, a large draw between several of them.

namespace {

// A bumpy indexed grid of n × n quads in front of a perspective camera, its near corner behind
// the near plane (clipped), with colour varyings; and a random soup of separate triangles.
struct QueuedScene {
  std::vector<ClipVertex> gridVertices, soupA, soupB;
  std::vector<uint32_t> gridIndices;
};

QueuedScene makeQueuedScene(uint64_t seed, double nearZ = 0.2) {
  TestRandom rng(seed);
  QueuedScene q;
  const glm::dmat4 p = perspective(70.0, 1.25, 0.5, 50.0);
  constexpr int n = 48;  // 4608 triangles: one draw much larger than the groups of 2 or 8 threads
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      ClipVertex v;
      const double x = -6.0 + 12.0 * i / n, z = nearZ - 14.0 * j / n;
      v.position = p * glm::dvec4(x, -2.0 + rng.uniform(-0.6, 0.6), z, 1.0);
      for (int k = 0; k < 4; ++k) v.varyings[size_t(k)] = rng.uniform(0.0, 1.0);
      q.gridVertices.push_back(v);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      // Alternate windings: half the quads face away and are culled.
      if ((i + j) % 3 == 0) q.gridIndices.insert(q.gridIndices.end(), {a, c, b, b, c, d});
      else q.gridIndices.insert(q.gridIndices.end(), {a, b, c, b, d, c});
    }
  for (std::vector<ClipVertex>* soup : {&q.soupA, &q.soupB})
    for (int t = 0; t < 3 * 40; ++t) {
      ClipVertex v;
      v.position = p * glm::dvec4(rng.uniform(-6, 6), rng.uniform(-5, 5), rng.uniform(-12, 1), 1.0);
      for (int k = 0; k < 4; ++k) v.varyings[size_t(k)] = rng.uniform(0.0, 1.0);
      soup->push_back(v);
    }
  return q;
}

// Soup A, the grid, soup B — with blending and stencil counting, so that the order of the
// fragments at each pixel shows in the bytes — drawn one by one on one thread, or queued under a
// DeferredDraws that keeps the geometry on `threads` threads. `reversed` swaps the soups.
Framebuffer renderQueued(const QueuedScene& q, int threads, bool queued, bool reversed, RasterStats& stats) {
  Framebuffer fb(160, 128);
  RenderState s = fullViewportState(fb);
  clearColor(fb, s, {0.1f, 0.2f, 0.3f, 0.4f});
  clearDepth(fb, s, 1.0);
  clearStencil(fb, s, 0);
  s.cull = CullMode::Back;
  s.depthFunc = CompareFunc::LEqual;
  s.blend = {true, BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha};
  s.stencilTest = true;
  for (StencilFaceState& f : s.stencil) {
    f.func = CompareFunc::Always;
    f.dppass = StencilOp::IncrWrap;
    f.dpfail = StencilOp::Invert;
  }
  const ColorVaryingShader shader;
  Renderer r(fb, threads);
  {
    std::optional<DeferredDraws> deferred;
    if (queued) deferred.emplace(r, DeferredDraws::Geometry::Kept);
    r.draw({.state = &s, .vertices = reversed ? q.soupB : q.soupA, .indices = {}, .shader = &shader});
    r.draw({.state = &s, .vertices = q.gridVertices, .indices = q.gridIndices, .shader = &shader});
    r.draw({.state = &s, .vertices = reversed ? q.soupA : q.soupB, .indices = {}, .shader = &shader});
  }
  stats = r.stats();
  return fb;
}

}  // namespace

TEST_CASE("queued draws cut into groups of triangles give the bytes and counts of drawing them one by one",
          "[raster][threads]") {
  for (uint64_t seed : {11u, 12u}) {
    const QueuedScene q = makeQueuedScene(seed);
    RasterStats referenceStats;
    const Framebuffer reference = renderQueued(q, 1, false, false, referenceStats);
    for (int threads : {2, 3, 8}) {
      INFO("seed " << seed << ", " << threads << " threads");
      RasterStats stats;
      const Framebuffer fb = renderQueued(q, threads, true, false, stats);
      CHECK(sameBytes(reference.color(), fb.color()));
      CHECK(sameBytes(reference.depthCodes(), fb.depthCodes()));
      CHECK(sameBytes(reference.stencil(), fb.stencil()));
      CHECK(stats.trianglesRasterized == referenceStats.trianglesRasterized);
      CHECK(stats.trianglesClipped == referenceStats.trianglesClipped);
      CHECK(stats.trianglesCulled == referenceStats.trianglesCulled);
      CHECK(stats.fragments == referenceStats.fragments);
    }
    // Not vacuous: the grid is clipped and half culled, and the order of the draws shows in the bytes.
    CHECK(referenceStats.trianglesClipped > 0);
    CHECK(referenceStats.trianglesCulled > 1000);
    CHECK(referenceStats.fragments > 10000);
    RasterStats reversedStats;
    const Framebuffer reversed = renderQueued(q, 2, true, true, reversedStats);
    CHECK_FALSE(sameBytes(reference.color(), reversed.color()));
  }
}

// ---------------------------------------------------------------------------------------------
// A flush that only adds to the stencil (the shadow volumes' counting) is counted by runs of
// triangles on the threads, each into a stencil of its own, summed at the end.

namespace {

// A depth-writing grid, then in one flush: a stencil clear and `soups` draws of random triangles,
// unculled, that count INCR_WRAP on front faces and DECR_WRAP on back faces where the depth test
// passes, and the reverse where it fails, with the grid again twice (at its own depth: every test
// fails) — 10496 triangles, enough for the runs of eight threads. `frontPass` replaces the front
// faces' pass op; `clearBetween` clears the stencil halfway through the draws.
struct CountingRun {
  Framebuffer fb{160, 128};
  RasterStats stats;
  uint64_t flushesByTriangles = 0, flushesByBands = 0;
};
// `depth`'s test without its writes, counting like z-fail's volumes: `frontPass` (INCR_WRAP in
// z-fail's place) and DECR_WRAP on front faces where the depth test passes and fails, the reverse on
// back faces.
RenderState countingState(const RenderState& depth, StencilOp frontPass) {
  RenderState counting = depth;
  counting.depthWrite = false;
  counting.stencilTest = true;
  counting.stencil[FrontFacing].dppass = frontPass;
  counting.stencil[FrontFacing].dpfail = StencilOp::DecrWrap;
  counting.stencil[BackFacing].dppass = StencilOp::DecrWrap;
  counting.stencil[BackFacing].dpfail = StencilOp::IncrWrap;
  return counting;
}

// Not vacuous: at least `least` counts above and below the cleared 0 (wrapped to 255 and down),
// and some failed depth tests, but not all.
void checkCountsBothWays(const CountingRun& run, int least, uint64_t failedAtLeast) {
  int positive = 0, negative = 0;
  for (const uint8_t v : run.fb.stencil()) {
    positive += v > 0 && v < 128;
    negative += v >= 128;
  }
  CHECK(positive > least);
  CHECK(negative > least);
  CHECK(run.stats.depthFailed > failedAtLeast);
  CHECK(run.stats.depthFailed < run.stats.fragments);
}

CountingRun renderCounting(const QueuedScene& q, int threads, StencilOp frontPass = StencilOp::IncrWrap,
                           bool clearBetween = false, FragmentObserver* history = nullptr) {
  CountingRun run;
  Framebuffer& fb = run.fb;
  RenderState depth = fullViewportState(fb);
  clearDepth(fb, depth, 1.0);
  clearStencil(fb, depth, 7);
  depth.depthTest = true;
  depth.depthFunc = CompareFunc::Less;
  const RenderState counting = countingState(depth, frontPass);
  Renderer r(fb, threads);
  r.draw({.state = &depth, .vertices = q.gridVertices, .indices = q.gridIndices});
  if (history) r.watchPixel(80, 64, history);
  {
    const DeferredDraws deferred(r, DeferredDraws::Geometry::Kept);
    r.clear({.state = counting, .stencil = 0});
    for (int k = 0; k < 32; ++k) {
      if (clearBetween && k == 16) r.clear({.state = counting, .stencil = 3});
      r.draw({.state = &counting, .vertices = k % 2 ? q.soupA : q.soupB, .indices = {}});
      if (k % 16 == 0) r.draw({.state = &counting, .vertices = q.gridVertices, .indices = q.gridIndices});
    }
  }
  run.stats = r.stats();
  run.flushesByTriangles = r.flushesCountedByTriangles();
  run.flushesByBands = r.flushesCountedByBands();
  return run;
}

// The soups write depth; then in one flush a stencil clear and the grid's small triangles, in
// three draws, counting as renderCounting does: fewer of them cross a row than it has pixels, so
// that the threads count it by bands of rows, helping each other finish.
CountingRun renderGridCounting(const QueuedScene& q, int threads) {
  CountingRun run;
  Framebuffer& fb = run.fb;
  RenderState depth = fullViewportState(fb);
  clearDepth(fb, depth, 1.0);
  depth.depthTest = true;
  depth.depthFunc = CompareFunc::Less;
  const RenderState counting = countingState(depth, StencilOp::IncrWrap);
  Renderer r(fb, threads);
  r.draw({.state = &depth, .vertices = q.soupA, .indices = {}});
  r.draw({.state = &depth, .vertices = q.soupB, .indices = {}});
  {
    const DeferredDraws deferred(r, DeferredDraws::Geometry::Kept);
    r.clear({.state = counting, .stencil = 0});
    // The grid in three draws (a band's setups come from several), a third of its triangles each.
    const size_t third = q.gridIndices.size() / 9 * 3;
    const std::span<const uint32_t> indices(q.gridIndices);
    for (size_t k = 0; k < 3; ++k)
      r.draw({.state = &counting, .vertices = q.gridVertices,
              .indices = k < 2 ? indices.subspan(k * third, third) : indices.subspan(2 * third)});
  }
  run.stats = r.stats();
  run.flushesByTriangles = r.flushesCountedByTriangles();
  run.flushesByBands = r.flushesCountedByBands();
  return run;
}

}  // namespace

TEST_CASE("a counting flush gives the bytes and counts of one thread at any thread count", "[raster][threads]") {
  const QueuedScene q = makeQueuedScene(31, -0.6);  // the grid wholly in front of the near plane
  const CountingRun one = renderCounting(q, 1);
  CHECK(one.flushesByTriangles == 0);
  checkCountsBothWays(one, 500, 10000);

  Renderer::oneFragmentAtATime(true);
  const CountingRun reference = renderCounting(q, 1);
  Renderer::oneFragmentAtATime(false);
  CHECK(sameBytes(reference.fb.stencil(), one.fb.stencil()));

  for (int threads : {2, 3, 8}) {
    INFO(threads << " threads");
    const CountingRun many = renderCounting(q, threads);
    CHECK(many.flushesByTriangles == 1);
    CHECK(sameBytes(one.fb.stencil(), many.fb.stencil()));
    CHECK(sameBytes(one.fb.depthCodes(), many.fb.depthCodes()));
    CHECK(many.stats.fragments == one.stats.fragments);
    CHECK(many.stats.depthFailed == one.stats.depthFailed);
    CHECK(many.stats.stencilWrites == one.stats.stencilWrites);
    CHECK(many.stats.trianglesRasterized == one.stats.trianglesRasterized);
    // A second frame on the same thread takes the kept extra stencils, zeroed by the sum.
    CHECK(sameBytes(one.fb.stencil(), renderCounting(q, threads).fb.stencil()));
  }
}

TEST_CASE("a counting flush of small triangles, by bands the threads help each other finish, gives one thread's bytes",
          "[raster][threads]") {
  const QueuedScene q = makeQueuedScene(34, -8.0);  // far off: small triangles
  const CountingRun one = renderGridCounting(q, 1);
  CHECK(one.flushesByBands == 0);
  checkCountsBothWays(one, 300, 1000);
  // Eight threads on this machine's two: a band whose task has not started keeps its setups, one
  // started is helped; which setups another thread takes varies from run to run.
  for (int threads : {2, 3, 8, 8, 8}) {
    INFO(threads << " threads");
    const CountingRun many = renderGridCounting(q, threads);
    CHECK(many.flushesByTriangles == 0);
    CHECK(many.flushesByBands == 1);
    CHECK(sameBytes(one.fb.stencil(), many.fb.stencil()));
    CHECK(many.stats.fragments == one.stats.fragments);
    CHECK(many.stats.depthFailed == one.stats.depthFailed);
    CHECK(many.stats.stencilWrites == one.stats.stencilWrites);
  }
}

TEST_CASE("a flush with an op that does not add, or a clear between its draws, goes by bands", "[raster][threads]") {
  const QueuedScene q = makeQueuedScene(32, -0.6);
  for (const bool clearBetween : {false, true}) {
    const StencilOp op = clearBetween ? StencilOp::IncrWrap : StencilOp::Incr;  // INCR saturates
    INFO((clearBetween ? "a clear between the draws" : "INCR"));
    const CountingRun one = renderCounting(q, 1, op, clearBetween);
    const CountingRun two = renderCounting(q, 2, op, clearBetween);
    CHECK(two.flushesByTriangles == 0);
    CHECK(two.flushesByBands == 0);
    CHECK(sameBytes(one.fb.stencil(), two.fb.stencil()));
  }
}

TEST_CASE("a counting flush the pixel history watches goes by bands and reports its fragments in order",
          "[raster][threads][history]") {
  const QueuedScene q = makeQueuedScene(33, -0.6);
  Recorder one, two;
  const CountingRun a = renderCounting(q, 1, StencilOp::IncrWrap, false, &one);
  const CountingRun b = renderCounting(q, 2, StencilOp::IncrWrap, false, &two);
  CHECK(b.flushesByTriangles == 0);
  CHECK(b.flushesByBands == 0);
  CHECK(sameBytes(a.fb.stencil(), b.fb.stencil()));
  REQUIRE(one.events.size() > 10);
  REQUIRE(two.events.size() == one.events.size());
  for (size_t k = 0; k < one.events.size(); ++k) {
    CHECK(two.events[k].drawIndex == one.events[k].drawIndex);
    CHECK(two.events[k].stencilAfter == one.events[k].stencilAfter);
  }
}

// ---------------------------------------------------------------------------------------------
// Kept setups (SetupReuse): a later pass of the same, unchanged arrays takes the setups the
// renderer kept from the first, which it finds by itself.

namespace {

// Two passes over the queued scene's grid (moved in front of the near plane: nothing clipped) and
// soups: an ambient-like pass that writes depth and colour, then a lit-like pass (EQUAL, additive
// blending, stencil counting) with other shaders. With `copies` the second pass draws copies of
// the arrays (elsewhere in memory: nothing to find). Returns the framebuffer; `reused` the draws
// that took kept setups.
Framebuffer renderTwoPasses(const QueuedScene& q, int threads, bool queued, bool copies, RasterStats& stats,
                            uint64_t& reused) {
  Framebuffer fb(160, 128);
  RenderState first = fullViewportState(fb);
  clearColor(fb, first, {0.1f, 0.2f, 0.3f, 0.4f});
  clearDepth(fb, first, 1.0);
  clearStencil(fb, first, 0);
  first.cull = CullMode::Back;
  first.depthFunc = CompareFunc::Less;
  RenderState second = first;
  second.depthFunc = CompareFunc::Equal;
  second.depthWrite = false;
  second.blend = {true, BlendFactor::One, BlendFactor::One};
  second.stencilTest = true;
  for (StencilFaceState& f : second.stencil) {
    f.func = CompareFunc::Always;
    f.dppass = StencilOp::IncrWrap;
  }
  const ConstantColorShader flat({0.2, 0.1, 0.05, 1.0});
  const ColorVaryingShader varying;
  const QueuedScene copy = q;
  Renderer r(fb, threads);
  for (const RenderState* s : {&first, &second}) {
    const QueuedScene& arrays = s == &second && copies ? copy : q;
    const FragmentShader* shader = s == &first ? static_cast<const FragmentShader*>(&flat) : &varying;
    std::optional<DeferredDraws> deferred;
    if (queued) deferred.emplace(r, DeferredDraws::Geometry::Kept);
    r.draw({.state = s, .vertices = arrays.soupA, .indices = {}, .shader = shader});
    r.draw({.state = s, .vertices = arrays.gridVertices, .indices = arrays.gridIndices, .shader = shader});
    r.draw({.state = s, .vertices = arrays.soupB, .indices = {}, .shader = shader});
  }
  stats = r.stats();
  reused = r.drawsReusingSetups();
  return fb;
}

// A triangle drawn (its setups kept) by a renderer into a cleared stencil; then drawn again by the
// same renderer, with what `change` changes, into the cleared stencil. The pictures show which
// triangle each draw covered; the renderer's count whether the second took the kept setups.
struct Redrawn {
  Framebuffer fb{32, 8};
  RenderState state = coverageCountingState(fb);
  // Triangle 0 at x 1 … 7, triangle 1 at x 17 … 23.
  std::vector<ClipVertex> vertices =
      windowTriangles(state.viewport, {{1, 1, 0.5}, {7, 1, 0.5}, {1, 7, 0.5}, {17, 1, 0.5}, {23, 1, 0.5}, {17, 7, 0.5}});
  std::vector<uint32_t> indices = {0, 1, 2};
  const ConstantColorShader shader{glm::dvec4(0.5, 0.25, 1.0, 1.0)};  // only shaded draws keep setups
  Renderer renderer;
  uint64_t reusedBefore = 0;

  explicit Redrawn(int threads = 1) : renderer(fb, threads) {
    clearStencil(fb, state, 0);
    renderer.draw({.state = &state, .vertices = vertices, .indices = indices, .shader = &shader});
    reusedBefore = renderer.drawsReusingSetups();
  }
  // The second draw's picture, with the first draw's call but for what `change` changes (it may
  // change the arrays in place).
  std::string redraw(const std::function<void(DrawCall&, RenderState&)>& change) {
    clearStencil(fb, state, 0);
    RenderState s = state;
    DrawCall call{.state = &s, .vertices = vertices, .indices = indices, .shader = &shader};
    change(call, s);
    renderer.draw(call);
    return stencilPicture(fb);
  }
  // The same, unchanged, `draws` times in one pass that keeps its geometry (queued at two threads).
  std::string redrawQueued(int draws) {
    clearStencil(fb, state, 0);
    {
      const DeferredDraws deferred(renderer, DeferredDraws::Geometry::Kept);
      for (int i = 0; i < draws; ++i)
        renderer.draw({.state = &state, .vertices = vertices, .indices = indices, .shader = &shader});
    }
    return stencilPicture(fb);
  }
  uint64_t reused() const { return renderer.drawsReusingSetups() - reusedBefore; }
};

// The picture of triangle `which` of Redrawn assembled afresh, in `s` (coverage counting when
// not given).
std::string freshPicture(int which, const std::function<void(RenderState&)>& change = {}) {
  Framebuffer fb(32, 8);
  RenderState s = coverageCountingState(fb);
  if (change) change(s);
  clearStencil(fb, s, 0);
  Renderer r(fb);
  const double x = which == 1 ? 16.0 : 0.0;
  draw(r, s, windowTriangles(s.viewport, {{x + 1, 1, 0.5}, {x + 7, 1, 0.5}, {x + 1, 7, 0.5}}));
  return stencilPicture(fb);
}

}  // namespace

TEST_CASE("a pass that takes the kept setups gives the bytes and counts of assembling them again",
          "[raster][reuse]") {
  for (uint64_t seed : {21u, 22u}) {
    const QueuedScene q = makeQueuedScene(seed, -1.0);  // the grid in front of the near plane
    RasterStats referenceStats;
    uint64_t reused = 0;
    const Framebuffer reference = renderTwoPasses(q, 1, false, true, referenceStats, reused);
    CHECK(reused == 0);  // copies: other arrays
    for (int threads : {1, 2, 8})
      for (bool queued : {false, true}) {
        INFO("seed " << seed << ", " << threads << " threads, queued " << queued);
        RasterStats stats;
        const Framebuffer fb = renderTwoPasses(q, threads, queued, false, stats, reused);
        CHECK(reused == 1);  // the second pass's grid; the soups cross the near plane (clipped: kept nothing)
        CHECK(sameBytes(reference.color(), fb.color()));
        CHECK(sameBytes(reference.depthCodes(), fb.depthCodes()));
        CHECK(sameBytes(reference.stencil(), fb.stencil()));
        CHECK(stats.trianglesIn == referenceStats.trianglesIn);
        CHECK(stats.trianglesRasterized == referenceStats.trianglesRasterized);
        CHECK(stats.trianglesCulled == referenceStats.trianglesCulled);
        CHECK(stats.fragments == referenceStats.fragments);
        CHECK(stats.stencilWrites == referenceStats.stencilWrites);
      }
    CHECK(referenceStats.trianglesCulled > 1000);  // half the grid faces away, in both passes
    CHECK(referenceStats.stencilWrites > 5000);    // the second pass passes EQUAL where the first drew
  }
}

TEST_CASE("kept setups are taken only for the same, unchanged arrays in a state that sets them up alike",
          "[raster][reuse]") {
  const std::string first = freshPicture(0), second = freshPicture(1);
  REQUIRE(first != second);
  SECTION("the same arrays and state: taken") {
    Redrawn m;
    CHECK(m.redraw([](DrawCall&, RenderState&) {}) == first);
    CHECK(m.reused() == 1);
  }
  SECTION("another depth test, blend, stencil op or scissor: taken") {
    Redrawn m;
    CHECK(m.redraw([](DrawCall&, RenderState& s) {
      s.depthTest = true;
      s.depthFunc = CompareFunc::LEqual;
      s.blend = {true, BlendFactor::One, BlendFactor::One};
      s.stencil[0].dppass = StencilOp::IncrWrap;
      s.scissorTest = true;
      s.scissor = {0, 0, 32, 8};
    }) == first);
    CHECK(m.reused() == 1);
  }
  SECTION("culling, front face, polygon offset, depth range, depth clamp or far clipping changed: assembled") {
    const std::vector<std::function<void(RenderState&)>> changes = {
        [](RenderState& s) { s.cull = CullMode::Back; },
        [](RenderState& s) { s.cull = CullMode::Front; },
        [](RenderState& s) { s.frontFace = FrontFace::CW; },
        [](RenderState& s) { s.polygonOffset = {true, 1.0, 1.0}; },
        [](RenderState& s) { s.viewport.nearVal = 0.25; },
        [](RenderState& s) { s.depthClamp = true; },
        [](RenderState& s) { s.clipFar = !s.clipFar; },
    };
    for (size_t i = 0; i < changes.size(); ++i) {
      INFO("change " << i);
      Redrawn m;
      CHECK(m.redraw([&](DrawCall&, RenderState& s) { changes[i](s); }) == freshPicture(0, changes[i]));
      CHECK(m.reused() == 0);
    }
  }
  SECTION("vertices moved in place: assembled, the moved triangle drawn") {
    Redrawn m;
    CHECK(m.redraw([&](DrawCall&, RenderState&) {
      for (int k = 0; k < 3; ++k) m.vertices[size_t(k)].position = m.vertices[size_t(k) + 3].position;
    }) == second);
    CHECK(m.reused() == 0);
  }
  SECTION("indices changed in place: assembled, the other triangle drawn") {
    Redrawn m;
    CHECK(m.redraw([&](DrawCall&, RenderState&) { m.indices = {3, 4, 5}; }) == second);
    CHECK(m.reused() == 0);
  }
  SECTION("a position's 0.0 made -0.0 (equal as numbers, not as bytes): assembled") {
    Redrawn m;
    REQUIRE(std::bit_cast<uint64_t>(m.vertices[0].position.z) == std::bit_cast<uint64_t>(0.0));
    CHECK(m.redraw([&](DrawCall&, RenderState&) { m.vertices[0].position.z = -0.0; }) == first);
    CHECK(m.reused() == 0);
  }
  SECTION("the same contents in another array, or another renderer: assembled") {
    Redrawn m;
    const std::vector<ClipVertex> copy = m.vertices;
    CHECK(m.redraw([&](DrawCall& c, RenderState&) { c.vertices = copy; }) == first);
    CHECK(m.reused() == 0);
    Redrawn o;
    clearStencil(o.fb, o.state, 0);
    Renderer other(o.fb);
    other.draw({.state = &o.state, .vertices = o.vertices, .indices = o.indices, .shader = &o.shader});
    CHECK(stencilPicture(o.fb) == first);
    CHECK(other.drawsReusingSetups() == 0);
  }
  SECTION("the same arrays drawn without a shader (no colour): assembled") {
    Redrawn m;
    CHECK(m.redraw([](DrawCall& c, RenderState&) { c.shader = nullptr; }) == first);
    CHECK(m.reused() == 0);
  }
  SECTION("queued on two threads: taken") {
    Redrawn m(2);
    CHECK(m.redrawQueued(1) == first);
    CHECK(m.reused() == 1);
  }
  SECTION("once per flush: of two draws of the arrays in one flush, the first takes the setups") {
    Redrawn m(2);
    std::string twice = first;
    for (char& c : twice)
      if (c == '1') c = '2';
    CHECK(m.redrawQueued(2) == twice);
    CHECK(m.reused() == 1);
    CHECK(m.redrawQueued(1) == first);  // kept again by the first
    CHECK(m.reused() == 2);
  }
}

TEST_CASE("a draw that clipped a triangle keeps no setups", "[raster][reuse]") {
  Framebuffer fb(16, 16);
  const RenderState s = coverageCountingState(fb);
  const ConstantColorShader shader({1.0, 1.0, 1.0, 1.0});
  std::vector<ClipVertex> v = windowTriangles(s.viewport, {{1, 1, 0.5}, {14, 1, 0.5}, {1, 14, 0.5}});
  Renderer r(fb);
  r.draw({.state = &s, .vertices = v, .indices = {}, .shader = &shader, .tag = 0});
  r.draw({.state = &s, .vertices = v, .indices = {}, .shader = &shader, .tag = 0});
  CHECK(r.drawsReusingSetups() == 1);
  std::vector<ClipVertex> crossing = v;
  crossing[2].position.z = -2.0 * crossing[2].position.w;  // behind the near plane
  r.draw({.state = &s, .vertices = crossing, .indices = {}, .shader = &shader, .tag = 0});
  r.draw({.state = &s, .vertices = crossing, .indices = {}, .shader = &shader, .tag = 0});
  CHECK(r.drawsReusingSetups() == 1);
  CHECK(r.stats().trianglesClipped == 2);
}
