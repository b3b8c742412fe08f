// An image as named channels of numbers, the common ground on which files and framebuffers are
// compared (image_compare.h). Values are doubles, which hold every float and every 32-bit count
// exactly.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image/image_writer.h"
#include "gl/framebuffer.h"

namespace shadowref {

struct ChannelImage {
  int width = 0;
  int height = 0;
  std::vector<std::string> names;
  // data[c][y * width + x]: channel c of pixel (x, y), y counted from the TOP (file order).
  std::vector<std::vector<double>> data;
  // integer[c]: channel c holds 32-bit integers (counts such as stencil), not normalised colour or
  // floats. Empty means none does.
  std::vector<bool> integer;

  int channelIndex(const std::string& name) const;  // -1 if absent
  bool isInteger(size_t c) const { return c < integer.size() && integer[c]; }
};

// What readChannelImage decodes at most, checked from the file's header before any pixel memory
// is allocated, so that a small file declaring a huge image is refused, not zero-filled.
struct ReadLimits {
  // width x height x channels; each value is a double, so 2^29 values are 4 GiB (8192 x 8192 with
  // 8 channels).
  uint64_t maxValues = uint64_t(1) << 29;
  // The file itself: a regular file of at most this many bytes (1 GiB holds an uncompressed
  // 8192 x 8192 EXR with 4 float channels).
  uint64_t maxFileBytes = uint64_t(1) << 30;
};

// Reads subimage 0 of any file OpenImageIO can read; throws std::runtime_error if it cannot.
// Before OpenImageIO opens it: a regular file of at most limits.maxFileBytes, and for OpenEXR every
// header attribute within the file (checkExrHeaders). Before reading pixels: width, height and channels must be positive, their product within
// limits.maxValues (overflow-safe), and where the compression bounds how much a byte can expand
// to — PNG and EXR zip/zips (deflate, at most 1032:1), EXR pxr24 (1376:1), rle (128:1), none
// (1:1) — the declared pixel bytes must fit in what the file's size can hold.
// How a channel's stored type becomes a number:
//   32-bit integer (EXR UINT, e.g. stencil) -> the integer itself (a count, not a colour);
//   8/16-bit integer (PNG, TIFF colour)     -> normalised to [0, 1], as OpenImageIO does;
//   half / float / double                   -> the value.
ChannelImage readChannelImage(const std::string& path, const ReadLimits& limits = {});

// The channels writeExr would write for fb and extras (exrChannels), flipped to file order:
// comparing this with a read EXR compares exactly what a round trip would keep.
ChannelImage channelImageOf(const Framebuffer& fb, const ExrExtras& extras = {});

}  // namespace shadowref
