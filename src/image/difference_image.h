// The picture of a comparison: where two images differ and by how much, as a heat map with a
// colour scale — what `shadowref compare --diff` and the golden failure reports draw.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "image/channel_image.h"
#include "image/image_writer.h"

namespace shadowref {

struct DifferenceMapOptions {
  // One channel's difference, or "" for all compared channels combined: per pixel the largest
  // difference over them (each in its own unit: colour and depth in [0, 1], counts in counts).
  std::string channel;
  // Integer channels compared modulo this (see Tolerances::integerModulo); 0: as they are.
  uint32_t integerModulo = 0;
};

// Per pixel (file order, top row first) the difference of A and B as compareChannelImages measures
// it (channelDifference). A and B must have the same size, and the channel (or, combined, every
// channel of A) must be in both; otherwise throws std::invalid_argument naming what is missing.
std::vector<double> differenceMap(const ChannelImage& a, const ChannelImage& b, const DifferenceMapOptions& options);

// The heat-map colour of a difference t (the difference divided by the top of the scale):
// 0 is black, so equal pixels stay black; above 0 the colour runs from dark violet through red,
// orange and yellow to white at t >= 1. An infinite difference (NaN against a number) is magenta.
std::array<uint8_t, 3> heatColour(double t);

// The heat map of `diffs` (width x height, top row first), each pixel drawn as pixelScale x
// pixelScale picture pixels, and below it on a dark grey strip the colour scale from 0 to `top`
// with both ends labelled. top <= 0 uses the largest finite difference (1 when there is none).
// pixelScale 0 chooses one: up to 8, so that small images are at least 128 pixels across.
Image8 differenceHeatMap(const std::vector<double>& diffs, int width, int height, double top = 0.0,
                         int pixelScale = 0);

// The top of the scale differenceHeatMap uses for `diffs` and `top`.
double heatScaleTop(const std::vector<double>& diffs, double top);

// The pixel scale differenceHeatMap chooses for pixelScale 0.
int heatPixelScale(int width, int height);

}  // namespace shadowref
