// An image as named channels of numbers, the common ground on which files and framebuffers are
// compared (image_compare.h). Values are doubles, which hold every float and every 32-bit count
// exactly.
#pragma once

#include <string>
#include <vector>

#include "image/image_writer.h"
#include "raster/framebuffer.h"

namespace shadowref {

struct ChannelImage {
  int width = 0;
  int height = 0;
  std::vector<std::string> names;
  // data[c][y * width + x]: channel c of pixel (x, y), y counted from the TOP (file order).
  std::vector<std::vector<double>> data;

  int channelIndex(const std::string& name) const;  // -1 if absent
};

// Reads subimage 0 of any file OpenImageIO can read; throws std::runtime_error if it cannot.
// How a channel's stored type becomes a number:
//   32-bit integer (EXR UINT, e.g. stencil) -> the integer itself (a count, not a colour);
//   8/16-bit integer (PNG, TIFF colour)     -> normalised to [0, 1], as OpenImageIO does;
//   half / float / double                   -> the value.
ChannelImage readChannelImage(const std::string& path);

// The channels writeExr would write for fb and extras (exrChannels), flipped to file order:
// comparing this with a read EXR compares exactly what a round trip would keep.
ChannelImage channelImageOf(const Framebuffer& fb, const ExrExtras& extras = {});

}  // namespace shadowref
