// Fill-rule ties: vertices exactly on pixel centres, so edges run through centres and the
// tie-breaking convention alone decides ownership. shadowref uses the top-left rule in a y-up
// window; this case shows where Mesa's drivers agree (docs/conformance.md §Ties).
#include "conformance/case_builder.h"

using namespace shadowref;
using namespace shadowref::conformance;

TEST_CASE("with vertices on pixel centres, coverage ties are decided like Mesa's (top-left, y up)",
          "[conformance][fillrule]") {
  Scenario sc;
  sc.name = "fill-rule ties: fan and grid with vertices on pixel centres";
  sc.width = sc.height = 64;
  sc.minStencilAgreement = 0.95;
  sc.note = "softpipe breaks ties by float rounding (§Ties)";
  DrawStep d;
  d.state = fullViewportState(64, 64);
  d.state.stencilTest = true;
  for (StencilFaceState& s : d.state.stencil) s.dppass = StencilOp::IncrWrap;
  // A fan of 12 triangles around the centre (32.5, 32.5), rim vertices on centres too.
  const glm::dvec2 rim[12] = {{60.5, 32.5}, {56.5, 48.5}, {44.5, 58.5}, {32.5, 60.5}, {16.5, 56.5}, {6.5, 44.5},
                              {4.5, 32.5},  {8.5, 16.5},  {20.5, 6.5},  {32.5, 4.5},  {48.5, 8.5},  {58.5, 20.5}};
  for (int i = 0; i < 12; ++i) {
    const glm::dvec2 a = rim[i], b = rim[(i + 1) % 12];
    addTriangle(d, {32.5, 32.5, 0}, {a.x, a.y, 0}, {b.x, b.y, 0}, {1, 1, 1, 1});
  }
  // Axis-aligned squares split into two triangles (horizontal and vertical edges on centres).
  for (int k = 0; k < 3; ++k) {
    const double x0 = 2.5 + 20 * k, y0 = 2.5, x1 = x0 + 10, y1 = y0 + 7;
    addTriangle(d, {x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {1, 1, 1, 1});
    addTriangle(d, {x0, y0, 0}, {x1, y1, 0}, {x0, y1, 0}, {1, 1, 1, 1});
  }
  sc.steps.push_back(d);
  checkAgreement(runCase(sc));
}
