// The buffers of a replay against the expected ones (the trace's own result, or a replay on
// another target), buffer by buffer, each differing pixel classified as on a triangle edge / a
// fill-rule tie (edge_mask.h) or elsewhere, and the report (text, and HTML with pictures).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "trace/trace.h"

namespace shadowref::trace {

// What may differ. Exact: nothing (a shadowref pipeline against the trace). Otherwise the bounds
// of docs/conformance.md, off the edges: colour by `colorTolerance255` (in 1/255; one 8-bit
// rounding per write or blended pass), depth by `depthTolerance` 24-bit codes, stencil not at all.
struct Tolerances {
  bool exact = true;
  double colorTolerance255 = 1.0;
  uint32_t depthTolerance = 2;
};

struct BufferComparison {
  std::string buffer;     // "colour", "depth", "stencil", "accumulation"
  bool comparable = true; // false: present on one side only
  size_t pixels = 0, edgePixels = 0;
  size_t differing = 0, differingOnEdge = 0, differingOffEdge = 0;  // beyond the tolerance
  // Of the differing pixels off the edges, depth only, against a GL: those within the bound of a
  // near-plane cut (edge_mask.h, NearCutBound), not counted in differingOffEdge.
  size_t differingNearCut = 0;
  double maxDifference = 0, maxDifferenceOffEdge = 0;  // colour 1/255, depth codes, stencil values
  double tolerance = 0;
  std::vector<uint8_t> differs;  // per pixel: 0 same, 1 on an edge, 2 off the edges, 3 near-plane cut
  std::string firstOffEdge;      // "(x,y): expected ... got ..."
  bool passes() const { return comparable && differingOffEdge == 0; }
};

struct TargetComparison {
  uint32_t target = 0;
  int width = 0, height = 0;
  std::vector<BufferComparison> buffers;
  bool passes() const;
};

struct Comparison {
  std::string expectedName, actualName;
  std::vector<TargetComparison> targets;
  bool passes() const;
};

// The colour tolerance of a target against an 8-bit GL: 1/255 for the last write, plus 1/255
// for every pass of blended draws and every accumulation operation (each rounds what is stored).
double fixedFunctionColorTolerance(const Trace& trace, uint32_t target);

// The depth tolerance of a target against a GL: `base` codes plus the largest |units| of its
// polygon-offset draws — Mesa moves depth by 2 codes per unit where shadowref moves it by 1
// (r = 1/(2^24 - 1), docs/conformance.md §Polygon offset) — plus 1 when it has any: Mesa adds
// the offset to its float depth, one more rounding.
uint32_t fixedFunctionDepthTolerance(const Trace& trace, uint32_t target, uint32_t base);

// Compares expected[t] with actual[t] for every target both have. Against a GL (tolerances not
// exact), a depth difference off the edges at a pixel of a triangle the near plane cuts is
// explained up to the tolerance plus that cut's bound (NearCutBound).
Comparison compareBuffers(const Trace& trace, const std::vector<const Buffers*>& expected,
                          const std::vector<Buffers>& actual, const std::vector<Tolerances>& tolerances);

// The report as text: per target and buffer, pixels, differing on / off the edges, the largest
// difference off the edges and the verdict.
std::string reportText(const Comparison& c);

// Writes `folder`/index.html and per target and buffer PNGs of the expected and actual buffer and
// of the differing pixels (yellow on an edge, red elsewhere). Throws std::runtime_error.
void writeReportHtml(const Comparison& c, const std::vector<const Buffers*>& expected, const std::vector<Buffers>& actual,
                     const std::string& folder);

}  // namespace shadowref::trace
