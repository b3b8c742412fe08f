// A conformance scenario run as `shadowref replay` runs a captured frame: the scenario's steps are
// captured through the trace recorder (src/trace/trace_recorder.h), read back from the trace
// format, replayed on shadowref's reference pipeline and on Mesa (OSMesa, the driver
// GALLIUM_DRIVER names) in the fixed-function mode, and compared by the replay's comparison
// (src/trace/trace_compare.h) with the case's tolerances; the report row it contributes to
// docs/conformance.md (scripts/conformance-report.sh).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "osmesa/scenario.h"
#include "trace/trace.h"
#include "trace/trace_compare.h"

namespace shadowref::conformance {

struct CaseResult {
  std::string name, driver;
  size_t pixels = 0;            // every pixel of the framebuffer
  size_t edgePixels = 0;        // of which within one pixel of a primitive edge
  size_t stencilMismatchOnEdge = 0, stencilMismatchOffEdge = 0;
  uint32_t maxDepthDiff = 0;    // 24-bit units, off edges
  double maxColorDiff255 = 0;   // in units of 1/255, off edges
  double colorTolerance255 = 1;
  uint32_t depthTolerance = 2;
  double minStencilAgreement = 0.999;
  std::string note;
  std::string firstOffEdgeDifference;  // where to look when something fails

  size_t stencilMismatches() const { return stencilMismatchOnEdge + stencilMismatchOffEdge; }
  double stencilAgreement() const { return pixels ? 1.0 - double(stencilMismatches()) / double(pixels) : 1.0; }
  // The conformance expectation: stencil identical on >= 99.9 % with differences only at edges,
  // depth within one 24-bit unit, colour within the case's tolerance (one 1/255 per pass).
  bool meetsIssueExpectation() const {
    return stencilAgreement() >= 0.999 && stencilMismatchOffEdge == 0 && maxDepthDiff <= 1 &&
           maxColorDiff255 <= colorTolerance255 + 1e-3;
  }
  // What the test asserts: the issue's expectation, or the documented bounds of a case with a note.
  bool withinDocumentedBounds() const {
    return stencilAgreement() >= minStencilAgreement && stencilMismatchOffEdge == 0 &&
           maxDepthDiff <= depthTolerance && maxColorDiff255 <= colorTolerance255 + 1e-3;
  }
};

// The scenario as a captured trace: one framebuffer of the scenario's size with 24-bit depth,
// every step a command (draws with ColorVaryingShader, colour in varyings 0..3), each step
// ending a pass; written by the recorder and parsed back. With SHADOWREF_CONFORMANCE_TRACES
// naming a folder, the trace is also written there as <case>.srtrace for `shadowref replay`.
trace::Trace captureScenario(const Scenario& scenario);

// Both sides' buffers of a scenario's trace, replayed in the fixed-function mode.
struct Replayed {
  trace::Trace trace;
  trace::Buffers shadowref, mesa;
};
Replayed replayScenario(const Scenario& scenario);

// The replay's comparison (trace::compareBuffers) with the scenario's tolerances, as a row.
CaseResult compare(const Scenario& scenario, const Replayed& replayed);

// Replays and compares. When the environment variable SHADOWREF_CONFORMANCE_REPORT names a
// file, appends the case's markdown table row to it; with SHADOWREF_CONFORMANCE_VERBOSE set,
// prints the replay's text report.
CaseResult runCase(const Scenario& scenario);

std::string markdownRow(const CaseResult& r);

}  // namespace shadowref::conformance
