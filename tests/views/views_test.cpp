// The teaching views against hand-computed expectations: the colour map's ends, the depth view's
// linear eye distances and auto-range, the stencil view's unsigned reading and bounded legend, the
// volume hues' distance from the scene's, and a shadow-map lookup traced step by step.
#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene_loader.h"
#include "shadow/shadow_lookup_trace.h"
#include "views/depth_view.h"
#include "views/stencil_counts_view.h"
#include "views/value_label.h"
#include "views/volume_colours.h"

using namespace shadowref;
using namespace shadowref::views;

namespace {

Rgb8 pixel(const Image8& image, int x, int y) {  // image coordinates, top row 0
  const size_t i = (size_t(y) * size_t(image.width) + size_t(x)) * size_t(image.channels);
  return {image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]};
}

const Viewport kUnitRange{0, 0, 1, 1, 0.0, 1.0};

}  // namespace

TEST_CASE("viridis: the fit's ends, rounded to bytes", "[views]") {
  // c0 · 255 = (70.82, 1.38, 85.19); the sum of the coefficients · 255 = (251.67, 231.13, 33.48).
  CHECK(viridis(0.0) == Rgb8{71, 1, 85});
  CHECK(viridis(1.0) == Rgb8{252, 231, 33});
  CHECK(viridis(-3.0) == viridis(0.0));  // clamped
  CHECK(viridis(7.0) == viridis(1.0));
  CHECK(viridis(std::nan("")) == viridis(0.0));
}

TEST_CASE("eye distance inverts perspective, infinite and orthographic projections", "[views]") {
  // n = 1, f = 10: z_ndc(distance e) = 11/9 - 20/(9 e); e = 2 -> 1/9 (d = 5/9), e = 5 -> 7/9 (d = 8/9).
  const glm::dmat4 P = glm::perspective(1.0, 1.0, 1.0, 10.0);
  CHECK(eyeDistance(5.0 / 9.0, P, kUnitRange) == Approx(2.0).epsilon(1e-12));
  CHECK(eyeDistance(8.0 / 9.0, P, kUnitRange) == Approx(5.0).epsilon(1e-12));
  CHECK(eyeDistance(0.0, P, kUnitRange) == Approx(1.0).epsilon(1e-12));
  CHECK(eyeDistance(1.0, P, kUnitRange) == Approx(10.0).epsilon(1e-12));
  // P_inf with n = 0.5: e = n / (1 - d); d = 0.75 -> 2.
  const glm::dmat4 inf = glm::infinitePerspective(1.0, 1.0, 0.5);
  CHECK(eyeDistance(0.75, inf, kUnitRange) == Approx(2.0).epsilon(1e-12));
  // Orthographic 1..10: linear, d = 0.5 -> 5.5.
  CHECK(eyeDistance(0.5, glm::ortho(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0), kUnitRange) == Approx(5.5).epsilon(1e-12));
}

TEST_CASE("depth view: the covered range maps to the colour map's ends, nothing drawn is grey", "[views]") {
  const glm::dmat4 P = glm::perspective(1.0, 1.0, 1.0, 10.0);
  // 3 x 1, framebuffer order: eye distance 2, 5, and the cleared depth 1.
  const std::vector<float> depth = {5.0f / 9.0f, 8.0f / 9.0f, 1.0f};
  const View v = depthView(depth, 3, 1, P, kUnitRange);
  CHECK(pixel(v.picture, 0, 0) == viridis(0.0));
  CHECK(pixel(v.picture, 1, 0) == viridis(1.0));
  CHECK(pixel(v.picture, 2, 0) == kNothingDrawn);
  REQUIRE(v.legend.kind == LegendKind::ColourBar);
  CHECK(v.legend.quantity == "eye depth");
  CHECK(v.legend.lo == Approx(2.0).epsilon(1e-6));  // the float depth's rounding
  CHECK(v.legend.hi == Approx(5.0).epsilon(1e-6));
  CHECK(v.legend.labels == std::vector<std::string>{"2.00", "5.00"});  // span 3: two decimals
  CHECK(v.legend.hasBackground);
  // The bar stands right of the picture: its top row is the high end, its bottom row the low end.
  const Image8 composed = composeView(v, 1);
  CHECK(composed.width > 3);
  const int barX = 3 + 3;  // margin 3g
  CHECK(pixel(composed, barX, 3) == viridis(1.0));
  CHECK(pixel(composed, barX, composed.height - 4) == viridis(0.0));
}

TEST_CASE("depth view of an empty buffer: grey, no legend", "[views]") {
  const std::vector<float> depth(4, 1.0f);
  const View v = depthView(depth, 2, 2, glm::perspective(1.0, 1.0, 1.0, 10.0), kUnitRange);
  CHECK(v.legend.kind == LegendKind::None);
  CHECK(pixel(v.picture, 1, 1) == kNothingDrawn);
}

TEST_CASE("shadow map view: 0.997 to 0.999 spans the whole colour map", "[views]") {
  // Framebuffer order, row 0 at the bottom: the picture's top row is the buffer's row 1.
  const std::vector<float> depth = {0.997f, 0.998f, 0.999f, 1.0f};
  const View v = shadowMapView(depth, 2, 2);
  CHECK(pixel(v.picture, 0, 1) == viridis(0.0));
  CHECK(pixel(v.picture, 0, 0) == viridis(1.0));
  CHECK(pixel(v.picture, 1, 0) == kNothingDrawn);
  CHECK(pixel(v.picture, 1, 1) != viridis(0.0));
  CHECK(pixel(v.picture, 1, 1) != viridis(1.0));
  CHECK(v.legend.quantity == "stored depth");
  // span 0.002: 2 - floor(log10 0.002) = 5 decimals.
  CHECK(v.legend.labels == std::vector<std::string>{"0.99700", "0.99900"});
}

TEST_CASE("range labels resolve the span and never use an exponent", "[views]") {
  CHECK(rangeLabel(2.13, 2.13, 17.8) == "2.1");
  CHECK(rangeLabel(17.8, 2.13, 17.8) == "17.8");
  CHECK(rangeLabel(1234567.0, 0.0, 1234567.0) == "1234567");
  CHECK(rangeLabel(0.5, 0.5, 0.5) == "0.500");
  CHECK(rangeLabel(std::nan(""), 0.0, 1.0) == "-");
}

TEST_CASE("stencil view reads 255 as 255 by default and as -1 when signed", "[views]") {
  const std::vector<uint8_t> stencil = {0, 1, 255, 1};
  const View u = stencilView(stencil, 2, 2);
  REQUIRE(u.legend.kind == LegendKind::Swatches);
  CHECK(u.legend.values == std::vector<int>{0, 1, 255});
  CHECK(u.legend.labels == std::vector<std::string>{"0", "1", "255"});
  const View s = stencilView(stencil, 2, 2, {.signedCounts = true});
  CHECK(s.legend.values == std::vector<int>{-1, 0, 1});
  CHECK(s.legend.labels == std::vector<std::string>{"-1", "0", "+1"});
  // Count 0 black, 1 the palette's red; buffer (0, 0) is the picture's bottom-left.
  CHECK(pixel(u.picture, 0, 1) == Rgb8{0, 0, 0});
  CHECK(pixel(u.picture, 1, 1) == Rgb8{230, 25, 75});
}

TEST_CASE("stencil view: many counts give a ramp whose legend height does not grow", "[views]") {
  // 320 x 250: row y holds count y + 1 in every pixel (250 distinct counts, as the overflow scene).
  const int w = 320, h = 250;
  std::vector<uint8_t> stencil(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) stencil[size_t(y) * size_t(w) + size_t(x)] = uint8_t(y + 1);
  const View v = stencilView(stencil, w, h);
  REQUIRE(v.legend.kind == LegendKind::Ramp);
  CHECK(v.legend.lo == 1);
  CHECK(v.legend.hi == 250);
  // Ticks: the ends and every multiple of the round step above (250 - 1) / 4 = 62.25, i.e. 100.
  CHECK(v.legend.values == std::vector<int>{1, 100, 200, 250});
  CHECK(pixel(v.picture, 0, h - 1) == viridis(0.0));  // count 1, buffer row 0
  CHECK(pixel(v.picture, 0, 0) == viridis(1.0));      // count 250, buffer row 249
  // Glyph scale 2: margin 6 + bar 8 + tick 4 + gap 2 + glyph 10 + margin 6 = 36 rows under the picture.
  const Image8 composed = composeView(v, 2);
  CHECK(composed.height - h == 36);
  CHECK(composed.width == w);
  // 16 counts still get swatches.
  std::vector<uint8_t> few(16);
  for (size_t i = 0; i < few.size(); ++i) few[i] = uint8_t(i);
  CHECK(stencilView(few, 4, 4).legend.kind == LegendKind::Swatches);
  few[0] = 200;
  CHECK(stencilView(few, 4, 4).legend.kind == LegendKind::Swatches);
  std::vector<uint8_t> seventeen(17);
  for (size_t i = 0; i < seventeen.size(); ++i) seventeen[i] = uint8_t(i);
  CHECK(stencilView(seventeen, 17, 1).legend.kind == LegendKind::Ramp);
}

TEST_CASE("volume hues: farthest from the materials' hues, greys ignored", "[views]") {
  CHECK(hueDegrees({1.0, 0.0, 0.0}) == 0.0);
  CHECK(hueDegrees({0.0, 0.0, 1.0}) == 240.0);
  CHECK(hueDegrees({0.3, 0.45, 0.8}) == Approx(222.0));  // (0.3 - 0.45) / 0.5 + 4 = 3.7 -> 222
  // Red (0) and blue (240): the larger gap is 0..240 -> its middle 120 (green); then every gap is
  // 120 wide and the first, 0..120, gives 60 (yellow).
  const std::vector<glm::dvec3> materials = {{1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {0.5, 0.5, 0.5}};
  const auto c = volumeColours(materials, 1);
  REQUIRE(c.size() == 1);
  CHECK(hueDegrees(c[0][0]) == 120.0);
  CHECK(hueDegrees(c[0][1]) == 60.0);
  // No coloured material: red first, then its opposite.
  const auto plain = volumeColours(std::vector<glm::dvec3>{{0.5, 0.5, 0.5}}, 1);
  CHECK(hueDegrees(plain[0][0]) == 0.0);
  CHECK(hueDegrees(plain[0][1]) == 180.0);
}

TEST_CASE("volume hues of the room and the two-light scene keep their distance from every material", "[views]") {
  for (const char* path : {"scenes/room.yaml", "scenes/two_lights.yaml", "scenes/pumpkins.yaml"}) {
    INFO(path);
    const Scene scene = loadScene(path);
    const auto colours = volumeColours(scene);
    REQUIRE(colours.size() == scene.lights.size());
    std::vector<double> hues;
    for (const Material& m : scene.materials)
      if (saturation(m.diffuse) >= kHuedSaturation) hues.push_back(hueDegrees(m.diffuse));
    std::vector<double> chosen;
    for (const auto& pair : colours)
      for (const glm::dvec3& c : pair) chosen.push_back(hueDegrees(c));
    // 2 · lights hues among the materials' k: the greedy choice keeps at least 360 / (2 (k + 2 · lights))
    // degrees from each of them and from each other (the widest gap is at least 360 / count wide).
    const double bound = 360.0 / (2.0 * double(hues.size() + chosen.size())) - 1.0;
    for (size_t i = 0; i < chosen.size(); ++i) {
      for (double h : hues) CHECK(hueDistance(chosen[i], h) >= bound);
      for (size_t j = 0; j < i; ++j) CHECK(hueDistance(chosen[i], chosen[j]) >= bound);
    }
  }
}

TEST_CASE("shadow lookup trace: texel, stored depth, compared r and result", "[views][shadow]") {
  // A 4 x 4 map whose texture matrix is the identity: strq = (x, y, z, 1). Texel (1, 2) holds 0.4.
  LightShadow shadow;
  shadow.textures[0] = DepthTexture::filled(4, 4, 1.0f);
  shadow.textures[0].set(1, 2, 0.4f);
  shadow.lookup.sampler.texture = &shadow.textures[0];
  shadow.lookup.sampler.failValue = 0.25;
  // s = 0.3 -> floor(1.2) = 1, t = 0.6 -> floor(2.4) = 2; r = 0.5 > 0.4: shadowed.
  ShadowLookupTrace t = traceShadowLookup(shadow, {0.3, 0.6, 0.5});
  CHECK(t.texelX == 1);
  CHECK(t.texelY == 2);
  CHECK(t.stored == 0.4f);
  CHECK(t.compared == 0.5f);
  CHECK_FALSE(t.passed);
  CHECK(t.result == 0.25);
  // r = 0.3 <= 0.4: lit.
  t = traceShadowLookup(shadow, {0.3, 0.6, 0.3});
  CHECK(t.passed);
  CHECK(t.result == 1.0);
  // A constant bias of 0.2 brings r = 0.5 down to 0.3: lit.
  shadow.lookup.constantBias = 0.2;
  t = traceShadowLookup(shadow, {0.3, 0.6, 0.5});
  CHECK(t.r == Approx(0.3));
  CHECK(t.passed);
  CHECK(t.result == 1.0);
}

TEST_CASE("shadow map view: depth 0 takes the low end without widening the range", "[views]") {
  const std::vector<float> depth = {0.0f, 0.5f, 0.75f, 1.0f};
  const View v = shadowMapView(depth, 4, 1);
  CHECK(v.legend.lo == 0.5);
  CHECK(v.legend.hi == 0.75);
  CHECK(pixel(v.picture, 0, 0) == viridis(0.0));
  CHECK(pixel(v.picture, 1, 0) == viridis(0.0));
  CHECK(pixel(v.picture, 2, 0) == viridis(1.0));
  // Only zeros: they are the range.
  const View zeros = shadowMapView(std::vector<float>{0.0f, 1.0f}, 2, 1);
  CHECK(zeros.legend.kind == LegendKind::ColourBar);
  CHECK(zeros.legend.lo == 0.0);
}

TEST_CASE("shadow map outline: the frustum's edges clipped to the map and the light's front", "[views]") {
  // An 8 x 8 map whose clip space is the world's x-y (w = 1): the frustum a box from x, y = -0.5
  // to 0.5 projects to the square of texels 2..6 ((x + 1) / 2 · 8), its near and far faces on
  // top of each other; the square's inside and the map's border stay as they were.
  const std::vector<float> depth(64, 0.5f);
  View view = shadowMapView(depth, 8, 8);
  const Rgb8 before = pixel(view.picture, 4, 4);
  ShadowMapOutline outline;
  for (size_t i = 0; i < 8; ++i) {
    const double x = (i % 4 == 1 || i % 4 == 2) ? 0.5 : -0.5, y = (i % 4 >= 2) ? 0.5 : -0.5;
    outline.frustum[i] = {x, y, i < 4 ? 1.0 : 2.0};
  }
  drawShadowMapOutline(view, outline);
  // Buffer (2, 2) is picture row 8 - 1 - 2 = 5.
  for (const auto& [bx, by] : std::vector<std::pair<int, int>>{{2, 2}, {6, 2}, {6, 6}, {2, 6}, {4, 2}, {2, 4}})
    CHECK(pixel(view.picture, bx, 7 - by) == kFrustumColour);
  CHECK(pixel(view.picture, 4, 4) == before);
  CHECK(pixel(view.picture, 0, 0) == before);
  CHECK(pixel(view.picture, 7, 7) == before);
  REQUIRE(view.legend.outlines.size() == 1);
  CHECK(view.legend.outlines[0].first == "camera frustum");

  // A perspective light (w = z): an edge from (0.5, 0) at w = 1 to a point behind the light
  // (w = -1) runs in front of the light from x/w = 0.5 out to infinity, right of texel 6 along row
  // 4; divided without clipping it would run to x/w = -0.5 instead, across the map's centre.
  View behind = shadowMapView(depth, 8, 8);
  ShadowMapOutline perspective;
  perspective.worldToClip = glm::dmat4(1.0);
  perspective.worldToClip[2][3] = 1.0;  // w = z (glm: [column][row])
  perspective.worldToClip[3][3] = 0.0;
  for (size_t i = 0; i < 8; ++i) perspective.frustum[i] = {0.5, 0.0, i < 4 ? 1.0 : -1.0};
  drawShadowMapOutline(behind, perspective);
  CHECK(pixel(behind.picture, 6, 7 - 4) == kFrustumColour);
  CHECK(pixel(behind.picture, 7, 7 - 4) == kFrustumColour);
  for (int x = 0; x < 6; ++x) CHECK(pixel(behind.picture, x, 7 - 4) == before);

  // The trapezoid in its own colour, on the texels the map's depth-0 outline takes.
  View tsm = shadowMapView(depth, 8, 8);
  ShadowMapOutline plain;
  plain.frustum = outline.frustum;
  plain.worldToClip = glm::dmat4(0.0);  // the frustum collapses to the map's centre, w = 0: clipped away
  plain.trapezoid = {{-0.75, -0.75}, {0.75, -0.75}, {0.25, 0.75}, {-0.25, 0.75}};
  drawShadowMapOutline(tsm, plain);
  CHECK(pixel(tsm.picture, 1, 7 - 1) == kTrapezoidColour);  // (-0.75 + 1) / 2 · 8 = 1
  CHECK(pixel(tsm.picture, 6, 7 - 1) == kTrapezoidColour);  // on the base line from texel (1, 1) to (7, 1)
  CHECK(pixel(tsm.picture, 4, 7 - 4) == before);
  CHECK(tsm.legend.outlines.size() == 2);
}
