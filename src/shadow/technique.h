// A shadow technique: what the scene's shadow.method and --method name. Each technique is one
// constant of this type, defined in the file of its algorithm and listed once in the registry
// (technique_registry.cpp); the frame renderer, the command line's --help and checks, and
// `shadowref info` know the techniques only through it (docs/shadow-techniques.md).
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "gl/pipeline.h"
#include "scene/scene.h"
#include "shadow/frame_renderer.h"

namespace shadowref {

// A key of the scene's shadow section a technique reads, with its documented values (the loader
// checks them: src/scene/scene_sections.cpp, docs/scene-format.md).
struct TechniqueSetting {
  std::string_view key;    // "map_size": shadow.map_size in a file, -D shadow.map_size=...
  std::string_view range;  // "8 to 8192"
};

struct ShadowTechnique {
  std::string_view name;     // the word in the scene file and after --method: lower case, unique
  std::string_view summary;  // one line for people: what it draws, after which source
  // The shadow.* keys it reads besides `method`: the others change nothing in its frames.
  std::span<const TechniqueSetting> settings;
  // Draws one stencil count per light (FrameResult::stencilPerLight with keepStencil, the passes
  // named "NN-stencil-L<i>"): --dump stencil and the EXR's stencil channels have something to show.
  bool countsInStencil = false;
  // Draws shadow volumes (with the camera's infinite projection P_inf, [Kuhn 2016, §3.3]): --view
  // volumes and volumes-overlay have something to draw.
  bool drawsVolumes = false;
  // Renders a depth map per light (FrameResult::shadowMaps with keepShadowMaps, the lookups of
  // FrameOptions::onShadowLookups): --dump shadowmap has something to show.
  bool rendersShadowMaps = false;
  // The whole frame: clears and draws every pass into the pipeline's framebuffer, reports the passes
  // through options.onPass and adds timings and notes to result. renderFrame made the pipeline
  // for result.framebuffer and adds its statistics afterwards.
  void (*render)(const Scene& scene, const FrameOptions& options, FrameResult& result, Pipeline& pipeline) = nullptr;
  // The values of `settings` for `shadowref info`, as a phrase ("silhouette kuhn, two-sided
  // stencil, ..."); empty when it reads none.
  std::string (*describe)(const ShadowSettings& settings) = nullptr;
};

}  // namespace shadowref
