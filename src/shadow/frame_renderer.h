// Renders one frame of a scene with its shadow method: the passes of SPEC.md §3 / §4 in order.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "raster/fragment_observer.h"
#include "raster/framebuffer.h"
#include "raster/raster_stats.h"
#include "scene/scene.h"

namespace shadowref {

struct FrameOptions {
  std::optional<ShadowMethod> method;  // overrides the scene's shadow.method
  // Pixel history: every fragment at (x, y) is reported to the observer.
  int watchX = -1, watchY = -1;
  FragmentObserver* observer = nullptr;
  // Called after every pass with its name ("01-ambient", ...) and the framebuffer as it stands.
  std::function<void(const std::string& pass, const Framebuffer&)> onPass;
};

struct PassTiming {
  std::string pass;
  double milliseconds = 0.0;
};

struct FrameResult {
  Framebuffer framebuffer;
  RasterStats stats;
  std::vector<PassTiming> timings;
  std::vector<std::string> notes;  // per-light statistics lines for --stats
};

// Throws std::runtime_error for a method this build cannot render.
FrameResult renderFrame(const Scene& scene, const FrameOptions& options = {});

}  // namespace shadowref
