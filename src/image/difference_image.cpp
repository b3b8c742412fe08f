#include "image/difference_image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "image/bitmap_font.h"
#include "image/image_compare.h"

namespace shadowref {

std::vector<double> differenceMap(const ChannelImage& a, const ChannelImage& b, const DifferenceMapOptions& options) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("the images differ in size: no difference picture");
  std::vector<size_t> channelsA;
  if (options.channel.empty()) {
    for (size_t c = 0; c < a.names.size(); ++c) channelsA.push_back(c);
  } else {
    const int c = a.channelIndex(options.channel);
    if (c < 0) throw std::invalid_argument("no channel '" + options.channel + "' to draw the difference of");
    channelsA.push_back(size_t(c));
  }
  const size_t n = size_t(a.width) * size_t(a.height);
  std::vector<double> diffs(n, 0.0);
  for (size_t ca : channelsA) {
    const int cb = b.channelIndex(a.names[ca]);
    if (cb < 0) throw std::invalid_argument("channel '" + a.names[ca] + "' is not in both images");
    const bool integer = a.isInteger(ca) && b.isInteger(size_t(cb));
    for (size_t i = 0; i < n; ++i)
      diffs[i] = std::max(diffs[i], channelDifference(a.data[ca][i], b.data[size_t(cb)][i], integer,
                                                      options.integerModulo));
  }
  return diffs;
}

std::array<uint8_t, 3> heatColour(double t) {
  if (std::isinf(t)) return {255, 0, 255};
  if (!(t > 0.0)) return {0, 0, 0};
  // Piecewise linear between stops whose luma rises (25, 57, 92, 176, 255 in Rec. 601 weights),
  // so a clearly larger difference is never drawn darker than a smaller one.
  struct Stop {
    double t;
    double r, g, b;
  };
  static constexpr Stop kStops[] = {
      {0.0, 48, 0, 96}, {0.25, 128, 0, 160}, {0.5, 230, 30, 40}, {0.75, 255, 170, 0}, {1.0, 255, 255, 255}};
  t = std::min(t, 1.0);
  for (size_t k = 1; k < std::size(kStops); ++k) {
    if (t > kStops[k].t) continue;
    const Stop& lo = kStops[k - 1];
    const Stop& hi = kStops[k];
    const double f = (t - lo.t) / (hi.t - lo.t);
    auto mix = [f](double x, double y) { return uint8_t(std::lround(x + (y - x) * f)); };
    return {mix(lo.r, hi.r), mix(lo.g, hi.g), mix(lo.b, hi.b)};
  }
  return {255, 255, 255};
}

double heatScaleTop(const std::vector<double>& diffs, double top) {
  if (top > 0.0) return top;
  double largest = 0.0;
  for (double d : diffs)
    if (std::isfinite(d)) largest = std::max(largest, d);
  return largest > 0.0 ? largest : 1.0;
}

int heatPixelScale(int width, int height) {
  const int longest = std::max(1, std::max(width, height));
  return std::clamp(128 / longest, 1, 8);
}

namespace {

std::string label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

void fill(Image8& image, int x0, int y0, int w, int h, std::array<uint8_t, 3> colour) {
  for (int y = std::max(0, y0); y < std::min(image.height, y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x0 + w); ++x) {
      const size_t i = (size_t(y) * size_t(image.width) + size_t(x)) * 3;
      image.pixels[i] = colour[0];
      image.pixels[i + 1] = colour[1];
      image.pixels[i + 2] = colour[2];
    }
}

}  // namespace

Image8 differenceHeatMap(const std::vector<double>& diffs, int width, int height, double top, int pixelScale) {
  if (width <= 0 || height <= 0 || diffs.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("differenceHeatMap: " + std::to_string(diffs.size()) + " values for " +
                                std::to_string(width) + "x" + std::to_string(height));
  const int k = pixelScale > 0 ? pixelScale : heatPixelScale(width, height);
  const double scaleTop = heatScaleTop(diffs, top);
  constexpr int kMargin = 4, kBarHeight = 10, kGlyphScale = 2, kMinBar = 96;
  const std::string hi = label(scaleTop);
  const int barWidth = std::max({width * k - 2 * kMargin, kMinBar, textWidth("0", kGlyphScale) + textWidth(hi, kGlyphScale) + 8});
  Image8 image;
  image.width = std::max(width * k, barWidth + 2 * kMargin);
  const int strip = kMargin + kBarHeight + 3 + kGlyphHeight * kGlyphScale + kMargin;
  image.height = height * k + strip;
  image.channels = 3;
  image.pixels.assign(size_t(image.width) * size_t(image.height) * 3, 0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double d = diffs[size_t(y) * size_t(width) + size_t(x)];
      fill(image, x * k, y * k, k, k, heatColour(std::isinf(d) ? d : d / scaleTop));
    }
  // The scale: a dark grey strip, the ramp from 0 to the top left to right, "0" under its left
  // end and the top's value under its right end.
  const int stripTop = height * k;
  fill(image, 0, stripTop, image.width, strip, {48, 48, 48});
  const int barTop = stripTop + kMargin;
  for (int x = 0; x < barWidth; ++x)
    fill(image, kMargin + x, barTop, 1, kBarHeight, heatColour(barWidth > 1 ? double(x) / double(barWidth - 1) : 1.0));
  const int textTop = barTop + kBarHeight + 3;
  drawText(image, kMargin, textTop, "0", kGlyphScale, {230, 230, 230});
  drawText(image, kMargin + barWidth - textWidth(hi, kGlyphScale), textTop, hi, kGlyphScale, {230, 230, 230});
  return image;
}

}  // namespace shadowref
