#include "trace/trace_compare.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "image/atomic_write.h"
#include "image/image_writer.h"
#include "trace/edge_mask.h"
#include "trace/trace_replay.h"

namespace shadowref::trace {

bool TargetComparison::passes() const {
  return std::all_of(buffers.begin(), buffers.end(), [](const BufferComparison& b) { return b.passes(); });
}

bool Comparison::passes() const {
  return std::all_of(targets.begin(), targets.end(), [](const TargetComparison& t) { return t.passes(); });
}

double fixedFunctionColorTolerance(const Trace& trace, uint32_t target) {
  double tolerance = 1.0;
  bool blendedInPass = false;
  for (const Command& c : trace.commands) {
    if (c.target != target) continue;
    if (const auto* d = std::get_if<DrawCommand>(&c.what)) {
      blendedInPass = blendedInPass || (d->state.blend.enabled && d->shader != kNoShader);
    } else if (std::holds_alternative<AccumCommand>(c.what)) {
      tolerance += 1.0 + (blendedInPass ? 1.0 : 0.0);
      blendedInPass = false;
    } else if (std::holds_alternative<EndPassCommand>(c.what)) {
      tolerance += blendedInPass ? 1.0 : 0.0;
      blendedInPass = false;
    }
  }
  return tolerance + (blendedInPass ? 1.0 : 0.0);
}

uint32_t fixedFunctionDepthTolerance(const Trace& trace, uint32_t target, uint32_t base) {
  double units = 0.0;
  bool offset = false;
  for (const Command& c : trace.commands)
    if (const auto* d = std::get_if<DrawCommand>(&c.what); d && c.target == target && d->state.polygonOffset.enabled) {
      units = std::max(units, std::fabs(d->state.polygonOffset.units));
      offset = true;
    }
  // Under polygon offset Mesa adds the offset to the interpolated float depth: one more float
  // rounding (half an ulp, up to half a code for depth in [0.5, 1)) beyond the 2 codes of
  // §Depth precision, so the two may be one code further apart.
  return base + uint32_t(std::min(std::ceil(units), 16777215.0)) + (offset ? 1u : 0u);
}

namespace {

EdgeMask edgesOf(const Trace& trace, uint32_t target) {
  const Target& t = trace.targets[target];
  EdgeMask mask(t.width, t.height);
  for (const Command& c : trace.commands) {
    const auto* d = std::get_if<DrawCommand>(&c.what);
    if (!d || c.target != target) continue;
    forEachTriangle(*d, [&](const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& e) {
      mask.addTriangle(a, b, e, d->state.viewport, d->state.depthClamp);
    });
  }
  return mask;
}

NearCutBound nearCutsOf(const Trace& trace, uint32_t target) {
  const Target& t = trace.targets[target];
  NearCutBound bound(t.width, t.height);
  for (const Command& c : trace.commands) {
    const auto* d = std::get_if<DrawCommand>(&c.what);
    if (!d || c.target != target) continue;
    forEachTriangle(*d, [&](const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& e) { bound.addTriangle(a, b, e, d->state); });
  }
  return bound;
}

std::string describeColor(const glm::vec4& c) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.2f,%.2f,%.2f,%.2f)/255", c.r * 255.0, c.g * 255.0, c.b * 255.0, c.a * 255.0);
  return text;
}

// Compares one buffer, pixel by pixel; diff(i) is the difference at pixel i in the buffer's
// units, text(i) a pixel's value for the first difference off the edges.
// explained(i, d): whether difference d off the edges at pixel i belongs to the near-plane class.
template <class Diff, class Text, class Explained>
BufferComparison compareOne(const std::string& buffer, size_t expectedSize, size_t actualSize, int width,
                            const EdgeMask& edges, double tolerance, bool exact, Diff diff, Text text,
                            Explained explained) {
  BufferComparison b;
  b.buffer = buffer;
  b.tolerance = exact ? 0.0 : tolerance;
  // A buffer the expected side never made (a shadow map's colour) is not compared.
  if (expectedSize == 0) return b;
  b.pixels = std::max(expectedSize, actualSize);
  if (expectedSize != actualSize) {
    b.comparable = false;
    return b;
  }
  b.differs.assign(b.pixels, 0);
  for (size_t i = 0; i < b.pixels; ++i) {
    const bool onEdge = edges.at(i);
    b.edgePixels += onEdge;
    const double d = diff(i);
    b.maxDifference = std::max(b.maxDifference, d);
    const bool differs = exact ? d != 0.0 : d > tolerance + 1e-3;
    if (!onEdge) b.maxDifferenceOffEdge = std::max(b.maxDifferenceOffEdge, d);
    if (!differs) continue;
    ++b.differing;
    if (!onEdge && !exact && explained(i, d)) {
      ++b.differingNearCut;
      b.differs[i] = 3;
      continue;
    }
    ++(onEdge ? b.differingOnEdge : b.differingOffEdge);
    b.differs[i] = onEdge ? 1 : 2;
    if (!onEdge && b.firstOffEdge.empty())
      b.firstOffEdge = "(" + std::to_string(i % size_t(width)) + "," + std::to_string(i / size_t(width)) + "): " + text(i);
  }
  // Exact: every differing pixel counts, on an edge or not (the bytes must be the same).
  if (exact) b.differingOffEdge = b.differing;
  return b;
}

}  // namespace

Comparison compareBuffers(const Trace& trace, const std::vector<const Buffers*>& expected,
                          const std::vector<Buffers>& actual, const std::vector<Tolerances>& tolerances) {
  Comparison out;
  for (uint32_t t = 0; t < trace.targets.size() && t < actual.size(); ++t) {
    const Buffers* e = expected[t];
    if (!e) continue;
    const Buffers& a = actual[t];
    const Tolerances& tol = tolerances[t];
    TargetComparison tc;
    tc.target = t;
    tc.width = e->width;
    tc.height = e->height;
    const EdgeMask edges = edgesOf(trace, t);
    const NearCutBound nearCuts = nearCutsOf(trace, t);
    const auto none = [](size_t, double) { return false; };
    tc.buffers.push_back(compareOne(
        "colour", e->color.size(), a.color.size(), e->width, edges, tol.colorTolerance255, tol.exact,
        [&](size_t i) {
          if (tol.exact) return e->color[i] == a.color[i] ? 0.0 : std::max(1e-9, double(glm::length(e->color[i] - a.color[i])) * 255.0);
          double d = 0;
          for (int c = 0; c < 4; ++c) d = std::max(d, std::fabs(double(e->color[i][c]) - double(a.color[i][c])) * 255.0);
          return d;
        },
        [&](size_t i) { return "expected " + describeColor(e->color[i]) + ", got " + describeColor(a.color[i]); }, none));
    tc.buffers.push_back(compareOne(
        "depth", e->depth.size(), a.depth.size(), e->width, edges, double(tol.depthTolerance), tol.exact,
        [&](size_t i) { return std::fabs(double(e->depth[i]) - double(a.depth[i])); },
        [&](size_t i) { return "expected code " + std::to_string(e->depth[i]) + ", got " + std::to_string(a.depth[i]); },
        [&](size_t i, double d) { return nearCuts.at(i) > 0.0 && d <= double(tol.depthTolerance) + nearCuts.at(i); }));
    tc.buffers.push_back(compareOne(
        "stencil", e->stencil.size(), a.stencil.size(), e->width, edges, 0.0, tol.exact,
        [&](size_t i) { return std::fabs(double(e->stencil[i]) - double(a.stencil[i])); },
        [&](size_t i) { return "expected " + std::to_string(e->stencil[i]) + ", got " + std::to_string(a.stencil[i]); }, none));
    if (tol.exact || !e->accum.empty() || !a.accum.empty())
      tc.buffers.push_back(compareOne(
          "accumulation", tol.exact ? e->accum.size() : 0, tol.exact ? a.accum.size() : 0, e->width, edges, 0.0, true,
          [&](size_t i) { return e->accum[i] == a.accum[i] ? 0.0 : std::max(1e-9, double(glm::length(e->accum[i] - a.accum[i]))); },
          [&](size_t) { return std::string("accumulation values differ"); }, none));
    out.targets.push_back(std::move(tc));
  }
  return out;
}

std::string reportText(const Comparison& c) {
  std::ostringstream o;
  o << "expected: " << c.expectedName << "\nactual:   " << c.actualName << "\n";
  for (const TargetComparison& t : c.targets) {
    o << "framebuffer " << t.target << (t.target == 0 ? " (the frame)" : " (a shadow map)") << ", " << t.width << "x"
      << t.height << ": " << (t.passes() ? "agrees" : "DIFFERS") << "\n";
    for (const BufferComparison& b : t.buffers) {
      if (b.pixels == 0) continue;
      char line[320];
      if (!b.comparable) {
        std::snprintf(line, sizeof line, "  %-12s present on one side only: DIFFERS\n", b.buffer.c_str());
        o << line;
        continue;
      }
      char nearCut[64] = "";
      if (b.differingNearCut) std::snprintf(nearCut, sizeof nearCut, " %zu on a near-plane cut,", b.differingNearCut);
      std::snprintf(line, sizeof line,
                    "  %-12s %zu pixels, %zu near an edge; differing %zu (%.3f %%): %zu on an edge,%s %zu elsewhere; "
                    "largest difference %.4g (off the edges %.4g, allowed %.4g): %s\n",
                    b.buffer.c_str(), b.pixels, b.edgePixels, b.differing, 100.0 * double(b.differing) / double(b.pixels),
                    b.differingOnEdge, nearCut, b.differingOffEdge, b.maxDifference, b.maxDifferenceOffEdge, b.tolerance,
                    b.passes() ? (b.differing ? (b.differingNearCut ? "explained (edges, near-plane cuts)" : "explained (edges only)") : "same")
                               : "DIFFERS");
      o << line;
      if (!b.firstOffEdge.empty()) o << "    first difference off the edges " << b.firstOffEdge << "\n";
    }
  }
  o << (c.passes() ? "result: agrees\n" : "result: DIFFERS\n");
  return o.str();
}

namespace {

Image8 pictureOf(const Buffers& b, const std::string& buffer) {
  Image8 img;
  img.width = b.width;
  img.height = b.height;
  img.channels = 3;
  img.pixels.assign(size_t(b.width) * size_t(b.height) * 3, 0);
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x) {
      const size_t i = size_t(y) * size_t(b.width) + size_t(x);
      uint8_t* p = &img.pixels[(size_t(b.height - 1 - y) * size_t(b.width) + size_t(x)) * 3];
      if (buffer == "colour" && i < b.color.size()) {
        for (int c = 0; c < 3; ++c) p[c] = uint8_t(std::lround(std::clamp(double(b.color[i][c]), 0.0, 1.0) * 255.0));
      } else if (buffer == "depth" && i < b.depth.size()) {
        const double z = b.depthFormat == DepthFormat::Unorm24 ? double(b.depth[i]) / 16777215.0
                                                                : double(std::bit_cast<float>(b.depth[i]));
        p[0] = p[1] = p[2] = uint8_t(std::lround(std::clamp(z, 0.0, 1.0) * 255.0));
      } else if (buffer == "stencil" && i < b.stencil.size()) {
        const int s = b.stencil[i];
        p[0] = p[1] = p[2] = uint8_t(s == 0 ? 0 : std::min(255, 64 + 32 * s));
      }
    }
  return img;
}

Image8 differencePicture(const BufferComparison& b, int width, int height) {
  Image8 img;
  img.width = width;
  img.height = height;
  img.channels = 3;
  img.pixels.assign(size_t(width) * size_t(height) * 3, 24);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      if (i >= b.differs.size() || b.differs[i] == 0) continue;
      uint8_t* p = &img.pixels[(size_t(height - 1 - y) * size_t(width) + size_t(x)) * 3];
      p[0] = 255;
      p[1] = b.differs[i] == 1 ? 220 : b.differs[i] == 3 ? 140 : 0;
      p[2] = 0;
    }
  return img;
}

std::string escape(const std::string& s) {
  std::string o;
  for (char ch : s) {
    if (ch == '<') o += "&lt;";
    else if (ch == '>') o += "&gt;";
    else if (ch == '&') o += "&amp;";
    else o += ch;
  }
  return o;
}

}  // namespace

void writeReportHtml(const Comparison& c, const std::vector<const Buffers*>& expected, const std::vector<Buffers>& actual,
                     const std::string& folder) {
  std::filesystem::create_directories(folder);
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>shadowref replay</title>\n"
       "<style>body{font-family:sans-serif}img{image-rendering:pixelated;max-width:32em;border:1px solid #888}"
       "td{vertical-align:top;padding:4px}.bad{color:#b00;font-weight:bold}</style></head><body>\n"
    << "<h1>shadowref replay: " << (c.passes() ? "agrees" : "<span class=bad>DIFFERS</span>") << "</h1>\n"
    << "<p>expected: " << escape(c.expectedName) << "<br>actual: " << escape(c.actualName) << "</p>\n"
    << "<p>Difference pictures: yellow = differs on a triangle edge (fill-rule tie, clipping), orange = depth "
       "differs on a triangle the near plane cuts, within the bound of a float clipper, red = differs elsewhere; row 0 of the buffers is the bottom of the picture.</p>\n<pre>"
    << escape(reportText(c)) << "</pre>\n";
  for (const TargetComparison& t : c.targets) {
    h << "<h2>framebuffer " << t.target << "</h2>\n<table><tr><th>buffer</th><th>expected</th><th>actual</th><th>difference</th></tr>\n";
    for (const BufferComparison& b : t.buffers) {
      if (b.pixels == 0 || !b.comparable || b.buffer == "accumulation") continue;
      const std::string stem = "fb" + std::to_string(t.target) + "-" + b.buffer;
      writePng8(pictureOf(*expected[t.target], b.buffer), folder + "/" + stem + "-expected.png");
      writePng8(pictureOf(actual[t.target], b.buffer), folder + "/" + stem + "-actual.png");
      writePng8(differencePicture(b, t.width, t.height), folder + "/" + stem + "-difference.png");
      h << "<tr><td>" << b.buffer << "<br>" << (b.passes() ? "ok" : "<span class=bad>DIFFERS</span>") << "<br>"
        << b.differingOnEdge << " on edges<br>" << b.differingNearCut << " on near-plane cuts<br>" << b.differingOffEdge
        << " elsewhere</td>";
      for (const char* kind : {"expected", "actual", "difference"})
        h << "<td><img src=\"" << stem << "-" << kind << ".png\" alt=\"" << kind << "\"></td>";
      h << "</tr>\n";
    }
    h << "</table>\n";
  }
  h << "</body></html>\n";
  const std::string html = h.str();
  writeFileAtomically(folder + "/index.html",
                      [&](const TempFile& temp) { writeAllAt(temp.fd, html.data(), html.size(), 0); });
}

}  // namespace shadowref::trace
