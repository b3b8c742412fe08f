// Pixel-by-pixel comparison of two images, per channel by name, with an absolute tolerance per
// channel and idiff's thresholds (a share of failing pixels allowed, a warning level, hard limits)
// — what `shadowref compare A B` and the golden suite report. Unlike idiff, which reads every
// channel as a normalised float (a 32-bit stencil count of 1 against 2 differs by 2^-32 there and
// passes), 32-bit integer channels are compared as the integers they hold.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "image/channel_image.h"
#include "image/image_writer.h"
#include "gl/framebuffer.h"

namespace shadowref {

// A pixel fails in a channel when |a - b| > tolerance, and is over the warning level when
// |a - b| > warn. Equal values (also two NaNs, or two equal infinities) never fail; NaN against a
// number always fails. Integer channels (ChannelImage::integer) are differences of whole counts.
struct Tolerances {
  double fallback = 0.0;                     // for every channel not named below
  std::map<std::string, double> perChannel;  // exact channel name -> absolute tolerance
  // The warning level for every channel; negative: each channel's own tolerance.
  double warn = -1.0;
  // Integer channels compared modulo this (256: an 8-bit stencil buffer, where a count of 257 is
  // the value 1); 0 compares the integers as they are.
  uint32_t integerModulo = 0;

  // The verdict, as idiff decides it: FAIL when more than failPercent % of the pixels (and more
  // than allowFailures of them) fail, or when any difference exceeds hardFail; otherwise WARN when
  // more than warnPercent % are over the warning level or any difference exceeds hardWarn.
  double failPercent = 0.0;
  double warnPercent = 0.0;
  double hardFail = std::numeric_limits<double>::infinity();
  double hardWarn = std::numeric_limits<double>::infinity();
  size_t allowFailures = 0;

  double forChannel(const std::string& name) const;
  double warnForChannel(const std::string& name) const;

  // For goldens: colour (R, G, B, A) within 1/255, everything else (Z, stencil, extras) exact.
  static Tolerances golden();
};

struct ChannelStats {
  std::string name;
  bool integer = false;      // compared as whole counts (a 32-bit integer channel in both images)
  double tolerance = 0.0;
  double warn = 0.0;         // the warning level used
  double maxAbsDiff = 0.0;   // infinity when a NaN met a number
  double meanAbsDiff = 0.0;  // over all pixels, counting NaN mismatches as 0 (they are in failCount)
  double rmse = 0.0;         // root of the mean squared difference, NaN mismatches counted as 0
  // Peak signal-to-noise ratio in dB, 20 log10(peak / rmse): peak 1 for colour, depth and floats,
  // 255 for integer channels (the range of an 8-bit stencil); infinity when rmse is 0.
  double psnr = 0.0;
  size_t failCount = 0;      // pixels whose difference in this channel exceeds the tolerance
  size_t warnCount = 0;      // pixels whose difference in this channel exceeds the warning level
  int maxX = -1, maxY = -1;  // where maxAbsDiff occurs first (image coordinates), -1 if no difference
};

enum class Verdict { Pass, Warn, Fail };
const char* verdictName(Verdict v);  // "PASS", "WARNING", "FAILURE" (as idiff prints them)

struct PixelFailure {
  int x = 0;
  int y = 0;     // image row, 0 = TOP row of the file (as idiff and image viewers count)
  int glY = 0;   // the same row counted from the bottom: the framebuffer's (glReadPixels) row
  std::vector<std::string> failingChannels;
  std::vector<double> a, b;  // every channel's value, in CompareResult::channels order
};

struct CompareResult {
  bool passed = false;          // verdict != Fail (with the default thresholds: no pixel fails)
  Verdict verdict = Verdict::Fail;
  std::string structuralError;  // non-empty when sizes or channel sets differ: nothing compared
  std::string nameA, nameB;
  int width = 0, height = 0;
  std::vector<ChannelStats> channels;  // in A's channel order
  size_t failedPixels = 0;             // pixels failing in at least one channel
  size_t warnedPixels = 0;             // pixels over the warning level in at least one channel
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

// The difference of channel c of A and B at pixel i as compareChannelImages measures it: |a - b|,
// 0 for equal values (two NaNs included), infinity for NaN against a number; an integer channel
// modulo tol.integerModulo when set.
double channelDifference(double a, double b, bool integer, uint32_t integerModulo);

// A human-readable report: verdict, per-channel statistics, the first failing pixels with both
// images' values. Ends with a newline.
std::string formatReport(const CompareResult& result);

// The same as one JSON object (verdict, sizes, counts, and per channel every statistic), ending
// with a newline. Infinite values are written as the strings "inf" (JSON has no infinity).
std::string formatJson(const CompareResult& result);

}  // namespace shadowref
