// The fast pipeline behind the Pipeline interface: passes of the draw contract (gl/pipeline.h),
// where the caller may change its arrays between passes, against the same draws made afresh. The
// executor finds the draws whose setups it kept by itself; its count shows whether it did.
#include <cstring>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/fast_pipeline.h"
#include "gl/projection.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

// A bumpy indexed grid of n × n quads in front of a perspective camera (nothing clipped), with
// colour varyings; `lift` raises its vertices (a caller that moves its geometry between passes).
void fillGrid(std::vector<ClipVertex>& vertices, std::vector<uint32_t>& indices, double lift) {
  TestRandom rng(7);
  const glm::dmat4 p = perspective(70.0, 1.25, 0.5, 50.0);
  constexpr int n = 24;
  vertices.clear();
  indices.clear();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      ClipVertex v;
      v.position = p * glm::dvec4(-6.0 + 12.0 * i / n, -2.0 + lift + rng.uniform(-0.6, 0.6), -1.0 - 14.0 * j / n, 1.0);
      for (int k = 0; k < 4; ++k) v.varyings[size_t(k)] = rng.uniform(0.0, 1.0);
      vertices.push_back(v);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      indices.insert(indices.end(), {a, b, c, b, d, c});
    }
}

struct Passes {
  RenderState fill, add;
  ColorVaryingShader shader;
  explicit Passes(const Framebuffer& fb) {
    fill = fullViewportState(fb);
    fill.depthTest = true;
    fill.cull = CullMode::Back;
    add = fill;
    add.depthFunc = CompareFunc::Equal;
    add.blend = {true, BlendFactor::One, BlendFactor::One};
  }
};

template <class T>
bool sameBytes(const PixelVector<T>& a, const PixelVector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

}  // namespace

TEST_CASE("the fast pipeline takes kept setups only for arrays unchanged since they were set up",
          "[raster][reuse][pipeline]") {
  for (int threads : {1, 2}) {
    INFO(threads << " threads");
    // The grid drawn in a depth pass, then again in an additive pass, through one pipeline, with
    // the arrays unchanged or lifted in place in between; the reference draws each pass's grid
    // from arrays of its own (nothing to take).
    for (const bool lifted : {false, true}) {
      INFO("lifted " << lifted);
      Framebuffer fb(96, 64), fresh(96, 64);
      const Passes s(fb);
      std::vector<ClipVertex> vertices;
      std::vector<uint32_t> indices;
      fillGrid(vertices, indices, 0.0);
      FastPipeline pipeline(fb, threads);
      pipeline.clear({.state = s.fill, .color = glm::vec4(0.0f), .depth = 1.0});
      pipeline.draw({.state = &s.fill, .vertices = vertices, .indices = indices, .shader = &s.shader});
      pipeline.endPass();
      if (lifted) fillGrid(vertices, indices, 0.5);
      pipeline.draw({.state = &s.add, .vertices = vertices, .indices = indices, .shader = &s.shader});
      pipeline.endPass();
      CHECK(pipeline.renderer().drawsReusingSetups() == (lifted ? 0u : 1u));

      std::vector<ClipVertex> firstVertices, secondVertices;
      std::vector<uint32_t> firstIndices, secondIndices;
      fillGrid(firstVertices, firstIndices, 0.0);
      fillGrid(secondVertices, secondIndices, lifted ? 0.5 : 0.0);
      FastPipeline reference(fresh, threads);
      reference.clear({.state = s.fill, .color = glm::vec4(0.0f), .depth = 1.0});
      reference.draw({.state = &s.fill, .vertices = firstVertices, .indices = firstIndices, .shader = &s.shader});
      reference.draw({.state = &s.add, .vertices = secondVertices, .indices = secondIndices, .shader = &s.shader});
      CHECK(sameBytes(reference.framebuffer().color(), pipeline.framebuffer().color()));
      CHECK(sameBytes(reference.framebuffer().depthCodes(), pipeline.framebuffer().depthCodes()));
      CHECK(reference.renderer().drawsReusingSetups() == 0);
      CHECK(pipeline.stats().fragments == reference.stats().fragments);
      CHECK(pipeline.stats().fragments > 1000);
    }
  }
}

TEST_CASE("the fast pipeline assembles again when a state field that enters a setup changes",
          "[raster][reuse][pipeline]") {
  Framebuffer fb(96, 64), fresh(96, 64);
  const Passes s(fb);
  RenderState offset = s.add;
  offset.depthFunc = CompareFunc::LEqual;
  offset.polygonOffset = {true, 0.0, -4.0};  // towards the viewer: passes LEQUAL where the grid is
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;
  fillGrid(vertices, indices, 0.0);
  FastPipeline pipeline(fb, 1), reference(fresh, 1);
  const std::vector<ClipVertex> copy = vertices;
  for (FastPipeline* p : {&pipeline, &reference}) {
    p->clear({.state = s.fill, .color = glm::vec4(0.0f), .depth = 1.0});
    p->draw({.state = &s.fill, .vertices = vertices, .indices = indices, .shader = &s.shader});
    p->endPass();
    p->draw({.state = &offset, .vertices = p == &pipeline ? vertices : copy, .indices = indices, .shader = &s.shader});
    p->endPass();
  }
  CHECK(pipeline.renderer().drawsReusingSetups() == 0);
  CHECK(sameBytes(reference.framebuffer().color(), pipeline.framebuffer().color()));
  CHECK(sameBytes(reference.framebuffer().depthCodes(), pipeline.framebuffer().depthCodes()));
}
