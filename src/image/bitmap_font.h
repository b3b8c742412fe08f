// A tiny built-in font for labels in pictures (legends, colour bars): the digits 0-9, '+', '-' and '.' as
// 3x5 pixel glyphs, scaled up by whole pixels. No font library, so the pictures are the same bytes
// on every machine.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "image/image_writer.h"

namespace shadowref {

constexpr int kGlyphWidth = 3;
constexpr int kGlyphHeight = 5;

// Width in pixels of text drawn at the given scale: glyphs one scaled pixel apart.
int textWidth(const std::string& text, int scale);

// Draws text with its top-left corner at (x, y) (image coordinates, y down) into an RGB Image8,
// clipped to the image. Characters without a glyph (anything but 0-9 + - .) leave a blank.
void drawText(Image8& image, int x, int y, const std::string& text, int scale,
              std::array<uint8_t, 3> colour);

}  // namespace shadowref
