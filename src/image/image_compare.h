// Pixel-by-pixel comparison of two images, per channel by name, with an absolute tolerance per
// channel — what `idiff` does, and what `shadowref compare A B` and the golden suite report.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "image/channel_image.h"
#include "image/image_writer.h"
#include "gl/framebuffer.h"

namespace shadowref {

// A pixel fails in a channel when |a - b| > tolerance. Equal values (also two NaNs, or two equal
// infinities) never fail; NaN against a number always fails.
struct Tolerances {
  double fallback = 0.0;                     // for every channel not named below
  std::map<std::string, double> perChannel;  // exact channel name -> absolute tolerance

  double forChannel(const std::string& name) const;

  // For goldens: colour (R, G, B, A) within 1/255, everything else (Z, stencil, extras) exact.
  static Tolerances golden();
};

struct ChannelStats {
  std::string name;
  double tolerance = 0.0;
  double maxAbsDiff = 0.0;   // infinity when a NaN met a number
  double meanAbsDiff = 0.0;  // over all pixels, counting NaN mismatches as 0 (they are in failCount)
  size_t failCount = 0;      // pixels whose difference in this channel exceeds the tolerance
  int maxX = -1, maxY = -1;  // where maxAbsDiff occurs first (image coordinates), -1 if no difference
};

struct PixelFailure {
  int x = 0;
  int y = 0;     // image row, 0 = TOP row of the file (as idiff and image viewers count)
  int glY = 0;   // the same row counted from the bottom: the framebuffer's (glReadPixels) row
  std::vector<std::string> failingChannels;
  std::vector<double> a, b;  // every channel's value, in CompareResult::channels order
};

struct CompareResult {
  bool passed = false;
  std::string structuralError;  // non-empty when sizes or channel sets differ: nothing compared
  std::string nameA, nameB;
  int width = 0, height = 0;
  std::vector<ChannelStats> channels;  // in A's channel order
  size_t failedPixels = 0;             // pixels failing in at least one channel
  std::vector<PixelFailure> firstFailures;  // up to maxReported, in file order (top row first)
};

// Compares two channel images. Channels are matched by name (order may differ); different sizes
// or different channel sets fail with a structuralError naming the difference.
CompareResult compareChannelImages(const ChannelImage& a, const ChannelImage& b, const Tolerances& tol,
                                   size_t maxReported = 10);

// Reads both files (any format OpenImageIO reads; see readChannelImage for how integer channels
// are read) and compares them. A file that cannot be read throws std::runtime_error: that is bad
// input, not a failed comparison.
CompareResult compareImages(const std::string& pathA, const std::string& pathB, const Tolerances& tol,
                            size_t maxReported = 10);

// Compares what writeExr would write for fb (A) with a golden EXR (B). Defaults: stencil and Z
// exact, colour within 1/255.
CompareResult compareWithExr(const Framebuffer& fb, const std::string& goldenExr,
                             const Tolerances& tol = Tolerances::golden(), size_t maxReported = 10);
// The same for a golden written with extra channels (per-light stencil "stencil.L0", ...).
CompareResult compareWithExr(const Framebuffer& fb, const ExrExtras& extras, const std::string& goldenExr,
                             const Tolerances& tol = Tolerances::golden(), size_t maxReported = 10);

// A human-readable report: verdict, per-channel statistics, the first failing pixels with both
// images' values. Ends with a newline.
std::string formatReport(const CompareResult& result);

}  // namespace shadowref
