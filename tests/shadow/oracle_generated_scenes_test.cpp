// The oracle on the documents' scenes at golden size (200 x 160): its two independent answers —
// volume crossing counts and shadow rays — must agree, and z-pass must agree with z-fail exactly
// where the camera is outside every volume ([Kuhn 2016, §3.4]).
#include <catch2/catch.hpp>

#include <chrono>

#include "scene/generators.h"
#include "oracle/oracle.h"

using namespace shadowref;
using namespace shadowref::oracle;

namespace {

struct Agreement {
  size_t compared = 0, countVsShadowRay = 0, zpassVsZfail = 0, shadowed = 0;
};

// Over the hit pixels away from edges: does (zfail > 0) match (not lit), does zpass match zfail?
Agreement agreement(const OracleImage& img) {
  Agreement a;
  for (size_t i = 0; i < img.zfail.size(); ++i) {
    if (!img.hitMask[i] || img.nearEdge[i]) continue;
    ++a.compared;
    a.shadowed += img.zfail[i] > 0;
    a.countVsShadowRay += (img.zfail[i] > 0) != (img.lit[i] == 0);
    a.zpassVsZfail += img.zpass[i] != img.zfail[i];
  }
  return a;
}

Scene sized(Scene scene) {
  scene.width = 200;
  scene.height = 160;
  return scene;
}

double secondsOf(const auto& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST_CASE("oracle: in the room, counts and shadow rays agree and z-pass equals z-fail (the eye is in no volume)",
          "[oracle]") {
  Scene scene;
  addRoom(scene);
  scene = sized(scene);
  REQUIRE(scene.lights.size() == 1);
  OracleImage img;
  const double seconds = secondsOf([&] { img = castOracle(scene, scene.lights[0]); });
  const Agreement a = agreement(img);
  INFO("compared " << a.compared << " shadowed " << a.shadowed << " seconds " << seconds);
  CHECK(a.compared > 20000);
  CHECK(a.shadowed > 300);
  CHECK(a.countVsShadowRay <= a.compared / 1000);  // agree on 99.9 % of the compared pixels
  CHECK(a.zpassVsZfail == 0);
}

TEST_CASE("oracle: at the pumpkins, counts and shadow rays agree, and z-pass is wrong where the camera sits in a "
          "volume", "[oracle]") {
  Scene scene;
  addPumpkins(scene);
  scene = sized(scene);
  REQUIRE_FALSE(scene.lights.empty());
  OracleImage img;
  const double seconds = secondsOf([&] { img = castOracle(scene, scene.lights[0]); });
  const Agreement a = agreement(img);
  INFO("compared " << a.compared << " shadowed " << a.shadowed << " z-pass wrong " << a.zpassVsZfail << " seconds "
                   << seconds);
  CHECK(a.compared > 5000);
  CHECK(a.countVsShadowRay <= a.compared / 1000);
  CHECK(a.zpassVsZfail > 100);  // [Kuhn 2016, Fig. 5.8]: the camera inside the shell's volume
}

TEST_CASE("oracle: in city-16, counts and shadow rays agree and z-pass equals z-fail", "[oracle]") {
  Scene scene;
  CityOptions options;
  options.houses = 16;
  addCity(scene, options);
  scene = sized(scene);
  REQUIRE_FALSE(scene.lights.empty());
  OracleImage img;
  const double seconds = secondsOf([&] { img = castOracle(scene, scene.lights[0]); });
  const Agreement a = agreement(img);
  INFO("compared " << a.compared << " shadowed " << a.shadowed << " seconds " << seconds);
  CHECK(a.compared > 5000);
  CHECK(a.shadowed > 500);
  CHECK(a.countVsShadowRay <= a.compared / 1000);
  CHECK(a.zpassVsZfail == 0);
}
