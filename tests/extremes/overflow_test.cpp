// 300 overlapping shadow volumes in an 8-bit stencil (docs/numerics.md, "Stencil
// overflow"; scenes/overflow.yaml: 256 big plates under 44 small ones, one point light).
//
// Wrapping ops (INCR_WRAP / DECR_WRAP, [SV slides]) keep every count modulo 256, so the stencil is
// the oracle's count mod 256 everywhere; the shadow test (stencil == 0 is lit) is then wrong
// exactly where the count is a non-zero multiple of 256. Saturating ops (INCR / DECR) lose the
// count as soon as it leaves [0, 255]; in two-sided stencil the increments and decrements of one
// pixel arrive in primitive order, so a DECR can clamp at 0 before its INCR arrives.
#include <span>
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "extremes/extreme_scene.h"
#include "scene/scene_loader.h"

using namespace shadowref;
using namespace shadowref::extremes;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr int kOverflowWidth = 100, kOverflowHeight = 80;
#else
constexpr int kOverflowWidth = 200, kOverflowHeight = 160;
#endif

Scene overflowScene(std::vector<std::string> overrides = {}) {
  LoadOptions options;
  options.overrides = {"image.width=" + std::to_string(kOverflowWidth),
                       "image.height=" + std::to_string(kOverflowHeight)};
  options.overrides.insert(options.overrides.end(), overrides.begin(), overrides.end());
  return loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/overflow.yaml", options);
}

struct OverflowCounts {
  size_t at300 = 0, at300Right = 0;      // off-edge pixels with count 300, and those the stencil gets right
  size_t at256 = 0, at256Lit = 0;        // count 256 (≡ 0 mod 256), and those the stencil calls lit
  size_t maskWrong = 0, maskWrongAt0Mod256 = 0;  // off-edge surface pixels with the wrong shadow test
};

OverflowCounts tally(std::span<const uint8_t> stencil, const oracle::OracleImage& img, int expectAt300) {
  OverflowCounts c;
  for (size_t i = 0; i < stencil.size(); ++i) {
    if (img.nearEdge[i]) continue;
    const int count = img.zfail[i];
    if (count == 300) {
      ++c.at300;
      c.at300Right += stencil[i] == expectAt300;
    }
    if (count == 256) {
      ++c.at256;
      c.at256Lit += stencil[i] == 0;
    }
    if (img.hitMask[i] && (stencil[i] == 0) != (img.lit[i] != 0)) {
      ++c.maskWrong;
      c.maskWrongAt0Mod256 += count != 0 && count % 256 == 0;
    }
  }
  return c;
}

}  // namespace

TEST_CASE("300 volumes, wrapping ops: the stencil is the count mod 256 (300 -> 44) on every off-edge pixel, the "
          "shadow test fails exactly where the count is 256", "[extremes]") {
  const Scene scene = overflowScene();
  const oracle::OracleImage img = castFor(scene);
  const FrameResult frame = renderStencil(scene, "zfail");
  const Agreement a = compare(frame.stencilPerLight.at(0), img, "zfail");
  const OverflowCounts c = tally(frame.stencilPerLight[0], img, 300 - 256);
  INFO(describe(a) << "\n300: " << c.at300 << " (" << c.at300Right << " read 44), 256: " << c.at256 << " ("
                   << c.at256Lit << " read 0), wrong shadow test " << c.maskWrong);
  CHECK(a.countMismatch == 0);
  CHECK(c.at300 > 0);
  CHECK(c.at300Right == c.at300);
  CHECK(c.at256 > 0);
  CHECK(c.at256Lit == c.at256);                 // in shadow, but the test says lit
  CHECK(c.maskWrong == c.maskWrongAt0Mod256);   // and nowhere else
  CHECK(c.maskWrong >= c.at256);
}

TEST_CASE("300 volumes, saturating ops in two passes (increments first): counts clamp at 255, so the stencil is "
          "wrong where the count passes 255, while in this scene the shadow test stays right", "[extremes]") {
  const Scene scene = overflowScene({"shadow.wrap=false", "shadow.two_sided=false"});
  const oracle::OracleImage img = castFor(scene);
  const FrameResult frame = renderStencil(scene, "zfail");
  const Agreement a = compare(frame.stencilPerLight.at(0), img, "zfail");
  const OverflowCounts c = tally(frame.stencilPerLight[0], img, 255);
  INFO(describe(a) << "\n300: " << c.at300 << " (" << c.at300Right << " read 255), wrong shadow test " << c.maskWrong);
  CHECK(a.countMismatch > 0);  // the counts are not kept ...
  CHECK(c.at300 > 0);
  CHECK(c.at300Right == c.at300);  // ... 300 reads 255
  CHECK(c.maskWrong == 0);         // ... but z-fail's increments all come before its decrements here
}

TEST_CASE("300 volumes, saturating ops with two-sided stencil: a DECR clamps at 0 before its INCR arrives, the count "
          "and the shadow test go wrong", "[extremes]") {
  const Scene scene = overflowScene({"shadow.wrap=false"});
  const oracle::OracleImage img = castFor(scene);
  const FrameResult frame = renderStencil(scene, "zfail");
  const Agreement a = compare(frame.stencilPerLight.at(0), img, "zfail");
  const OverflowCounts c = tally(frame.stencilPerLight[0], img, 255);
  INFO(describe(a) << "\nwrong shadow test " << c.maskWrong);
  CHECK(a.countMismatch > 0);
  CHECK(c.maskWrong > 0);
}
