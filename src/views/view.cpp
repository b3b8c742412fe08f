#include "views/view.h"

#include <algorithm>
#include <cmath>

#include "image/bitmap_font.h"

namespace shadowref::views {

namespace {

constexpr Rgb8 kPanel = {48, 48, 48};    // the legend's strip
constexpr Rgb8 kInk = {235, 235, 235};   // its text and ticks
constexpr Rgb8 kFrame = {160, 160, 160}; // swatch and bar frames

void fill(Image8& image, int x0, int y0, int w, int h, Rgb8 c) {
  for (int y = std::max(0, y0); y < std::min(image.height, y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x0 + w); ++x) {
      uint8_t* px = &image.pixels[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
      px[0] = c[0];
      px[1] = c[1];
      px[2] = c[2];
      px[3] = 255;
    }
}

void blit(Image8& to, const Image8& from, int x0, int y0) {
  for (int y = 0; y < from.height; ++y)
    for (int x = 0; x < from.width; ++x) {
      const uint8_t* src = &from.pixels[(size_t(y) * size_t(from.width) + size_t(x)) * 4];
      uint8_t* dst = &to.pixels[(size_t(y + y0) * size_t(to.width) + size_t(x + x0)) * 4];
      std::copy(src, src + 4, dst);
    }
}

int maxTextWidth(const std::vector<std::string>& labels, int g) {
  int w = 0;
  for (const std::string& s : labels) w = std::max(w, textWidth(s, g));
  return w;
}

// The colour bar to the right of the picture: a margin, the bar (hi at the top, lo at the bottom,
// framed), a gap and the two labels at its ends.
Image8 withColourBar(const View& view, int g) {
  const Image8& pic = view.picture;
  const int margin = 3 * g, barWidth = 6 * g, glyphH = kGlyphHeight * g;
  const std::string hiLabel = view.legend.labels.size() > 1 ? view.legend.labels[1] : "";
  const std::string loLabel = !view.legend.labels.empty() ? view.legend.labels[0] : "";
  const int labelWidth = std::max(textWidth(hiLabel, g), textWidth(loLabel, g));
  const int minBar = 4 * glyphH;  // room for both labels one above the other
  const int height = std::max(pic.height, minBar + 2 * margin);
  Image8 out = filledPicture(pic.width + margin + barWidth + 2 * g + labelWidth + margin, height, kPanel);
  blit(out, pic, 0, 0);
  const int barX = pic.width + margin, barTop = margin, barHeight = height - 2 * margin;
  fill(out, barX - 1, barTop - 1, barWidth + 2, barHeight + 2, kFrame);
  for (int y = 0; y < barHeight; ++y) {
    const double t = barHeight > 1 ? 1.0 - double(y) / double(barHeight - 1) : 1.0;
    fill(out, barX, barTop + y, barWidth, 1, viridis(t));
  }
  const int labelX = barX + barWidth + 2 * g;
  drawText(out, labelX, barTop, hiLabel, g, kInk);
  drawText(out, labelX, barTop + barHeight - glyphH, loLabel, g, kInk);
  return out;
}

// Swatches under the picture: framed squares with their labels, in rows.
Image8 withSwatches(const View& view, int g) {
  const Image8& pic = view.picture;
  const ViewLegend& legend = view.legend;
  const int margin = 2 * g, swatch = kGlyphHeight * g + 2;
  const int entryWidth = swatch + 2 * g + maxTextWidth(legend.labels, g) + 3 * g;
  const int width = std::max(pic.width, entryWidth + 2 * margin);
  const int perRow = std::max(1, (width - 2 * margin) / entryWidth);
  const int rowHeight = swatch + 2 * g;
  const int rows = int((legend.values.size() + size_t(perRow) - 1) / size_t(perRow));
  const int strip = rows * rowHeight + 2 * margin - 2 * g;
  Image8 out = filledPicture(width, pic.height + std::max(strip, 0), kPanel);
  blit(out, pic, 0, 0);
  for (size_t i = 0; i < legend.values.size(); ++i) {
    const int left = margin + int(i % size_t(perRow)) * entryWidth;
    const int top = pic.height + margin + int(i / size_t(perRow)) * rowHeight;
    fill(out, left, top, swatch, swatch, kFrame);
    fill(out, left + 1, top + 1, swatch - 2, swatch - 2, legend.colours[i]);
    drawText(out, left + swatch + 2 * g, top + 1, legend.labels[i], g, kInk);
  }
  return out;
}

// A ramp under the picture: a framed horizontal bar from lo (left) to hi (right) with a tick and
// a label at each of `values`; labels that would overlap the one before are left out.
Image8 withRamp(const View& view, int g) {
  const Image8& pic = view.picture;
  const ViewLegend& legend = view.legend;
  const int margin = 3 * g, barHeight = 4 * g, tick = 2 * g, glyphH = kGlyphHeight * g;
  const int labelWidth = maxTextWidth(legend.labels, g);
  const int width = std::max(pic.width, 2 * labelWidth + 2 * margin + 8 * g);
  const int strip = margin + barHeight + tick + g + glyphH + margin;
  Image8 out = filledPicture(width, pic.height + strip, kPanel);
  blit(out, pic, 0, 0);
  const int barX = margin + labelWidth / 2, barWidth = width - 2 * barX, barY = pic.height + margin;
  fill(out, barX - 1, barY - 1, barWidth + 2, barHeight + 2, kFrame);
  for (int x = 0; x < barWidth; ++x)
    fill(out, barX + x, barY, 1, barHeight, viridis(barWidth > 1 ? double(x) / double(barWidth - 1) : 0.0));
  int lastRight = -1000000;
  for (size_t i = 0; i < legend.values.size(); ++i) {
    const double t = legend.hi > legend.lo ? (legend.values[i] - legend.lo) / (legend.hi - legend.lo) : 0.0;
    const int x = barX + int(std::lround(t * double(std::max(barWidth - 1, 0))));
    fill(out, x, barY + barHeight + 1, std::max(1, g / 2), tick, kInk);
    const std::string& label = legend.labels[i];
    const int left = std::clamp(x - textWidth(label, g) / 2, 0, width - textWidth(label, g));
    if (left < lastRight + 2 * g) continue;
    drawText(out, left, barY + barHeight + tick + g, label, g, kInk);
    lastRight = left + textWidth(label, g);
  }
  return out;
}

}  // namespace

Image8 filledPicture(int width, int height, Rgb8 colour) {
  Image8 image;
  image.width = width;
  image.height = height;
  image.channels = 4;
  image.pixels.resize(size_t(width) * size_t(height) * 4);
  fill(image, 0, 0, width, height, colour);
  return image;
}

void setBufferPixel(Image8& picture, int x, int y, Rgb8 colour) {
  fill(picture, x, picture.height - 1 - y, 1, 1, colour);
}

Image8 composeView(const View& view, int glyphScale) {
  const int g = std::max(1, glyphScale);
  switch (view.legend.kind) {
    case LegendKind::ColourBar: return withColourBar(view, g);
    case LegendKind::Swatches: return withSwatches(view, g);
    case LegendKind::Ramp: return withRamp(view, g);
    case LegendKind::None: break;
  }
  return view.picture;
}

void writeViewPng(const View& view, const std::string& path, const OutputMetadata& metadata, int glyphScale) {
  writePng8(composeView(view, glyphScale), path, metadata);
}

}  // namespace shadowref::views
