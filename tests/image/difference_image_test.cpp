// The difference picture's pieces (image/difference_image.h): the colour scale and the per-pixel
// difference it draws, against values worked out by hand.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "image/difference_image.h"

using namespace shadowref;

namespace {

ChannelImage image(std::vector<std::string> names, std::vector<std::vector<double>> data, std::vector<bool> integer,
                   int w, int h) {
  ChannelImage out;
  out.width = w;
  out.height = h;
  out.names = std::move(names);
  out.data = std::move(data);
  out.integer = std::move(integer);
  return out;
}

}  // namespace

TEST_CASE("heatColour: black at 0, white at the top and above, magenta for NaN against a number, never darker "
          "for a larger difference", "[image][compare]") {
  CHECK(heatColour(0.0) == std::array<uint8_t, 3>{0, 0, 0});
  CHECK(heatColour(1.0) == std::array<uint8_t, 3>{255, 255, 255});
  CHECK(heatColour(7.0) == std::array<uint8_t, 3>{255, 255, 255});
  CHECK(heatColour(std::numeric_limits<double>::infinity()) == std::array<uint8_t, 3>{255, 0, 255});
  CHECK(heatColour(0.5) == std::array<uint8_t, 3>{230, 30, 40});   // a stop of the ramp
  CHECK(heatColour(0.125) == std::array<uint8_t, 3>{88, 0, 128});  // halfway between (48,0,96) and (128,0,160)
  // Luma (Rec. 601 weights) rises along the ramp: sampled every 1/50, where the rounding of each
  // channel (at most half a level) cannot undo a step.
  double previous = 0.0;
  for (int k = 1; k <= 50; ++k) {
    const auto c = heatColour(k / 50.0);
    const double luma = 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2];
    INFO("t = " << k / 50.0);
    REQUIRE(luma > previous);
    previous = luma;
  }
}

TEST_CASE("differenceMap: one channel or the largest over all, integer channels modulo when asked",
          "[image][compare]") {
  const ChannelImage a = image({"R", "stencil"}, {{0.5, 0.5, 0.5}, {1, 1, 257}}, {false, true}, 3, 1);
  const ChannelImage b = image({"stencil", "R"}, {{1, 3, 1}, {0.75, 0.5, 0.5}}, {true, false}, 3, 1);
  DifferenceMapOptions combined;
  CHECK(differenceMap(a, b, combined) == std::vector<double>{0.25, 2.0, 256.0});
  combined.integerModulo = 256;
  CHECK(differenceMap(a, b, combined) == std::vector<double>{0.25, 2.0, 0.0});
  DifferenceMapOptions red;
  red.channel = "R";
  CHECK(differenceMap(a, b, red) == std::vector<double>{0.25, 0.0, 0.0});
  DifferenceMapOptions missing;
  missing.channel = "Z";
  CHECK_THROWS_AS(differenceMap(a, b, missing), std::invalid_argument);
  const ChannelImage wide = image({"R", "stencil"}, {{0, 0, 0, 0}, {0, 0, 0, 0}}, {false, true}, 4, 1);
  CHECK_THROWS_AS(differenceMap(a, wide, combined), std::invalid_argument);
}

TEST_CASE("differenceHeatMap: the picture above its scale strip, top of the scale the largest difference",
          "[image][compare]") {
  const std::vector<double> diffs = {0.0, 0.5, 2.0, 1.0};  // 2 x 2, top row first
  const Image8 picture = differenceHeatMap(diffs, 2, 2, 0.0, 3);
  REQUIRE(picture.channels == 3);
  CHECK(heatScaleTop(diffs, 0.0) == 2.0);
  CHECK(picture.height > 6);
  auto at = [&](int x, int y) {
    const size_t i = (size_t(y) * size_t(picture.width) + size_t(x)) * 3;
    return std::array<uint8_t, 3>{picture.pixels[i], picture.pixels[i + 1], picture.pixels[i + 2]};
  };
  CHECK(at(1, 1) == heatColour(0.0));    // pixel (0, 0) drawn 3 x 3
  CHECK(at(4, 1) == heatColour(0.25));   // 0.5 of 2
  CHECK(at(1, 4) == heatColour(1.0));    // the largest: white
  CHECK(at(5, 5) == heatColour(0.5));
  CHECK_THROWS_AS(differenceHeatMap(diffs, 3, 2), std::invalid_argument);
}
