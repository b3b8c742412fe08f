#include "image/bitmap_font.h"

namespace shadowref {

namespace {

// Each glyph is 5 rows of 3 bits, the most significant bit the leftmost pixel.
using Glyph = std::array<uint8_t, kGlyphHeight>;

bool glyphFor(char c, Glyph& g) {
  switch (c) {
    case '0': g = {0b111, 0b101, 0b101, 0b101, 0b111}; return true;
    case '1': g = {0b010, 0b110, 0b010, 0b010, 0b111}; return true;
    case '2': g = {0b111, 0b001, 0b111, 0b100, 0b111}; return true;
    case '3': g = {0b111, 0b001, 0b011, 0b001, 0b111}; return true;
    case '4': g = {0b101, 0b101, 0b111, 0b001, 0b001}; return true;
    case '5': g = {0b111, 0b100, 0b111, 0b001, 0b111}; return true;
    case '6': g = {0b111, 0b100, 0b111, 0b101, 0b111}; return true;
    case '7': g = {0b111, 0b001, 0b010, 0b010, 0b010}; return true;
    case '8': g = {0b111, 0b101, 0b111, 0b101, 0b111}; return true;
    case '9': g = {0b111, 0b101, 0b111, 0b001, 0b111}; return true;
    case '+': g = {0b000, 0b010, 0b111, 0b010, 0b000}; return true;
    case '-': g = {0b000, 0b000, 0b111, 0b000, 0b000}; return true;
    case '.': g = {0b000, 0b000, 0b000, 0b000, 0b010}; return true;
    default: return false;
  }
}

void setPixel(Image8& image, int x, int y, std::array<uint8_t, 3> colour) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  const size_t i = (size_t(y) * size_t(image.width) + size_t(x)) * size_t(image.channels);
  for (int k = 0; k < 3 && k < image.channels; ++k) image.pixels[i + size_t(k)] = colour[size_t(k)];
}

}  // namespace

int textWidth(const std::string& text, int scale) {
  if (text.empty()) return 0;
  return int(text.size()) * (kGlyphWidth + 1) * scale - scale;
}

void drawText(Image8& image, int x, int y, const std::string& text, int scale, std::array<uint8_t, 3> colour) {
  for (size_t i = 0; i < text.size(); ++i) {
    Glyph g{};
    if (!glyphFor(text[i], g)) continue;
    const int left = x + int(i) * (kGlyphWidth + 1) * scale;
    for (int row = 0; row < kGlyphHeight; ++row)
      for (int col = 0; col < kGlyphWidth; ++col) {
        if (!(g[size_t(row)] & (1u << (kGlyphWidth - 1 - col)))) continue;
        for (int dy = 0; dy < scale; ++dy)
          for (int dx = 0; dx < scale; ++dx) setPixel(image, left + col * scale + dx, y + row * scale + dy, colour);
      }
  }
}

}  // namespace shadowref
