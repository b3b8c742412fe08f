#include "support/raster_harness.h"

#include <sstream>

#include <catch2/catch.hpp>

namespace shadowref::testing {

RenderState fullViewportState(const Framebuffer& fb) {
  RenderState s;
  s.viewport = Viewport{0, 0, fb.width(), fb.height(), 0.0, 1.0};
  return s;
}

ClipVertex windowVertex(const Viewport& vp, double x, double y, double z) {
  ClipVertex v;
  v.position = glm::dvec4(2.0 * (x - vp.x) / vp.width - 1.0, 2.0 * (y - vp.y) / vp.height - 1.0,
                          2.0 * z - 1.0, 1.0);
  return v;
}

std::vector<ClipVertex> windowTriangles(const Viewport& vp, std::initializer_list<glm::dvec3> points) {
  std::vector<ClipVertex> out;
  for (const glm::dvec3& p : points) out.push_back(windowVertex(vp, p.x, p.y, p.z));
  return out;
}

std::vector<ClipVertex> windowRect(const Viewport& vp, double x0, double y0, double x1, double y1, double z) {
  return windowTriangles(vp, {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y0, z}, {x1, y1, z}, {x0, y1, z}});
}

void draw(Renderer& renderer, const RenderState& state, const std::vector<ClipVertex>& vertices,
          const FragmentShader* shader, uint32_t tag) {
  DrawCall call;
  call.state = &state;
  call.vertices = vertices;
  call.shader = shader;
  call.tag = tag;
  renderer.draw(call);
}

void draw(Pipeline& pipeline, const RenderState& state, const std::vector<ClipVertex>& vertices,
          const FragmentShader* shader, uint32_t tag) {
  pipeline.draw({.state = &state, .vertices = vertices, .indices = {}, .shader = shader, .tag = tag});
}

RenderState coverageCountingState(const Framebuffer& fb) {
  RenderState s = fullViewportState(fb);
  s.stencilTest = true;
  for (StencilFaceState& face : s.stencil) {
    face.func = CompareFunc::Always;
    face.sfail = face.dpfail = face.dppass = StencilOp::Incr;
  }
  return s;
}

std::string picture(int width, int height, const std::function<char(int x, int y)>& pixel) {
  std::string out;
  for (int y = height - 1; y >= 0; --y) {
    for (int x = 0; x < width; ++x) out += pixel(x, y);
    if (y > 0) out += '\n';
  }
  return out;
}

std::string stencilPicture(const Framebuffer& fb) {
  return picture(fb.width(), fb.height(), [&](int x, int y) {
    const int v = fb.hasStencil() ? fb.stencilAt(x, y) : 0;
    if (v == 0) return '.';
    if (v < 10) return char('0' + v);
    if (v < 36) return char('a' + v - 10);
    return '#';
  });
}

std::string rows(std::initializer_list<const char*> lines) {
  std::string out;
  for (const char* line : lines) {
    if (!out.empty()) out += '\n';
    out += line;
  }
  return out;
}

void addTriangle(std::vector<uint32_t>& indices, uint32_t a, uint32_t b, uint32_t c, Winding winding, TestRandom& rng) {
  const bool flip = winding == Winding::CW || (winding == Winding::Mixed && rng.below(2) == 1);
  indices.insert(indices.end(), {a, flip ? c : b, flip ? b : c});
}

std::vector<uint32_t> gridTriangles(int nx, int ny, Winding winding, TestRandom& rng) {
  std::vector<uint32_t> indices;
  auto at = [nx](int i, int j) { return uint32_t(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (rng.below(2) == 0) {  // the diagonal a-c
        addTriangle(indices, a, b, c, winding, rng);
        addTriangle(indices, a, c, d, winding, rng);
      } else {  // the diagonal b-d
        addTriangle(indices, a, b, d, winding, rng);
        addTriangle(indices, b, c, d, winding, rng);
      }
    }
  return indices;
}

void requireCoverage(const Framebuffer& fb, const Polygon2& outline) {
  int wrong = 0, inside = 0;
  const std::string pic = picture(fb.width(), fb.height(), [&](int x, int y) {
    const int count = fb.stencilAt(x, y);
    const int expected = expectedCoverage(outline, {x + 0.5, y + 0.5}, kEdgeMargin);
    inside += expected == 1;
    const bool ok = count <= 1 && (expected < 0 || count == expected);
    wrong += !ok;
    if (ok) return count == 0 ? '.' : '1';
    return count == 0 ? 'o' : 'X';
  });
  INFO("o: missing, X: wrong count\n" << pic);
  CHECK(wrong == 0);
  CHECK(inside > 0);
}

}  // namespace shadowref::testing
