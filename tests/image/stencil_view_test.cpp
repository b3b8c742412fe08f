#include <set>
#include <stdexcept>

#include <catch2/catch.hpp>
#include <OpenImageIO/imageio.h>

#include "image/bitmap_font.h"
#include "image/stencil_view.h"
#include "image/temp_dir.h"

using namespace shadowref;
using shadowref::test::TempDir;

namespace {

std::array<uint8_t, 3> pixelAt(const Image8& image, int x, int y) {
  const size_t i = (size_t(y) * size_t(image.width) + size_t(x)) * size_t(image.channels);
  return {image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]};
}

// A 4x3 stencil, framebuffer rows (row 0 at the bottom):
//   row 2:   0   0   1   0
//   row 1:   0   2   2 255
//   row 0:  10   0   1   0
Framebuffer makeStencil() {
  Framebuffer fb(4, 3);
  fb.ensureStencil();
  const uint8_t rows[3][4] = {{10, 0, 1, 0}, {0, 2, 2, 255}, {0, 0, 1, 0}};
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) fb.stencil()[fb.index(x, y)] = rows[y][x];
  return fb;
}

}  // namespace

TEST_CASE("stencil grid prints the region top row first with framebuffer row labels", "[image]") {
  const std::string expected =
      "stencil x 0..3, y 0..2 (y is the framebuffer row: row 0 is the bottom; top row first)\n"
      "y\\x   0   1   2   3\n"
      "  2   0   0   1   0\n"
      "  1   0   2   2 255\n"
      "  0  10   0   1   0\n";
  CHECK(stencilGrid(makeStencil(), 0, 0, 4, 3) == expected);
}

TEST_CASE("stencil grid of a sub-region, signed, reads 255 as -1", "[image]") {
  const std::string expected =
      "stencil x 2..3, y 1..2, signed (y is the framebuffer row: row 0 is the bottom; top row first)\n"
      "y\\x  2  3\n"
      "  2  1  0\n"
      "  1  2 -1\n";
  CHECK(stencilGrid(makeStencil(), 2, 1, 2, 2, true) == expected);
}

TEST_CASE("stencil grid clips the region to the framebuffer and says so", "[image]") {
  const std::string expected =
      "stencil x 3..3, y 2..2 (y is the framebuffer row: row 0 is the bottom; top row first)"
      " [clipped to the 4x3 framebuffer]\n"
      "y\\x 3\n"
      "  2 0\n";
  CHECK(stencilGrid(makeStencil(), 3, 2, 5, 5) == expected);
  CHECK_THROWS_AS(stencilGrid(makeStencil(), 4, 0, 1, 1), std::invalid_argument);
  CHECK_THROWS_AS(stencilGrid(makeStencil(), 0, 0, 0, 1), std::invalid_argument);
  CHECK_THROWS_AS(stencilGrid(Framebuffer(2, 2), 0, 0, 1, 1), std::invalid_argument);
}

TEST_CASE("stencil counts read 128..255 as negative only when signed", "[image]") {
  CHECK(stencilCount(255, false) == 255);
  CHECK(stencilCount(255, true) == -1);
  CHECK(stencilCount(128, true) == -128);
  CHECK(stencilCount(127, true) == 127);
  CHECK(stencilCount(0, true) == 0);
}

TEST_CASE("stencil colours: 0 is black, counts -128..-1 and 1..255 are pairwise distinct and never black",
          "[image]") {
  CHECK(stencilColour(0) == std::array<uint8_t, 3>{0, 0, 0});
  std::set<std::array<uint8_t, 3>> seen;
  for (int k = 1; k <= 255; ++k) {
    CHECK(stencilColour(k) != std::array<uint8_t, 3>{0, 0, 0});
    seen.insert(stencilColour(k));
  }
  CHECK(seen.size() == 255);
  for (int k = 1; k <= 128; ++k) {
    CHECK(stencilColour(-k) != std::array<uint8_t, 3>{0, 0, 0});
    seen.insert(stencilColour(-k));
  }
  CHECK(seen.size() == 255 + 128);  // no negative count looks like any positive one either
}

TEST_CASE("stencil false colour flips rows and scales pixels", "[image]") {
  StencilViewOptions options;
  options.legend = false;
  options.pixelScale = 2;
  Image8 image = stencilFalseColour(makeStencil(), options);
  REQUIRE(image.width == 8);
  REQUIRE(image.height == 6);
  // Framebuffer (0, 0) holds 10: the bottom-left 2x2 block of the picture.
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) CHECK(pixelAt(image, dx, 4 + dy) == stencilColour(10));
  CHECK(pixelAt(image, 4, 0) == stencilColour(1));  // framebuffer (2, 2): top row
  CHECK(pixelAt(image, 7, 2) == stencilColour(255));
  options.signedCounts = true;
  CHECK(pixelAt(stencilFalseColour(makeStencil(), options), 7, 2) == stencilColour(-1));
}

TEST_CASE("stencil legend shows one swatch per count present, in increasing order", "[image]") {
  StencilViewOptions options;
  options.glyphScale = 1;
  Image8 image = stencilFalseColour(makeStencil(), options);
  // Counts present: 0 1 2 10 255. Layout with glyph scale 1: margin 2, swatch 7 (5 + frame),
  // entry 7 + 2 + 3 label chars * 4 + 3 = 24 wide, so the canvas widens to 28: one entry per row.
  REQUIRE(image.width == 28);
  REQUIRE(image.height == 3 + 5 * 9 + 2);
  const int legendTop = 3 + 2;
  const std::array<int, 5> counts = {0, 1, 2, 10, 255};
  for (size_t i = 0; i < counts.size(); ++i) {
    const int top = legendTop + int(i) * 9;
    CHECK(pixelAt(image, 2, top) == std::array<uint8_t, 3>{160, 160, 160});  // frame
    CHECK(pixelAt(image, 5, top + 3) == stencilColour(counts[i]));            // swatch centre
  }
  // The label of the first entry is "0": its top bar starts right of the swatch, at x 2 + 7 + 2.
  CHECK(pixelAt(image, 11, legendTop + 1) == std::array<uint8_t, 3>{235, 235, 235});
  CHECK(pixelAt(image, 12, legendTop + 2) == std::array<uint8_t, 3>{48, 48, 48});  // hole of the 0
}

TEST_CASE("the bitmap font draws 3x5 glyphs scaled by whole pixels", "[image]") {
  Image8 image;
  image.width = 8;
  image.height = 10;
  image.channels = 3;
  image.pixels.assign(8 * 10 * 3, 0);
  drawText(image, 1, 0, "-", 2, {255, 255, 255});
  // '-' is the middle row of the glyph: rows 4..5 at scale 2, columns 1..6.
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool ink = y >= 4 && y <= 5 && x >= 1 && x <= 6;
      CHECK(pixelAt(image, x, y) == (ink ? std::array<uint8_t, 3>{255, 255, 255} : std::array<uint8_t, 3>{0, 0, 0}));
    }
  CHECK(textWidth("-12", 2) == 3 * 8 - 2);
}

TEST_CASE("stencil PNG is written with the legend below the picture", "[image]") {
  TempDir dir("stencil-png");
  const std::string path = dir.file("stencil.png");
  writeStencilPng(makeStencil(), path);
  auto in = OIIO::ImageInput::open(path);
  REQUIRE(in);
  Image8 expected = stencilFalseColour(makeStencil());
  CHECK(in->spec().width == expected.width);
  CHECK(in->spec().height == expected.height);
  std::vector<uint8_t> px(expected.pixels.size());
  REQUIRE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  CHECK(px == expected.pixels);
}
