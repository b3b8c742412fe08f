// Test helpers for the raster pipeline: triangles given in window (pixel) coordinates, a
// framebuffer-sized viewport, and buffers printed as pictures so a failing test shows the image.
//
// A window point (x, y, z) becomes the clip vertex (x_ndc, y_ndc, z_ndc, 1) with the viewport equal to
// the framebuffer and depth range [0, 1]. With power-of-two framebuffer sizes the round trip
// window -> NDC -> window is exact for every dyadic coordinate, so tests can place vertices exactly
// on pixel centres (x + 0.5) and edges exactly through them.
#pragma once

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/fragment_shader.h"
#include "gl/framebuffer.h"
#include "gl/pipeline.h"
#include "gl/render_state.h"
#include "exec/renderer.h"
#include "gl/vertex.h"
#include "support/polygon_geometry.h"

namespace shadowref::testing {

// A render state whose viewport is the whole framebuffer, depth range [0, 1], everything else GL's
// defaults (no tests, no culling, no blending).
RenderState fullViewportState(const Framebuffer& fb);

// The clip vertex with w = 1 that lands on window position (x, y) at window depth z.
ClipVertex windowVertex(const Viewport& vp, double x, double y, double z = 0.5);

// Triangles from consecutive triples of window points (x, y, z), in the order given.
std::vector<ClipVertex> windowTriangles(const Viewport& vp, std::initializer_list<glm::dvec3> points);

// The rectangle [x0, x1] x [y0, y1] at depth z as two counter-clockwise triangles.
std::vector<ClipVertex> windowRect(const Viewport& vp, double x0, double y0, double x1, double y1,
                                   double z = 0.5);

void draw(Renderer& renderer, const RenderState& state, const std::vector<ClipVertex>& vertices,
          const FragmentShader* shader = nullptr, uint32_t tag = 0);
// The same through a pipeline: the draw borrows `state` and `vertices` until its pass ends.
void draw(Pipeline& pipeline, const RenderState& state, const std::vector<ClipVertex>& vertices,
          const FragmentShader* shader = nullptr, uint32_t tag = 0);

// How a mesh's triangles wind: all counter-clockwise, all clockwise, or each either way at random.
enum class Winding { CCW, CW, Mixed };
class TestRandom;

// The triangle (a, b, c), given counter-clockwise, appended to `indices` wound as `winding` says
// (Mixed: a coin of `rng` per triangle).
void addTriangle(std::vector<uint32_t>& indices, uint32_t a, uint32_t b, uint32_t c, Winding winding, TestRandom& rng);

// The triangles of an (nx + 1) x (ny + 1) grid of points, point (i, j) at index j * (nx + 1) + i
// with i growing to the right and j upwards: two per cell, split along a diagonal chosen by `rng`,
// wound as `winding` says. Every cell is covered by its two triangles exactly once.
std::vector<uint32_t> gridTriangles(int nx, int ny, Winding winding, TestRandom& rng);

// A state that counts coverage: stencil test on, func ALWAYS, every op INCR on both faces (the
// counting pass of the watertightness tests), no culling, no colour.
RenderState coverageCountingState(const Framebuffer& fb);

// Checks (Catch) a coverage count left by coverageCountingState against the outline it drew: every
// pixel centre farther than kEdgeMargin from the outline counts 1 inside and 0 outside, none more
// than 1, and some lie inside. A failure prints the picture: 'o' missing, 'X' a wrong count.
void requireCoverage(const Framebuffer& fb, const Polygon2& outline);

// One character per pixel, the top row first (row 0 is the bottom, as in the framebuffer), rows
// separated by '\n'.
std::string picture(int width, int height, const std::function<char(int x, int y)>& pixel);
// Stencil as a picture: '.' for 0, '1'..'9', then 'a'.. for 10.., '#' from 36 on.
std::string stencilPicture(const Framebuffer& fb);
// Joins picture rows written top row first, as they appear in the test source.
std::string rows(std::initializer_list<const char*> lines);

// Seeded, library-independent random numbers: std::mt19937_64's sequence is fixed by the standard
// (the std distributions are not), and the top 53 bits make a double in [0, 1). The random tests
// therefore draw the same geometry with every standard library.
class TestRandom {
 public:
  explicit TestRandom(uint64_t seed) : engine_(seed) {}
  double uniform() { return double(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  int below(int n) { return int(uniform() * double(n)); }  // 0 .. n-1
  uint64_t bits() { return engine_(); }  // 64 random bits

 private:
  std::mt19937_64 engine_;
};

}  // namespace shadowref::testing
