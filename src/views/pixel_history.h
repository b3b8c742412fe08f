// Pixel history: the answer to "why is this pixel dark?". Every fragment that reached one pixel,
// in order, grouped by the pass it belongs to and so by its light ("02-stencil-L0": light L0's
// volumes), every clear of the pixel's buffers (the stencil clear that starts each light's
// volume pass), and for a shadow-map method each light's lookup of the visible fragment: its
// light-space coordinates, texel, stored depth, compared r and result
// ([Hempe 2004, §3.1, §5.1.4]).
//
// It is fed by the frame renderer: it is the FragmentObserver, and FrameOptions::onPass and
// onShadowLookups call onPass and onShadowLookups (attach() sets all three).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gl/fragment_observer.h"
#include "gl/framebuffer.h"
#include "scene/scene.h"
#include "shadow/frame_renderer.h"
#include "shadow/shadow_lookup_trace.h"

namespace shadowref::views {

struct HistoryLookup {
  size_t light = 0;        // the scene light whose map was looked up
  std::string lightName;   // its name
  ShadowLookupTrace trace;
};

struct HistoryStep {
  enum class Kind { Fragment, Clear } kind = Kind::Fragment;
  FragmentEvent fragment;            // Kind::Fragment
  ClearEvent clear;                  // Kind::Clear
  std::vector<HistoryLookup> lookups;  // a shaded fragment of a shadow-map camera pass
};

struct HistoryPass {
  std::string name;   // "02-stencil-L0"
  std::string light;  // "L0" when the pass belongs to one light, else ""
  std::vector<HistoryStep> steps;
  std::optional<uint8_t> stencilAfter;  // the pixel's stencil when the pass had ended, if any
};

class PixelHistory final : public FragmentObserver {
 public:
  PixelHistory(int x, int y) : x_(x), y_(y) {}

  // Sets options' watched pixel, observer, onPass and onShadowLookups to this history's (an
  // onPass already there is still called, after).
  void attach(FrameOptions& options);

  void onFragment(const FragmentEvent& event) override;
  void onClear(const ClearEvent& event) override;
  void onPass(const std::string& pass, const Framebuffer& fb);
  void onShadowLookups(std::span<const LightShadow* const> shadows);

  int x() const { return x_; }
  int y() const { return y_; }
  // The passes in order; a pass that left no step at the pixel is listed with none.
  const std::vector<HistoryPass>& passes() const { return passes_; }
  size_t fragmentCount() const;

  // The history as text, one line a step, each pass under a heading naming its light (L<i> of the
  // frame's lights, soft lights expanded: lightNames[i]); stencil values read unsigned (0..255) as
  // --dump-region prints them by default, or signed.
  std::string text(const std::vector<Instance>& instances, const std::vector<std::string>& lightNames,
                   bool signedCounts = false) const;

 private:
  HistoryPass& current();
  int x_, y_;
  std::vector<HistoryPass> passes_;
  bool open_ = false;  // passes_.back() is the pass being drawn
  std::vector<const LightShadow*> shadows_;
};

// "L3" from a pass name ending "-L3", or "".
std::string passLight(const std::string& pass);

}  // namespace shadowref::views
