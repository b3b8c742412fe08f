#include "conformance/case_builder.h"

#include <cmath>
#include <random>

namespace shadowref::conformance {

glm::dvec4 windowToClip(const Viewport& vp, double wx, double wy, double zNdc, double w) {
  const double xn = (wx - vp.x) / vp.width * 2.0 - 1.0;
  const double yn = (wy - vp.y) / vp.height * 2.0 - 1.0;
  return {xn * w, yn * w, zNdc * w, w};
}

void addTriangle(DrawStep& d, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec4& color) {
  for (const glm::dvec3& p : {a, b, c})
    d.vertices.push_back({windowToClip(d.state.viewport, p.x, p.y, p.z), color});
}

std::vector<ColoredVertex> triangleSoup(const Viewport& vp, int count, uint32_t seed, bool onSubpixelGrid,
                                        double margin) {
  // std::mt19937 is specified exactly by the standard; the distributions are not, so values are
  // derived from raw 32-bit draws.
  std::mt19937 rng(seed);
  auto unit = [&] { return double(rng()) / 4294967296.0; };
  auto coordinate = [&](double lo, double hi) {
    const double v = lo + (hi - lo) * unit();
    return onSubpixelGrid ? std::round(v * 256.0) / 256.0 : v;
  };
  std::vector<ColoredVertex> out;
  for (int t = 0; t < count; ++t) {
    for (int k = 0; k < 3; ++k) {
      const double wx = coordinate(vp.x - margin, vp.x + vp.width + margin);
      const double wy = coordinate(vp.y - margin, vp.y + vp.height + margin);
      const double z = std::round((unit() * 1.8 - 0.9) * 65536.0) / 65536.0;
      const glm::dvec4 colour(unit(), unit(), unit(), unit());
      out.push_back({windowToClip(vp, wx, wy, z), colour});
    }
  }
  return out;
}

void checkAgreement(const CaseResult& r) {
  INFO("case " << r.name << " on " << r.driver << ": " << r.pixels << " pixels, " << r.edgePixels << " on edges");
  INFO("stencil mismatches on/off edge " << r.stencilMismatchOnEdge << "/" << r.stencilMismatchOffEdge
                                          << ", max depth diff " << r.maxDepthDiff << ", max colour diff "
                                          << r.maxColorDiff255 << "/255");
  INFO("note: " << r.note);
  INFO("first off-edge difference: " << r.firstOffEdgeDifference);
  CHECK(r.stencilAgreement() >= r.minStencilAgreement);
  CHECK(r.stencilMismatchOffEdge == 0);
  CHECK(r.maxDepthDiff <= r.depthTolerance);
  CHECK(r.maxColorDiff255 <= r.colorTolerance255 + 1e-3);
}

}  // namespace shadowref::conformance
