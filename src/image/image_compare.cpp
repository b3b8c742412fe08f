#include "image/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

namespace shadowref {

double Tolerances::forChannel(const std::string& name) const {
  auto it = perChannel.find(name);
  return it == perChannel.end() ? fallback : it->second;
}

double Tolerances::warnForChannel(const std::string& name) const {
  return warn < 0.0 ? forChannel(name) : warn;
}

const char* verdictName(Verdict v) {
  switch (v) {
    case Verdict::Pass: return "PASS";
    case Verdict::Warn: return "WARNING";
    case Verdict::Fail: return "FAILURE";
  }
  return "FAILURE";
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

// v mod m in [0, m) for an integer-valued v (a count read from a 32-bit channel, signed or not).
double wrapInteger(double v, uint32_t m) {
  const double r = std::fmod(v, double(m));
  return r < 0.0 ? r + double(m) : r;
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

double channelDifference(double a, double b, bool integer, uint32_t integerModulo) {
  if (integer && integerModulo > 0 && std::isfinite(a) && std::isfinite(b))
    return absDiff(wrapInteger(a, integerModulo), wrapInteger(b, integerModulo));
  return absDiff(a, b);
}

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
    s.integer = a.isInteger(c) && b.isInteger(size_t(inB[c]));
    s.tolerance = tol.forChannel(s.name);
    s.warn = tol.warnForChannel(s.name);
    r.channels.push_back(s);
  }
  std::vector<double> sums(nc, 0.0), squares(nc, 0.0);
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const size_t i = size_t(y) * size_t(a.width) + size_t(x);
      PixelFailure failure;
      bool warned = false;
      for (size_t c = 0; c < nc; ++c) {
        ChannelStats& s = r.channels[c];
        const double d = channelDifference(a.data[c][i], b.data[size_t(inB[c])][i], s.integer, tol.integerModulo);
        if (d > s.maxAbsDiff) {
          s.maxAbsDiff = d;
          s.maxX = x;
          s.maxY = y;
        }
        if (std::isfinite(d)) {
          sums[c] += d;
          squares[c] += d * d;
        }
        if (d > s.warn) {
          ++s.warnCount;
          warned = true;
        }
        if (d > s.tolerance) {
          ++s.failCount;
          failure.failingChannels.push_back(s.name);
        }
      }
      if (warned) ++r.warnedPixels;
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
  double maxDiff = 0.0;
  for (size_t c = 0; c < nc; ++c) {
    ChannelStats& s = r.channels[c];
    s.meanAbsDiff = pixels > 0 ? sums[c] / pixels : 0.0;
    s.rmse = pixels > 0 ? std::sqrt(squares[c] / pixels) : 0.0;
    const double peak = s.integer ? 255.0 : 1.0;
    s.psnr = s.rmse > 0.0 ? 20.0 * std::log10(peak / s.rmse) : std::numeric_limits<double>::infinity();
    maxDiff = std::max(maxDiff, s.maxAbsDiff);
  }
  // idiff's decision: a share of failing pixels (or up to allowFailures of them) is tolerated, and
  // then reported as a warning, since those pixels are over the warning level too when it is at
  // most the tolerance. (idiff 2.4 skips the warning test whenever no more than allowFailures
  // pixels fail, so its warning level never acts alone; here it does.)
  const bool failed = r.failedPixels > tol.allowFailures &&
                      (double(r.failedPixels) > tol.failPercent / 100.0 * pixels || maxDiff > tol.hardFail);
  const bool warned = double(r.warnedPixels) > tol.warnPercent / 100.0 * pixels || maxDiff > tol.hardWarn;
  r.verdict = failed ? Verdict::Fail : warned ? Verdict::Warn : Verdict::Pass;
  r.passed = r.verdict != Verdict::Fail;
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
  const double share = pixels ? 100.0 * double(r.failedPixels) / double(pixels) : 0.0;
  char line[320];
  if (r.verdict == Verdict::Pass && r.failedPixels == 0) {
    out += "PASSED (" + std::to_string(r.width) + "x" + std::to_string(r.height) + ", every channel within tolerance)\n";
  } else if (r.verdict == Verdict::Pass) {
    std::snprintf(line, sizeof line, "PASSED: %zu of %zu pixels (%.3f%%) differ beyond tolerance, within the allowance\n",
                  r.failedPixels, pixels, share);
    out += line;
  } else if (r.verdict == Verdict::Warn) {
    std::snprintf(line, sizeof line,
                  "WARNING: %zu of %zu pixels (%.3f%%) over the warning level, %zu (%.3f%%) beyond tolerance\n",
                  r.warnedPixels, pixels, pixels ? 100.0 * double(r.warnedPixels) / double(pixels) : 0.0,
                  r.failedPixels, share);
    out += line;
  } else {
    std::snprintf(line, sizeof line, "FAILED: %zu of %zu pixels (%.3f%%) differ beyond tolerance\n", r.failedPixels,
                  pixels, share);
    out += line;
  }
  std::snprintf(line, sizeof line, "  %-12s %-15s %-15s %-12s %-15s %-15s %-9s %s\n", "channel", "tolerance",
                "max |A-B|", "at (x, y)", "mean |A-B|", "RMSE", "PSNR dB", "failing");
  out += line;
  for (const ChannelStats& s : r.channels) {
    std::string at = s.maxX < 0 ? "-" : "(" + std::to_string(s.maxX) + ", " + std::to_string(s.maxY) + ")";
    char psnr[32];
    std::snprintf(psnr, sizeof psnr, std::isinf(s.psnr) ? "inf" : "%.2f", s.psnr);
    char failing[64];
    std::snprintf(failing, sizeof failing, "%zu (%.3f%%)%s", s.failCount,
                  pixels ? 100.0 * double(s.failCount) / double(pixels) : 0.0, s.integer ? "  integer" : "");
    std::snprintf(line, sizeof line, "  %-12s %-15s %-15s %-12s %-15s %-15s %-9s %s\n", s.name.c_str(),
                  number(s.tolerance).c_str(), number(s.maxAbsDiff).c_str(), at.c_str(), number(s.meanAbsDiff).c_str(),
                  number(s.rmse).c_str(), psnr, failing);
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

namespace shadowref {

namespace {

// JSON has no infinity or NaN: those become strings.
nlohmann::ordered_json jsonNumber(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

}  // namespace

std::string formatJson(const CompareResult& r) {
  nlohmann::ordered_json j;
  j["a"] = r.nameA;
  j["b"] = r.nameB;
  if (!r.structuralError.empty()) {
    j["verdict"] = verdictName(Verdict::Fail);
    j["error"] = r.structuralError;
    return j.dump(2) + "\n";
  }
  const double pixels = double(r.width) * double(r.height);
  j["verdict"] = verdictName(r.verdict);
  j["width"] = r.width;
  j["height"] = r.height;
  j["failed_pixels"] = r.failedPixels;
  j["failed_percent"] = pixels > 0 ? 100.0 * double(r.failedPixels) / pixels : 0.0;
  j["warned_pixels"] = r.warnedPixels;
  j["warned_percent"] = pixels > 0 ? 100.0 * double(r.warnedPixels) / pixels : 0.0;
  nlohmann::ordered_json channels = nlohmann::ordered_json::array();
  for (const ChannelStats& s : r.channels) {
    nlohmann::ordered_json c;
    c["name"] = s.name;
    c["integer"] = s.integer;
    c["tolerance"] = jsonNumber(s.tolerance);
    c["warn"] = jsonNumber(s.warn);
    c["max_abs"] = jsonNumber(s.maxAbsDiff);
    c["max_at"] = s.maxX < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json::array({s.maxX, s.maxY});
    c["mean_abs"] = jsonNumber(s.meanAbsDiff);
    c["rmse"] = jsonNumber(s.rmse);
    c["psnr"] = jsonNumber(s.psnr);
    c["over_tolerance"] = s.failCount;
    c["over_tolerance_percent"] = pixels > 0 ? 100.0 * double(s.failCount) / pixels : 0.0;
    c["over_warn"] = s.warnCount;
    channels.push_back(std::move(c));
  }
  j["channels"] = std::move(channels);
  nlohmann::ordered_json first = nlohmann::ordered_json::array();
  for (const PixelFailure& f : r.firstFailures) {
    nlohmann::ordered_json p;
    p["x"] = f.x;
    p["y"] = f.y;
    p["fb_row"] = f.glY;
    p["channels"] = f.failingChannels;
    nlohmann::ordered_json va = nlohmann::ordered_json::array(), vb = nlohmann::ordered_json::array();
    for (size_t c = 0; c < f.a.size(); ++c) {
      va.push_back(jsonNumber(f.a[c]));
      vb.push_back(jsonNumber(f.b[c]));
    }
    p["a"] = std::move(va);
    p["b"] = std::move(vb);
    first.push_back(std::move(p));
  }
  j["first_failures"] = std::move(first);
  return j.dump(2) + "\n";
}

}  // namespace shadowref
