#include "image/failure_report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "image/atomic_write.h"
#include "image/difference_image.h"
#include "image/stencil_view.h"

namespace shadowref {

namespace fs = std::filesystem;

namespace {

std::string html(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// A channel name as a file name: anything but letters, digits, '-' and '_' becomes '_'.
std::string fileSafe(const std::string& name) {
  std::string out = name;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return out;
}

void writeText(const fs::path& path, const std::string& text) {
  writeFileAtomically(path.string(), [&](const TempFile& temp) { writeAllAt(temp.fd, text.data(), text.size(), 0); });
}

std::string picture(const std::string& file, const std::string& caption) {
  return "<figure><img src=\"" + html(file) + "\" alt=\"" + html(caption) + "\"><figcaption>" + html(caption) +
         "</figcaption></figure>\n";
}

const char* kStyle =
    "<style>body{font-family:sans-serif;background:#222;color:#ddd}figure{display:inline-block;margin:6px}"
    "img{image-rendering:pixelated;border:1px solid #555;min-width:200px}pre{background:#111;padding:8px;"
    "overflow-x:auto}a{color:#8cf}</style>\n";

void rewriteIndex(const fs::path& folder) {
  std::vector<std::string> cases;
  for (const fs::directory_entry& e : fs::directory_iterator(folder))
    if (e.is_directory() && fs::exists(e.path() / "index.html")) cases.push_back(e.path().filename().string());
  std::sort(cases.begin(), cases.end());
  std::ostringstream page;
  page << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>shadowref failure report</title>\n" << kStyle
       << "</head><body>\n<h1>Failing cases (" << cases.size() << ")</h1>\n<ul>\n";
  for (const std::string& c : cases) page << "<li><a href=\"" << html(c) << "/index.html\">" << html(c) << "</a></li>\n";
  page << "</ul>\n</body></html>\n";
  writeText(folder / "index.html", page.str());
}

}  // namespace

Image8 viewOf(const ChannelImage& image, const std::string& channel) {
  Image8 out;
  out.width = image.width;
  out.height = image.height;
  out.channels = 3;
  const size_t n = size_t(image.width) * size_t(image.height);
  out.pixels.assign(n * 3, 0);
  const int r = image.channelIndex("R"), g = image.channelIndex("G"), b = image.channelIndex("B");
  if (channel.empty() && r >= 0 && g >= 0 && b >= 0) {
    for (size_t i = 0; i < n; ++i) {
      const int cs[3] = {r, g, b};
      for (int k = 0; k < 3; ++k) {
        const double v = image.data[size_t(cs[k])][i];
        out.pixels[i * 3 + size_t(k)] = uint8_t(std::lround(std::clamp(std::isnan(v) ? 0.0 : v, 0.0, 1.0) * 255.0));
      }
    }
    return out;
  }
  const int c = channel.empty() ? (image.names.empty() ? -1 : 0) : image.channelIndex(channel);
  if (c < 0) return out;
  const std::vector<double>& values = image.data[size_t(c)];
  if (image.isInteger(size_t(c))) {
    for (size_t i = 0; i < n; ++i) {
      const auto colour = stencilColour(int(std::clamp(values[i], -1e6, 1e6)));
      for (int k = 0; k < 3; ++k) out.pixels[i * 3 + size_t(k)] = colour[size_t(k)];
    }
    return out;
  }
  double lo = INFINITY, hi = -INFINITY;
  for (double v : values)
    if (std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  for (size_t i = 0; i < n; ++i) {
    const double v = values[i];
    const double t = !std::isfinite(v) || !(hi > lo) ? 0.0 : (v - lo) / (hi - lo);
    const uint8_t grey = uint8_t(std::lround(t * 255.0));
    for (int k = 0; k < 3; ++k) out.pixels[i * 3 + size_t(k)] = grey;
  }
  return out;
}

std::string writeFailureReport(const std::string& folder, const ReportCase& c) {
  if (!c.reference || !c.result) throw std::invalid_argument("writeFailureReport: no images for " + c.name);
  const fs::path dir = fs::path(folder) / fileSafe(c.name);
  fs::create_directories(dir);
  const ChannelImage& ref = *c.reference;
  const ChannelImage& res = *c.result;
  CompareResult comparison = c.comparison ? *c.comparison : compareChannelImages(res, ref, Tolerances{});

  writePng8(viewOf(ref), (dir / "reference.png").string());
  writePng8(viewOf(res), (dir / "result.png").string());
  const bool sameSize = ref.width == res.width && ref.height == res.height;
  std::ostringstream page;
  page << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << html(c.name) << "</title>\n" << kStyle
       << "</head><body>\n<p><a href=\"../index.html\">all failing cases</a></p>\n<h1>" << html(c.name) << "</h1>\n";
  if (!c.note.empty()) page << "<p>" << html(c.note) << "</p>\n";
  page << "<h2>Pictures</h2>\n" << picture("reference.png", c.referenceLabel) << picture("result.png", c.resultLabel);
  if (sameSize) {
    DifferenceMapOptions all;
    std::vector<std::string> common;
    ChannelImage refCommon, resCommon;  // the channels both have
    refCommon.width = resCommon.width = ref.width;
    refCommon.height = resCommon.height = ref.height;
    for (size_t k = 0; k < res.names.size(); ++k) {
      const int kr = ref.channelIndex(res.names[k]);
      if (kr < 0) continue;
      common.push_back(res.names[k]);
      resCommon.names.push_back(res.names[k]);
      resCommon.data.push_back(res.data[k]);
      resCommon.integer.push_back(res.isInteger(k));
      refCommon.names.push_back(res.names[k]);
      refCommon.data.push_back(ref.data[size_t(kr)]);
      refCommon.integer.push_back(ref.isInteger(size_t(kr)));
    }
    const std::vector<double> diffs = differenceMap(resCommon, refCommon, all);
    writePng8(differenceHeatMap(diffs, ref.width, ref.height), (dir / "difference.png").string());
    page << picture("difference.png", "difference (largest over every channel; black: equal)");
    // A row per channel that differs: its two views and its own heat map.
    for (const std::string& name : common) {
      DifferenceMapOptions one;
      one.channel = name;
      const std::vector<double> d = differenceMap(resCommon, refCommon, one);
      if (std::none_of(d.begin(), d.end(), [](double v) { return v != 0.0; })) continue;
      const std::string stem = fileSafe(name);
      writePng8(viewOf(refCommon, name), (dir / (stem + "-reference.png")).string());
      writePng8(viewOf(resCommon, name), (dir / (stem + "-result.png")).string());
      writePng8(differenceHeatMap(d, ref.width, ref.height), (dir / (stem + "-difference.png")).string());
      page << "<h3>channel " << html(name) << "</h3>\n"
           << picture(stem + "-reference.png", c.referenceLabel + ": " + name)
           << picture(stem + "-result.png", c.resultLabel + ": " + name)
           << picture(stem + "-difference.png", "difference: " + name);
    }
  }
  page << "<h2>Comparison</h2>\n<pre>" << html(formatReport(comparison)) << "</pre>\n</body></html>\n";
  writeText(dir / "index.html", page.str());
  rewriteIndex(fs::path(folder));
  return (dir / "index.html").string();
}

}  // namespace shadowref
