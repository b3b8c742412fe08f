// The rasterized stencil shadow volumes checked against the independent ray-cast oracle
// (src/oracle/oracle.h).
//
// The oracle never touches the rasterizer: it counts the signed crossings of the volume polygons
// along each pixel's ray in double precision. The stencil after a light's volume pass must hold
// that count — as an 8-bit wrapping value, so the comparison is modulo 256 — on every pixel the
// oracle does not mark as near an edge, and the shadow mask (stencil == 0 means lit) must agree
// with the oracle's shadow rays on >= 99.9 % of the pixels.
#include <span>
#include <catch2/catch.hpp>

#include <cstdint>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "shadow/frame_renderer.h"
#include "shadow/occlusion_pyramid.h"
#include "shadow/scene_passes.h"
#include "shadow/scene_view.h"
#include "oracle/oracle.h"
#include "support/scene_oracle.h"

using namespace shadowref;
using oracle::OracleImage;
using testing::drawnLights;
using testing::renderWithStencil;

namespace {

// About the golden size; smaller under AddressSanitizer, where the oracle is slow.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kWidth = 100, kHeight = 80;
#else
constexpr int kWidth = 200, kHeight = 160;
#endif

Scene documentScene(const std::string& name, std::vector<std::string> overrides = {}) {
  return testing::sceneAtSize(name + ".yaml", kWidth, kHeight, overrides);
}

// An 8-bit wrapping stencil holds a count modulo 256 (INCR_WRAP / DECR_WRAP, [SV slides]).
uint8_t wrapped(int count) { return static_cast<uint8_t>(count & 0xFF); }
int asSigned(uint8_t value) { return static_cast<int8_t>(value); }

struct CountCheck {
  size_t compared = 0, mismatched = 0, nonZero = 0;
  std::string firstMismatch;
};

// Stencil against the oracle's count on every pixel not marked nearEdge.
CountCheck compareCounts(std::span<const uint8_t> stencil, const OracleImage& img, const std::vector<int>& counts) {
  CountCheck c;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const size_t i = img.index(x, y);
      if (img.nearEdge[i]) continue;
      ++c.compared;
      c.nonZero += counts[i] != 0;
      if (stencil[i] == wrapped(counts[i])) continue;
      if (c.mismatched++ == 0) {
        std::ostringstream s;
        s << "pixel " << x << "," << y << ": stencil " << asSigned(stencil[i]) << ", oracle " << counts[i];
        c.firstMismatch = s.str();
      }
    }
  return c;
}

// Every shadow-casting mesh closed (each edge has exactly two triangles, mesh.h): the shadow mask claim
// is made for closed-mesh scenes only: an open mesh's volume is not closed, so counts leak.
bool everyCasterClosed(const Scene& scene) {
  for (const Instance& inst : scene.instances())
    if (inst.shadowMesh && inst.shadowMesh->topology != Topology::Closed) return false;
  return true;
}

const std::vector<std::string> kDocumentScenes{"room", "pumpkins", "city16", "minimal"};

}  // namespace

TEST_CASE("z-fail: the stencil after each light's volume pass equals the oracle's z-fail count away from edges",
          "[volumes-oracle]") {
  for (const std::string& name : kDocumentScenes) {
    const Scene scene = documentScene(name);
    const FrameResult frame = renderWithStencil(scene, "zfail");
    const std::vector<Light> lights = drawnLights(scene);
    REQUIRE(frame.stencilPerLight.size() == lights.size());
    for (size_t l = 0; l < lights.size(); ++l) {
      const OracleImage img = testing::castVolumeOracle(scene, lights[l]);
      const CountCheck c = compareCounts(frame.stencilPerLight[l], img, img.zfail);
      INFO(name << " light " << l << ": compared " << c.compared << ", shadowed " << c.nonZero << "; "
                << c.firstMismatch);
      CHECK(c.compared > size_t(kWidth * kHeight) / 2);  // the edge marks leave most pixels to compare
      CHECK(c.nonZero > 0);                              // there is a shadow to get wrong
      CHECK(c.mismatched == 0);
    }
  }
}

TEST_CASE("z-pass: the stencil equals the oracle's z-pass count (near plane to hit), which is the true count where "
          "the camera is outside every volume", "[volumes-oracle]") {
  for (const std::string& name : kDocumentScenes) {
    const Scene scene = documentScene(name);
    const FrameResult frame = renderWithStencil(scene, "zpass");
    const std::vector<Light> lights = drawnLights(scene);
    REQUIRE(frame.stencilPerLight.size() == lights.size());
    for (size_t l = 0; l < lights.size(); ++l) {
      const OracleImage img = testing::castVolumeOracle(scene, lights[l]);
      const CountCheck c = compareCounts(frame.stencilPerLight[l], img, img.zpass);
      INFO(name << " light " << l << ": compared " << c.compared << "; " << c.firstMismatch);
      CHECK(c.compared > size_t(kWidth * kHeight) / 2);
      CHECK(c.mismatched == 0);
      if (name != "pumpkins") {
        // The camera is in no volume here, so z-pass is right: its count is z-fail's
        // ([Kuhn 2016, §3.4]).
        const CountCheck truth = compareCounts(frame.stencilPerLight[l], img, img.zfail);
        CHECK(truth.mismatched == 0);
      }
    }
  }
}

TEST_CASE("z-fail shadow mask (stencil == 0 is lit) agrees with ray-traced light visibility on >= 99.9 % of the "
          "pixels of every closed-mesh scene", "[volumes-oracle]") {
  for (const std::string& name : kDocumentScenes) {
    const Scene scene = documentScene(name);
    REQUIRE(everyCasterClosed(scene));
    const FrameResult frame = renderWithStencil(scene, "zfail");
    const std::vector<Light> lights = drawnLights(scene);
    REQUIRE(frame.stencilPerLight.size() == lights.size());
    for (size_t l = 0; l < lights.size(); ++l) {
      const OracleImage img = testing::castVolumeOracle(scene, lights[l]);
      size_t hits = 0, disagree = 0, shadowed = 0;
      for (size_t i = 0; i < img.lit.size(); ++i) {
        if (!img.hitMask[i]) continue;  // background: no surface to light
        ++hits;
        shadowed += !img.lit[i];
        disagree += (frame.stencilPerLight[l][i] == 0) != (img.lit[i] != 0);
      }
      INFO(name << " light " << l << ": " << hits << " surface pixels, " << shadowed << " shadowed, " << disagree
                << " disagree");
      CHECK(hits > size_t(kWidth * kHeight) / 4);
      CHECK(shadowed > 0);
      CHECK(disagree * 1000 <= hits);
    }
  }
}

TEST_CASE("auto gives the same stencil as z-fail, byte for byte", "[volumes-oracle]") {
  // Always at 200 x 160 (no oracle here, cheap under ASan too). Known open case: at 100 x 80 one
  // pixel of the pumpkins differs (63, 46), where pumpkin4's surface folds — a back-facing
  // triangle lies 2e-6 in front of the visible front-facing one — and a self-intersecting caster
  // has no exact volume; the pumpkin generator should not fold there.
  for (const std::string& name : kDocumentScenes) {
    const Scene scene = documentScene(name, {"image.width=200", "image.height=160"});
    const FrameResult zfail = renderWithStencil(scene, "zfail");
    const FrameResult automatic = renderWithStencil(scene, "auto");
    INFO(name);
    REQUIRE(automatic.stencilPerLight.size() == zfail.stencilPerLight.size());
    for (size_t l = 0; l < zfail.stencilPerLight.size(); ++l) {
      const bool equal = automatic.stencilPerLight[l] == zfail.stencilPerLight[l];
      CHECK(equal);
    }
  }
}

namespace {

struct MethodSplit {
  size_t zpass = 0, zfail = 0;
};

// McGuire's choice per caster ([Kuhn 2016, §4.3.2]), computed here from the occlusion pyramid.
MethodSplit expectedSplit(const Scene& scene, const Light& light) {
  const double aspect = makeCameraView(scene, true).aspect;
  MethodSplit split;
  for (const Instance& inst : scene.instances()) {
    if (!inst.shadowMesh || !withinRange(light, inst.worldBounds)) continue;
    ++(needsZFail(inst.worldBounds, scene.camera, aspect, light.homogeneous()) ? split.zfail : split.zpass);
  }
  return split;
}

// The renderer's --stats line: "light L0 'sun': 65 casters (60 z-pass, 5 z-fail), ..."
MethodSplit reportedSplit(const std::string& note) {
  static const std::regex pattern(R"(\((\d+) z-pass, (\d+) z-fail\))");
  std::smatch m;
  if (!std::regex_search(note, m, pattern)) FAIL("no method split in the stats note: " << note);
  return {std::stoul(m[1].str()), std::stoul(m[2].str())};
}

}  // namespace

TEST_CASE("auto uses z-pass for most objects of the city and z-fail for the pumpkin the camera sits in the volume of",
          "[volumes-oracle]") {
  for (const char* name : {"city", "city16"}) {
    const Scene scene = documentScene(name);
    const FrameResult frame = renderWithStencil(scene, "auto");
    REQUIRE(frame.notes.size() == scene.lights.size());
    const MethodSplit expected = expectedSplit(scene, scene.lights[0]);
    const MethodSplit reported = reportedSplit(frame.notes[0]);
    INFO(name << ": " << frame.notes[0]);
    CHECK(reported.zpass == expected.zpass);
    CHECK(reported.zfail == expected.zfail);
    CHECK(reported.zpass > 2 * reported.zfail);  // "most": at least two thirds
  }
  const Scene porch = documentScene("pumpkins");
  const FrameResult frame = renderWithStencil(porch, "auto");
  const MethodSplit reported = reportedSplit(frame.notes.at(0));
  INFO(frame.notes[0]);
  CHECK(reported.zfail >= 1);  // the hollow pumpkin holding the light ([Kuhn 2016, Fig. 5.8])
  CHECK(reported.zfail == expectedSplit(porch, porch.lights[0]).zfail);
}

TEST_CASE("pumpkins with z-pass: the camera inside the hollow pumpkin's volume makes z-pass miscount, by exactly "
          "the oracle's z-pass minus z-fail", "[volumes-oracle]") {
  const Scene scene = documentScene("pumpkins");
  const FrameResult zpass = renderWithStencil(scene, "zpass");
  const FrameResult zfail = renderWithStencil(scene, "zfail");
  REQUIRE(zpass.stencilPerLight.size() == 1);
  const OracleImage img = testing::castVolumeOracle(scene, scene.lights[0]);
  const auto& p = zpass.stencilPerLight[0];
  const auto& f = zfail.stencilPerLight[0];

  size_t differ = 0, compared = 0, predicted = 0, wrongDifference = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    differ += p[i] != f[i];
    if (img.nearEdge[i]) continue;
    ++compared;
    const int oracleDifference = img.zpass[i] - img.zfail[i];
    predicted += oracleDifference != 0;
    wrongDifference += wrapped(p[i] - f[i]) != wrapped(oracleDifference);
  }
  INFO("pixels differing " << differ << " of " << p.size() << ", oracle predicts " << predicted << " of " << compared);
  // [Kuhn 2016, Fig. 5.8]: a large part of the picture is counted wrongly, not a few edge pixels.
  CHECK(differ * 10 > p.size());
  CHECK(predicted * 10 > compared);
  CHECK(wrongDifference == 0);
}
