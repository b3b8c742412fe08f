#include "image/stencil_view.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "image/bitmap_font.h"

namespace shadowref {

namespace {

using Rgb = std::array<uint8_t, 3>;

// Distinct colours for the small counts a teaching scene shows (after Trubetskoy's list of 20
// distinct colours, without the dark ones that a halved negative colour could be mistaken for).
constexpr std::array<Rgb, 16> kPalette = {{
    {230, 25, 75},   {60, 180, 75},   {255, 225, 25},  {0, 130, 200},
    {245, 130, 48},  {145, 30, 180},  {70, 240, 240},  {240, 50, 230},
    {210, 245, 60},  {250, 190, 212}, {0, 128, 128},   {220, 190, 255},
    {170, 110, 40},  {255, 250, 200}, {170, 255, 195}, {255, 215, 180},
}};

constexpr Rgb kLegendBackground = {48, 48, 48};
constexpr Rgb kLegendInk = {235, 235, 235};
constexpr Rgb kSwatchFrame = {160, 160, 160};

// A fully saturated-ish colour of the given hue in [0, 1) (HSV with s = 0.65, v = 0.95).
Rgb hueColour(double hue) {
  const double s = 0.65, v = 0.95;
  const double h6 = hue * 6.0;
  const int sector = int(std::floor(h6)) % 6;
  const double f = h6 - std::floor(h6);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r = v, g = t, b = p;
  switch (sector) {
    case 0: r = v; g = t; b = p; break;
    case 1: r = q; g = v; b = p; break;
    case 2: r = p; g = v; b = t; break;
    case 3: r = p; g = q; b = v; break;
    case 4: r = t; g = p; b = v; break;
    default: r = v; g = p; b = q; break;
  }
  return {uint8_t(std::lround(r * 255)), uint8_t(std::lround(g * 255)), uint8_t(std::lround(b * 255))};
}

Rgb positiveColour(int k) {
  if (k <= int(kPalette.size())) return kPalette[size_t(k - 1)];
  const double golden = 0.6180339887498949;
  double hue = 0.5 + double(k) * golden;
  return hueColour(hue - std::floor(hue));
}

std::string countLabel(int count, bool signedCounts) {
  std::string label = signedCounts && count > 0 ? std::string("+") : std::string();
  return label.append(std::to_string(count));
}

void fillRect(Image8& image, int x0, int y0, int w, int h, Rgb colour) {
  for (int y = std::max(0, y0); y < std::min(image.height, y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x0 + w); ++x) {
      const size_t i = (size_t(y) * size_t(image.width) + size_t(x)) * 3;
      image.pixels[i] = colour[0];
      image.pixels[i + 1] = colour[1];
      image.pixels[i + 2] = colour[2];
    }
}

void checkStencil(std::span<const uint8_t> stencil, int width, int height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("stencil size must be positive");
  if (stencil.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("stencil has " + std::to_string(stencil.size()) + " values for " +
                                std::to_string(width) + "x" + std::to_string(height) + " pixels");
}

// Legend geometry: each entry is a framed swatch, a gap, its label, and a wider gap.
struct LegendLayout {
  int margin, swatch, entryWidth, rowHeight, perRow, rows;
};

LegendLayout layoutLegend(int canvasWidth, size_t entries, int maxLabelChars, int g) {
  LegendLayout l;
  l.margin = 2 * g;
  l.swatch = kGlyphHeight * g + 2;
  l.entryWidth = l.swatch + 2 * g + maxLabelChars * (kGlyphWidth + 1) * g + 3 * g;
  l.rowHeight = l.swatch + 2 * g;
  l.perRow = std::max(1, (canvasWidth - 2 * l.margin) / l.entryWidth);
  l.rows = int((entries + size_t(l.perRow) - 1) / size_t(l.perRow));
  return l;
}

}  // namespace

int stencilCount(uint8_t value, bool signedCounts) {
  return signedCounts ? int(int8_t(value)) : int(value);
}

Rgb stencilColour(int count) {
  if (count == 0) return {0, 0, 0};
  Rgb c = positiveColour(std::abs(count));
  if (count < 0)
    for (uint8_t& v : c) v = uint8_t(v / 2);
  return c;
}

Image8 stencilFalseColour(std::span<const uint8_t> stencil, int width, int height,
                          const StencilViewOptions& options) {
  checkStencil(stencil, width, height);
  const int s = std::max(1, options.pixelScale);
  const int g = std::max(1, options.glyphScale);

  std::set<int> present;  // ordered: the legend lists counts in increasing order
  for (uint8_t v : stencil) present.insert(stencilCount(v, options.signedCounts));
  int maxLabelChars = 1;
  for (int c : present) maxLabelChars = std::max(maxLabelChars, int(countLabel(c, options.signedCounts).size()));

  const int pictureWidth = width * s, pictureHeight = height * s;
  int canvasWidth = pictureWidth;
  LegendLayout legend{};
  int legendHeight = 0;
  if (options.legend) {
    legend = layoutLegend(pictureWidth, present.size(), maxLabelChars, g);
    canvasWidth = std::max(pictureWidth, legend.entryWidth + 2 * legend.margin);
    legend = layoutLegend(canvasWidth, present.size(), maxLabelChars, g);
    legendHeight = legend.rows * legend.rowHeight + 2 * legend.margin - 2 * g;
  }

  Image8 image;
  image.width = canvasWidth;
  image.height = pictureHeight + legendHeight;
  image.channels = 3;
  image.pixels.assign(size_t(image.width) * size_t(image.height) * 3, 0);
  fillRect(image, 0, 0, image.width, image.height, kLegendBackground);

  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int count = stencilCount(stencil[size_t(y) * size_t(width) + size_t(x)], options.signedCounts);
      fillRect(image, x * s, (height - 1 - y) * s, s, s, stencilColour(count));  // row 0 at the bottom
    }

  if (options.legend) {
    int i = 0;
    for (int count : present) {
      const int left = legend.margin + (i % legend.perRow) * legend.entryWidth;
      const int top = pictureHeight + legend.margin + (i / legend.perRow) * legend.rowHeight;
      fillRect(image, left, top, legend.swatch, legend.swatch, kSwatchFrame);
      fillRect(image, left + 1, top + 1, legend.swatch - 2, legend.swatch - 2, stencilColour(count));
      drawText(image, left + legend.swatch + 2 * g, top + 1, countLabel(count, options.signedCounts), g, kLegendInk);
      ++i;
    }
  }
  return image;
}

Image8 stencilFalseColour(const Framebuffer& fb, const StencilViewOptions& options) {
  if (!fb.hasStencil()) throw std::invalid_argument("the framebuffer has no stencil buffer");
  return stencilFalseColour(fb.stencil(), fb.width(), fb.height(), options);
}

void writeStencilPng(std::span<const uint8_t> stencil, int width, int height, const std::string& path,
                     const StencilViewOptions& options, const OutputMetadata& metadata) {
  writePng8(stencilFalseColour(stencil, width, height, options), path, metadata);
}

void writeStencilPng(const Framebuffer& fb, const std::string& path, const StencilViewOptions& options,
                     const OutputMetadata& metadata) {
  writePng8(stencilFalseColour(fb, options), path, metadata);
}

namespace {

std::string padLeft(const std::string& s, size_t width) {
  std::string padded(width > s.size() ? width - s.size() : 0, ' ');
  return padded.append(s);
}

// One grid cell: a separating space, then the text right-aligned in the column.
void appendCell(std::string& out, const std::string& text, size_t width) {
  out += ' ';
  out += padLeft(text, width);
}

}  // namespace

std::string stencilGrid(std::span<const uint8_t> stencil, int fbWidth, int fbHeight, int x, int y, int w, int h,
                        bool signedCounts) {
  checkStencil(stencil, fbWidth, fbHeight);
  if (w <= 0 || h <= 0) throw std::invalid_argument("stencil region needs a positive width and height");
  // The ends in 64 bits: x + w overflows an int for x, w near INT_MAX.
  const int64_t xEnd = int64_t(x) + w, yEnd = int64_t(y) + h;  // exclusive
  const int x0 = std::max(x, 0), y0 = std::max(y, 0);
  const int x1 = int(std::min<int64_t>(xEnd, fbWidth)) - 1, y1 = int(std::min<int64_t>(yEnd, fbHeight)) - 1;
  if (x0 > x1 || y0 > y1)
    throw std::invalid_argument("stencil region " + std::to_string(x) + "," + std::to_string(y) + " " +
                                std::to_string(w) + "x" + std::to_string(h) + " lies outside the " +
                                std::to_string(fbWidth) + "x" + std::to_string(fbHeight) + " framebuffer");
  const bool clipped = x0 != x || y0 != y || x1 + 1 != xEnd || y1 + 1 != yEnd;

  size_t column = 1;
  for (int cx = x0; cx <= x1; ++cx) column = std::max(column, std::to_string(cx).size());
  for (int cy = y0; cy <= y1; ++cy)
    for (int cx = x0; cx <= x1; ++cx)
      column = std::max(column, std::to_string(stencilCount(stencil[size_t(cy) * size_t(fbWidth) + size_t(cx)],
                                                            signedCounts)).size());
  size_t rowLabel = 3;  // "y\x"
  for (int cy = y0; cy <= y1; ++cy) rowLabel = std::max(rowLabel, std::to_string(cy).size());

  std::string out = "stencil x " + std::to_string(x0) + ".." + std::to_string(x1) + ", y " + std::to_string(y0) +
                    ".." + std::to_string(y1) + (signedCounts ? ", signed" : "") +
                    " (y is the framebuffer row: row 0 is the bottom; top row first)";
  if (clipped) out += " [clipped to the " + std::to_string(fbWidth) + "x" + std::to_string(fbHeight) + " framebuffer]";
  out += '\n';
  out += padLeft("y\\x", rowLabel);
  for (int cx = x0; cx <= x1; ++cx) appendCell(out, std::to_string(cx), column);
  out += '\n';
  for (int cy = y1; cy >= y0; --cy) {
    out += padLeft(std::to_string(cy), rowLabel);
    for (int cx = x0; cx <= x1; ++cx)
      appendCell(out, std::to_string(stencilCount(stencil[size_t(cy) * size_t(fbWidth) + size_t(cx)], signedCounts)),
                 column);
    out += '\n';
  }
  return out;
}

std::string stencilGrid(const Framebuffer& fb, int x, int y, int w, int h, bool signedCounts) {
  if (!fb.hasStencil()) throw std::invalid_argument("the framebuffer has no stencil buffer");
  return stencilGrid(fb.stencil(), fb.width(), fb.height(), x, y, w, h, signedCounts);
}

}  // namespace shadowref
