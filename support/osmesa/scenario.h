// A conformance case as data: the steps (clears, draws, accumulation operations) that are
// captured as a trace and replayed on shadowref and on Mesa with the same clip-space vertices and
// the same render state (tests/conformance/comparison.h, docs/conformance.md).
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include "gl/accumulation.h"
#include "gl/render_state.h"

namespace shadowref::conformance {

// Clip-space position (given to GL as glVertex4d with identity matrices) and RGBA colour (GL:
// glColor4d with GL_SMOOTH; shadowref: varyings 0..3 through ColorVaryingShader).
struct ColoredVertex {
  glm::dvec4 clip{0.0, 0.0, 0.0, 1.0};
  glm::dvec4 color{1.0};
};

struct DrawStep {
  RenderState state;
  std::vector<ColoredVertex> vertices;  // three per triangle
};

// glClear of the chosen buffers under `state` (scissor box, colour mask, depth mask and the front
// stencil write mask apply).
struct ClearStep {
  RenderState state;
  bool color = false, depth = false, stencil = false, accum = false;
  glm::vec4 colorValue{0.0f};
  double depthValue = 1.0;
  int stencilValue = 0;
  glm::vec4 accumValue{0.0f};
};

// glAccum(op, value) under `state` (scissor box; the colour mask for RETURN).
struct AccumStep {
  RenderState state;
  AccumOp op = AccumOp::Accum;
  float value = 1.0f;
};

using Step = std::variant<DrawStep, ClearStep, AccumStep>;

struct Scenario {
  std::string name;
  int width = 64, height = 64;
  // Every scenario starts with all four buffers cleared to colour 0, depth 1, stencil 0, accum 0
  // (GL leaves a new context's buffers undefined).
  std::vector<Step> steps;
  // Colour may differ by this much (in units of 1/255): 1 for a single write; additive blending
  // of n passes rounds to 8 bits after each pass in Mesa, so n (see docs/conformance.md).
  double colorTolerance255 = 1.0;
  // Depth may differ by this many 24-bit units. The aim is 1; Mesa interpolates depth in
  // float32 (one ulp is one 24-bit unit for z in [0.5, 1)) and truncates when converting, so it
  // is up to 2 units from the exact value that shadowref rounds to ("depth is exact" test,
  // docs/conformance.md §Depth precision).
  uint32_t depthTolerance = 2;
  // Fraction of pixels whose stencil must be identical: 0.999, which leaves room only for edge
  // pixels. A case lowers it only together with a `note` naming the documented cause
  // (docs/conformance.md).
  double minStencilAgreement = 0.999;
  std::string note;
};


// The default state of a draw over the whole framebuffer: viewport = framebuffer, all tests off.
RenderState fullViewportState(int width, int height);

}  // namespace shadowref::conformance
