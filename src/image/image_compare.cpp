#include "image/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace shadowref {

double Tolerances::forChannel(const std::string& name) const {
  auto it = perChannel.find(name);
  return it == perChannel.end() ? fallback : it->second;
}

Tolerances Tolerances::golden() {
  Tolerances t;
  t.fallback = 0.0;
  for (const char* c : {"R", "G", "B", "A"}) t.perChannel[c] = 1.0 / 255.0;
  return t;
}

namespace {

// |a - b|, with equal values (including two NaNs) giving 0 and NaN against a number infinity.
double absDiff(double a, double b) {
  if (a == b) return 0.0;
  if (std::isnan(a) && std::isnan(b)) return 0.0;
  if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<double>::infinity();
  return std::fabs(a - b);
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "(none)" : s;
}

// Sizes and channel sets must agree before any pixel is compared.
std::string structuralDifference(const ChannelImage& a, const ChannelImage& b) {
  if (a.width != b.width || a.height != b.height)
    return "sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
           std::to_string(b.width) + "x" + std::to_string(b.height);
  std::vector<std::string> onlyA, onlyB;
  for (const std::string& n : a.names)
    if (b.channelIndex(n) < 0) onlyA.push_back(n);
  for (const std::string& n : b.names)
    if (a.channelIndex(n) < 0) onlyB.push_back(n);
  if (!onlyA.empty() || !onlyB.empty())
    return "channel sets differ: only in A: " + joinNames(onlyA) + "; only in B: " + joinNames(onlyB);
  return "";
}

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

CompareResult compareChannelImages(const ChannelImage& a, const ChannelImage& b, const Tolerances& tol,
                                   size_t maxReported) {
  CompareResult r;
  r.width = a.width;
  r.height = a.height;
  r.structuralError = structuralDifference(a, b);
  if (!r.structuralError.empty()) return r;

  const size_t nc = a.names.size();
  std::vector<int> inB(nc);  // channel c of A is channel inB[c] of B
  for (size_t c = 0; c < nc; ++c) {
    inB[c] = b.channelIndex(a.names[c]);
    ChannelStats s;
    s.name = a.names[c];
    s.tolerance = tol.forChannel(s.name);
    r.channels.push_back(s);
  }
  std::vector<double> sums(nc, 0.0);
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const size_t i = size_t(y) * size_t(a.width) + size_t(x);
      PixelFailure failure;
      for (size_t c = 0; c < nc; ++c) {
        const double d = absDiff(a.data[c][i], b.data[size_t(inB[c])][i]);
        ChannelStats& s = r.channels[c];
        if (d > s.maxAbsDiff) {
          s.maxAbsDiff = d;
          s.maxX = x;
          s.maxY = y;
        }
        if (std::isfinite(d)) sums[c] += d;
        if (d > s.tolerance) {
          ++s.failCount;
          failure.failingChannels.push_back(s.name);
        }
      }
      if (failure.failingChannels.empty()) continue;
      ++r.failedPixels;
      if (r.firstFailures.size() >= maxReported) continue;
      failure.x = x;
      failure.y = y;
      failure.glY = a.height - 1 - y;
      for (size_t c = 0; c < nc; ++c) {
        failure.a.push_back(a.data[c][i]);
        failure.b.push_back(b.data[size_t(inB[c])][i]);
      }
      r.firstFailures.push_back(std::move(failure));
    }
  }
  const double pixels = double(a.width) * double(a.height);
  for (size_t c = 0; c < nc; ++c) r.channels[c].meanAbsDiff = pixels > 0 ? sums[c] / pixels : 0.0;
  r.passed = r.failedPixels == 0;
  return r;
}

CompareResult compareImages(const std::string& pathA, const std::string& pathB, const Tolerances& tol,
                            size_t maxReported) {
  CompareResult r = compareChannelImages(readChannelImage(pathA), readChannelImage(pathB), tol, maxReported);
  r.nameA = pathA;
  r.nameB = pathB;
  return r;
}

CompareResult compareWithExr(const Framebuffer& fb, const std::string& goldenExr, const Tolerances& tol,
                             size_t maxReported) {
  return compareWithExr(fb, ExrExtras{}, goldenExr, tol, maxReported);
}

CompareResult compareWithExr(const Framebuffer& fb, const ExrExtras& extras, const std::string& goldenExr,
                             const Tolerances& tol, size_t maxReported) {
  CompareResult r = compareChannelImages(channelImageOf(fb, extras), readChannelImage(goldenExr), tol, maxReported);
  r.nameA = "framebuffer";
  r.nameB = goldenExr;
  return r;
}

std::string formatReport(const CompareResult& r) {
  const std::string a = r.nameA.empty() ? "A" : r.nameA;
  const std::string b = r.nameB.empty() ? "B" : r.nameB;
  std::string out = "compare " + a + " (A) with " + b + " (B): ";
  if (!r.structuralError.empty()) return out + "FAILED: " + r.structuralError + "\n";

  const size_t pixels = size_t(r.width) * size_t(r.height);
  char line[256];
  if (r.passed) {
    out += "PASSED (" + std::to_string(r.width) + "x" + std::to_string(r.height) + ", every channel within tolerance)\n";
  } else {
    std::snprintf(line, sizeof line, "FAILED: %zu of %zu pixels (%.3f%%) differ beyond tolerance\n", r.failedPixels,
                  pixels, pixels ? 100.0 * double(r.failedPixels) / double(pixels) : 0.0);
    out += line;
  }
  std::snprintf(line, sizeof line, "  %-12s %-15s %-15s %-12s %-15s %s\n", "channel", "tolerance", "max |A-B|",
                "at (x, y)", "mean |A-B|", "failing");
  out += line;
  for (const ChannelStats& s : r.channels) {
    std::string at = s.maxX < 0 ? "-" : "(" + std::to_string(s.maxX) + ", " + std::to_string(s.maxY) + ")";
    std::snprintf(line, sizeof line, "  %-12s %-15s %-15s %-12s %-15s %zu\n", s.name.c_str(), number(s.tolerance).c_str(),
                  number(s.maxAbsDiff).c_str(), at.c_str(), number(s.meanAbsDiff).c_str(), s.failCount);
    out += line;
  }
  if (!r.firstFailures.empty()) {
    out += "  first failing pixels (x, y: y counted from the top row of the file; fb row: from the bottom):\n";
    for (const PixelFailure& f : r.firstFailures) {
      out += "    (" + std::to_string(f.x) + ", " + std::to_string(f.y) + ") fb row " + std::to_string(f.glY) + ":";
      for (size_t c = 0; c < r.channels.size(); ++c) {
        const bool failing = std::find(f.failingChannels.begin(), f.failingChannels.end(), r.channels[c].name) !=
                             f.failingChannels.end();
        if (!failing) continue;
        out += " " + r.channels[c].name + " A=" + number(f.a[c]) + " B=" + number(f.b[c]);
      }
      out += "\n";
    }
    if (r.failedPixels > r.firstFailures.size())
      out += "    ... and " + std::to_string(r.failedPixels - r.firstFailures.size()) + " more\n";
  }
  return out;
}

}  // namespace shadowref
