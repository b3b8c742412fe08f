#include "conformance/comparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "conformance/edge_mask.h"
#include "osmesa/osmesa_harness.h"
#include "conformance/shadowref_backend.h"

namespace shadowref::conformance {

namespace {

uint32_t absDiff(uint32_t a, uint32_t b) { return a > b ? a - b : b - a; }

double colorDiff255(const glm::vec4& a, const glm::vec4& b) {
  double d = 0;
  for (int c = 0; c < 4; ++c) d = std::max(d, std::fabs(double(a[c]) - double(b[c])) * 255.0);
  return d;
}

std::string describe(int x, int y, const Readback& s, const Readback& m, size_t i) {
  std::ostringstream o;
  o << "(" << x << "," << y << "): stencil " << int(s.stencil[i]) << " vs mesa " << int(m.stencil[i]) << ", depth "
    << s.depth24[i] << " vs " << m.depth24[i] << ", colour (" << s.color[i].r * 255 << "," << s.color[i].g * 255 << ","
    << s.color[i].b * 255 << "," << s.color[i].a * 255 << ") vs (" << m.color[i].r * 255 << "," << m.color[i].g * 255
    << "," << m.color[i].b * 255 << "," << m.color[i].a * 255 << ")";
  return o.str();
}

}  // namespace

CaseResult compare(const Scenario& scenario, const Readback& s, const Readback& m) {
  CaseResult r;
  r.name = scenario.name;
  r.colorTolerance255 = scenario.colorTolerance255;
  r.depthTolerance = scenario.depthTolerance;
  r.minStencilAgreement = scenario.minStencilAgreement;
  r.note = scenario.note;
  const std::vector<bool> edges = edgeMask(scenario);
  const bool verbose = std::getenv("SHADOWREF_CONFORMANCE_VERBOSE") != nullptr;
  for (int y = 0; y < scenario.height; ++y) {
    for (int x = 0; x < scenario.width; ++x) {
      const size_t i = size_t(y) * size_t(scenario.width) + size_t(x);
      ++r.pixels;
      const bool onEdge = edges[i];
      r.edgePixels += onEdge;
      const bool stencilDiffers = s.stencil[i] != m.stencil[i];
      if (stencilDiffers) ++(onEdge ? r.stencilMismatchOnEdge : r.stencilMismatchOffEdge);
      const uint32_t depthDiff = absDiff(s.depth24[i], m.depth24[i]);
      const double colourDiff = colorDiff255(s.color[i], m.color[i]);
      const bool differs = stencilDiffers || depthDiff > scenario.depthTolerance || colourDiff > scenario.colorTolerance255 + 1e-3;
      if (verbose && differs)
        std::cerr << scenario.name << (onEdge ? " edge " : " OFF-EDGE ") << describe(x, y, s, m, i) << "\n";
      if (onEdge) continue;
      r.maxDepthDiff = std::max(r.maxDepthDiff, depthDiff);
      r.maxColorDiff255 = std::max(r.maxColorDiff255, colourDiff);
      if (differs && r.firstOffEdgeDifference.empty()) r.firstOffEdgeDifference = describe(x, y, s, m, i);
    }
  }
  return r;
}

std::string markdownRow(const CaseResult& r) {
  char agreement[32], colour[32];
  std::snprintf(agreement, sizeof agreement, "%.2f %%", 100.0 * r.stencilAgreement());
  std::snprintf(colour, sizeof colour, "%.2f / %.0f", r.maxColorDiff255, r.colorTolerance255);
  std::ostringstream o;
  o << "| " << r.name << " | " << r.driver << " | " << r.pixels << " | " << r.edgePixels << " | " << agreement
    << " | " << r.stencilMismatchOnEdge << " / " << r.stencilMismatchOffEdge << " | " << r.maxDepthDiff << " / "
    << r.depthTolerance << " | " << colour << " | " << (r.meetsIssueExpectation() ? "yes" : r.withinDocumentedBounds() ? "explained" : "**NO**")
    << " | " << r.note << " |";
  return o.str();
}

CaseResult runCase(const Scenario& scenario) {
  const Readback mesa = renderWithMesa(scenario);
  const Readback ours = renderWithShadowref(scenario);
  CaseResult r = compare(scenario, ours, mesa);
  r.driver = mesaDriverName();
  if (const char* path = std::getenv("SHADOWREF_CONFORMANCE_REPORT")) {
    std::ofstream out(path, std::ios::app);
    out << markdownRow(r) << "\n";
  }
  return r;
}

}  // namespace shadowref::conformance
