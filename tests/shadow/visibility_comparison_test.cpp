// oracle::compareVisibility and comparedPixels on a hand-made 3 × 2 oracle image: each verdict,
// its count and its colour in the error map (top row first), and a spot light's cone.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <stdexcept>

#include "oracle/visibility_comparison.h"

using namespace shadowref;

namespace {

// Row 0 (bottom): hit & lit, hit & shadowed, no hit. Row 1 (top): hit & lit, hit & shadowed
// near an edge, hit & lit near an edge.
oracle::OracleImage smallImage() {
  oracle::OracleImage o;
  o.width = 3;
  o.height = 2;
  o.hitMask = {1, 1, 0, 1, 1, 1};
  o.lit = {1, 0, 0, 1, 0, 1};
  o.nearEdge = {0, 0, 0, 0, 1, 1};
  o.hitPoint.assign(6, glm::dvec3(0.0));
  return o;
}

std::array<uint8_t, 3> pixel(const std::vector<uint8_t>& map, int x, int yFromTop) {
  const size_t at = (size_t(yFromTop) * 3 + size_t(x)) * 3;
  return {map[at], map[at + 1], map[at + 2]};
}

}  // namespace

TEST_CASE("compareVisibility: agreement, false and missed shadows are counted and coloured", "[oracle]") {
  const oracle::OracleImage o = smallImage();
  // Per pixel, the render's verdict against the oracle's:
  //   0: rendered lit, traced lit -> agree (grey 200)
  //   1: rendered lit, traced shadowed -> missed shadow
  //   2: not compared (no hit)
  //   3: rendered shadowed, traced lit -> false shadow
  //   4: rendered shadowed, traced shadowed -> agree (grey 90)
  //   5: rendered shadowed, traced lit, near an edge -> false shadow near an edge
  const std::array<bool, 6> renderedLit = {true, true, true, false, false, false};
  std::vector<size_t> asked;
  const auto lit = [&](size_t i) {
    asked.push_back(i);
    return renderedLit[i];
  };
  const std::vector<uint8_t> mask = oracle::comparedPixels(o, Light{});
  CHECK(mask == o.hitMask);

  const oracle::VisibilityComparison plain = oracle::compareVisibility(o, mask, lit, false);
  CHECK(asked == std::vector<size_t>{0, 1, 3, 4, 5});  // never outside the mask
  const oracle::VisibilityCounts& n = plain.counts;
  CHECK(n.compared == 5);
  CHECK(n.agree == 2);
  CHECK(n.falseShadow == 2);
  CHECK(n.missedShadow == 1);
  CHECK(n.nearEdge == 1);
  CHECK(n.elsewhere == 2);
  CHECK(n.agreePercent() == Approx(40.0));
  REQUIRE(plain.errorMap.size() == 3 * 2 * 3);
  // Framebuffer row 0 is the map's second row.
  CHECK(pixel(plain.errorMap, 0, 1) == std::array<uint8_t, 3>{200, 200, 200});
  CHECK(pixel(plain.errorMap, 1, 1) == std::array<uint8_t, 3>{0, 64, 255});
  CHECK(pixel(plain.errorMap, 2, 1) == std::array<uint8_t, 3>{0, 0, 0});
  CHECK(pixel(plain.errorMap, 0, 0) == std::array<uint8_t, 3>{255, 0, 0});
  CHECK(pixel(plain.errorMap, 1, 0) == std::array<uint8_t, 3>{90, 90, 90});
  CHECK(pixel(plain.errorMap, 2, 0) == std::array<uint8_t, 3>{255, 0, 0});

  asked.clear();
  const oracle::VisibilityComparison pale = oracle::compareVisibility(o, mask, lit, true);
  CHECK(pale.counts.falseShadow == 2);
  CHECK(pixel(pale.errorMap, 2, 0) == std::array<uint8_t, 3>{255, 160, 160});  // near an edge: paler
  CHECK(pixel(pale.errorMap, 0, 0) == std::array<uint8_t, 3>{255, 0, 0});      // elsewhere: as before
}

TEST_CASE("comparedPixels: a spot light's mask keeps only the hits inside its cone", "[oracle]") {
  oracle::OracleImage o = smallImage();
  // A spot at the origin looking down +x with a 45° cone: along +x inside, along +y (90°) and
  // at 60° outside, at 30° inside.
  o.hitPoint = {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0),
                glm::dvec3(1, std::tan(glm::radians(30.0)), 0), glm::dvec3(1, std::tan(glm::radians(60.0)), 0),
                glm::dvec3(2, 0, 0.5)};
  Light spot;
  spot.type = LightType::Spot;
  spot.position = glm::dvec3(0.0);
  spot.direction = glm::dvec3(1, 0, 0);
  spot.spotCutoffDegrees = 45.0;
  // Pixel 2 is inside the cone but has no hit: not compared.
  CHECK(oracle::comparedPixels(o, spot) == std::vector<uint8_t>{1, 0, 0, 1, 0, 1});
  CHECK_THROWS_AS(oracle::compareVisibility(o, {1, 1}, [](size_t) { return true; }, false), std::invalid_argument);
}
