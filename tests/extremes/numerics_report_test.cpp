// The tables of docs/numerics.md, printed as Markdown (hidden test; run with
//   ./build/tests/shadowref_tests "[.numerics]"
// and paste). The asserting tests are in the other files of tests/extremes; this one only measures
// the wider sweeps the document shows.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "extremes/depth_code.h"
#include "extremes/extreme_scene.h"
#include "gl/projection.h"

using namespace shadowref;
using namespace shadowref::extremes;

namespace {

const char* formatName(DepthFormat f) { return f == DepthFormat::Float32 ? "float32" : "unorm24"; }

void nearPlaneTable() {
  std::printf("\n| near | depth | codes across the scene (d = 3 ... 12) | compared | count mismatches | share | shadow mask agreement |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
  for (DepthFormat format : {DepthFormat::Float32, DepthFormat::Unorm24})
    for (double nearPlane : {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
      Scene scene = boxOnGround();
      scene.camera.nearPlane = nearPlane;
      scene.depthFormat = format;
      const Agreement a = renderAndCompare(scene, "zfail");
      const uint64_t codes = codesBetween(infinitePerspective(50.0, 1.25, nearPlane), 3.0, 12.0, format);
      std::printf("| %g | %s | %llu | %zu | %zu | %.4f %% | %.4f %% |\n", nearPlane, formatName(format),
                  static_cast<unsigned long long>(codes), a.compared, a.countMismatch,
                  100.0 * double(a.countMismatch) / double(a.compared), 100.0 * a.maskAgreement());
    }
}

void similarityTable() {
  std::printf("\n| transform | compared | count mismatches | mask disagreements (all / off edges) | mask agreement |\n");
  std::printf("| --- | --- | --- | --- | --- |\n");
  struct Case {
    const char* name;
    double scale, offset;
  };
  for (const Case& c : {Case{"none", 1.0, 0.0}, Case{"translate 1e4", 1.0, 1e4}, Case{"translate 1e6", 1.0, 1e6},
                        Case{"translate 1e8", 1.0, 1e8}, Case{"scale 1e-4", 1e-4, 0.0}, Case{"scale 1e4", 1e4, 0.0},
                        Case{"scale 1e-4, translate 1e2", 1e-4, 1e2}}) {
    const Scene scene = similar(boxOnGround(), c.scale, glm::dvec3(c.offset, 0.5 * c.offset, -c.offset));
    const Agreement a = renderAndCompare(scene, "zfail");
    std::printf("| %s | %zu | %zu | %zu / %zu | %.4f %% |\n", c.name, a.compared, a.countMismatch, a.maskDisagree,
                a.maskDisagreeOffEdge, 100.0 * a.maskAgreement());
  }
}

void depthRatioTable() {
  std::printf("\n| interval (n = 1) | codes, far 100 (unorm24) | P_inf / far 100 (unorm24) | codes, far 100 (float32) | P_inf / far 100 (float32) |\n");
  std::printf("| --- | --- | --- | --- | --- |\n");
  const glm::dmat4 finite = perspective(60.0, 1.0, 1.0, 100.0);
  const glm::dmat4 infinite = infinitePerspective(60.0, 1.0, 1.0);
  const double intervals[][2] = {{1.01, 1.5}, {1.5, 2.0}, {2.0, 3.0}, {5.0, 6.0}, {10.0, 11.0}, {50.0, 51.0}, {90.0, 100.0}};
  for (const auto& i : intervals) {
    const uint64_t fu = codesBetween(finite, i[0], i[1], DepthFormat::Unorm24);
    const uint64_t iu = codesBetween(infinite, i[0], i[1], DepthFormat::Unorm24);
    const uint64_t ff = codesBetween(finite, i[0], i[1], DepthFormat::Float32);
    const uint64_t jf = codesBetween(infinite, i[0], i[1], DepthFormat::Float32);
    std::printf("| [%g, %g) | %llu | %.5f | %llu | %.5f |\n", i[0], i[1], static_cast<unsigned long long>(fu),
                double(iu) / double(fu), static_cast<unsigned long long>(ff), double(jf) / double(ff));
  }
}

void farPlaneTable() {
  std::printf("\n| far (near 0.1) | float32: distance per code at d = 10 | unorm24: distance per code at d = 10 | float32 code shift vs P_inf (max over d) |\n");
  std::printf("| --- | --- | --- | --- |\n");
  const glm::dmat4 infinite = infinitePerspective(60.0, 1.0, 0.1);
  for (double farPlane : {1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9}) {
    const glm::dmat4 finite = perspective(60.0, 1.0, 0.1, farPlane);
    const double span = 0.1;  // [10, 10.1)
    const double f32 = span / double(codesBetween(finite, 10.0, 10.0 + span, DepthFormat::Float32));
    const double u24 = span / double(codesBetween(finite, 10.0, 10.0 + span, DepthFormat::Unorm24));
    int64_t shift = 0;
    for (int k = 1; k <= 200; ++k) {
      const double d = 0.1 * std::pow(farPlane / 0.1, k / 200.0);
      shift = std::max(shift, std::abs(int64_t(depthCode(finite, d, DepthFormat::Float32)) -
                                       int64_t(depthCode(infinite, d, DepthFormat::Float32))));
    }
    std::printf("| %g | %.3g | %.3g | %lld |\n", farPlane, f32, u24, static_cast<long long>(shift));
  }
  std::printf("| P_inf | %.3g | %.3g | 0 |\n",
              0.1 / double(codesBetween(infinite, 10.0, 10.1, DepthFormat::Float32)),
              0.1 / double(codesBetween(infinite, 10.0, 10.1, DepthFormat::Unorm24)));
}

}  // namespace

TEST_CASE("docs/numerics.md tables", "[.numerics]") {
  nearPlaneTable();
  similarityTable();
  depthRatioTable();
  farPlaneTable();
  SUCCEED();
}
