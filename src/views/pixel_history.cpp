#include "views/pixel_history.h"

#include <cctype>
#include <iomanip>
#include <sstream>

#include "shadow/draw_tag.h"
#include "views/stencil_counts_view.h"

namespace shadowref::views {

std::string passLight(const std::string& pass) {
  const size_t at = pass.rfind("-L");
  if (at == std::string::npos || at + 2 >= pass.size()) return "";
  for (size_t i = at + 2; i < pass.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(pass[i]))) return "";
  return pass.substr(at + 1);
}

void PixelHistory::attach(FrameOptions& options) {
  options.watchX = x_;
  options.watchY = y_;
  options.observer = this;
  auto before = std::move(options.onPass);
  options.onPass = [this, before](const std::string& pass, const Framebuffer& fb) {
    onPass(pass, fb);
    if (before) before(pass, fb);
  };
  options.onShadowLookups = [this](std::span<const LightShadow* const> shadows) { onShadowLookups(shadows); };
}

HistoryPass& PixelHistory::current() {
  if (!open_) {
    passes_.emplace_back();
    open_ = true;
  }
  return passes_.back();
}

void PixelHistory::onFragment(const FragmentEvent& event) {
  HistoryStep step;
  step.fragment = event;
  // The camera pass of a shadow-map method shades with the lookups of onShadowLookups' lights:
  // traced from the world position the shader read (the fragment's first three varyings).
  if (event.varyingCount >= 3 && !shadows_.empty() && drawKindOf(event.drawTag) == DrawKind::Lit) {
    const glm::dvec3 p(event.varyings[0], event.varyings[1], event.varyings[2]);
    auto vertex = [&](size_t i) {
      const std::array<double, 3>& v = event.triangleVaryings[i];
      return glm::dvec3(v[0], v[1], v[2]);
    };
    const glm::dvec4 plane = trianglePlane(vertex(0), vertex(1), vertex(2));
    for (size_t l = 0; l < shadows_.size(); ++l)
      step.lookups.push_back({l, shadows_[l]->light.name, traceShadowLookup(*shadows_[l], p, plane)});
  }
  current().steps.push_back(std::move(step));
}

void PixelHistory::onClear(const ClearEvent& event) {
  HistoryStep step;
  step.kind = HistoryStep::Kind::Clear;
  step.clear = event;
  current().steps.push_back(std::move(step));
}

void PixelHistory::onPass(const std::string& pass, const Framebuffer& fb) {
  HistoryPass& p = current();
  p.name = pass;
  p.light = passLight(pass);
  if (fb.hasStencil() && x_ < fb.width() && y_ < fb.height()) p.stencilAfter = fb.stencil()[fb.index(x_, y_)];
  open_ = false;
  shadows_.clear();  // they live for their pass only
}

void PixelHistory::onShadowLookups(std::span<const LightShadow* const> shadows) {
  shadows_.assign(shadows.begin(), shadows.end());
}

size_t PixelHistory::fragmentCount() const {
  size_t n = 0;
  for (const HistoryPass& p : passes_)
    for (const HistoryStep& s : p.steps) n += s.kind == HistoryStep::Kind::Fragment;
  return n;
}

namespace {

std::string lightLabel(const std::string& light, const std::vector<std::string>& names) {
  if (light.empty()) return "";
  const size_t i = std::stoul(light.substr(1));
  return "light " + light + (i < names.size() ? " '" + names[i] + "'" : "");
}

// Floats as stored: 9 significant digits tell any two floats apart.
std::string exact(double v) {
  std::ostringstream out;
  out << std::setprecision(9) << v;
  return out.str();
}

void printLookup(std::ostringstream& out, const HistoryLookup& l) {
  const ShadowLookupTrace& t = l.trace;
  out << "      lookup light L" << l.light << " '" << l.lightName << "'";
  if (t.face >= 0) out << " cube face " << t.face;
  out << ": strq (" << t.strq.x << ", " << t.strq.y << ", " << t.strq.z << ", " << t.strq.w << ")  s,t,r (" << t.s
      << ", " << t.t << ", " << exact(t.r) << ")";
  if (t.behindLight) {
    out << "  behind the light: lit, 1\n";
    return;
  }
  if (t.outsideMap) {
    out << "  outside the map fitted to the casters: lit, 1\n";
    return;
  }
  out << "  texel (" << t.texelX << ", " << t.texelY << ") of " << t.mapWidth << "x" << t.mapHeight << "  stored D "
      << exact(t.stored) << "  compared r " << exact(t.compared) << (t.passed ? " <= D: lit" : " > D: shadowed");
  if (t.pcf > 1) out << "  (nearest texel; " << t.pcf << "x" << t.pcf << " PCF mean)";
  out << "  result " << t.result << '\n';
}

}  // namespace

std::string PixelHistory::text(const std::vector<Instance>& instances, const std::vector<std::string>& lightNames,
                               bool signedCounts) const {
  std::ostringstream out;
  const size_t fragments = fragmentCount();
  out << "pixel " << x_ << "," << y_ << " (row 0 is the bottom): " << fragments
      << (fragments == 1 ? " fragment" : " fragments") << "; stencil " << (signedCounts ? "signed" : "unsigned") << "\n";
  auto count = [&](uint8_t v) { return stencilCountOf(v, signedCounts); };
  for (const HistoryPass& pass : passes_) {
    out << "pass " << (pass.name.empty() ? std::string("(unfinished)") : pass.name);
    if (!pass.light.empty()) out << " (" << lightLabel(pass.light, lightNames) << ")";
    if (pass.steps.empty()) out << ": nothing reached the pixel";
    out << '\n';
    for (const HistoryStep& step : pass.steps) {
      if (step.kind == HistoryStep::Kind::Clear) {
        const ClearEvent& c = step.clear;
        out << "  clear";
        if (c.stencilAfter) out << "  stencil " << count(*c.stencilBefore) << " -> " << count(*c.stencilAfter);
        if (c.depthAfter) out << "  depth " << *c.depthBefore << " -> " << *c.depthAfter;
        if (c.color) out << "  colour";
        out << '\n';
        continue;
      }
      const FragmentEvent& e = step.fragment;
      out << "  draw " << e.drawIndex << "  ";
      if (!pass.light.empty()) out << "light " << pass.light << "  ";
      out << describeDrawTag(e.drawTag, instances) << "  " << (e.facing == FrontFacing ? "front" : "back")
          << "  z=" << e.depth << " (stored " << e.storedDepth << ")  stencil test "
          << (e.stencilPassed ? "pass" : "FAIL") << "  depth test "
          << (!e.stencilPassed ? "-" : e.depthPassed ? "pass" : "FAIL") << "  stencil " << count(e.stencilBefore)
          << " -> " << count(e.stencilAfter);
      if (e.colorAfter != e.colorBefore)
        out << "  colour (" << e.colorAfter.r << ", " << e.colorAfter.g << ", " << e.colorAfter.b << ")";
      out << '\n';
      for (const HistoryLookup& l : step.lookups) printLookup(out, l);
    }
    if (pass.stencilAfter && !pass.light.empty() && pass.name.find("stencil") != std::string::npos)
      out << "  stencil after the pass: " << count(*pass.stencilAfter) << (*pass.stencilAfter == 0 ? " (lit)" : " (in shadow)")
          << '\n';
  }
  return out.str();
}

}  // namespace shadowref::views
