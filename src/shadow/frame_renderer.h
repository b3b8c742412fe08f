// Renders one frame of a scene with its shadow technique (technique_registry.h): the passes of the
// stencil shadow volumes ([Kuhn 2016, §3.1, §4.2]) or of shadow mapping ([Hempe 2004, §3.1, §5.1])
// in order.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gl/depth_compare_sampler.h"
#include "gl/fragment_observer.h"
#include "gl/framebuffer.h"
#include "gl/pipeline.h"
#include "gl/raster_stats.h"
#include "scene/scene.h"

namespace shadowref {

struct ShadowTechnique;
struct LightShadow;

// Teaching views of the volumes drawn over the finished frame.
enum class VolumeViewMode : uint8_t {
  None,
  FrontBack,  // front faces red, back faces blue ([SV slides])
  Overlay,    // translucent red volumes over the scene ([DSS article], render mode 2)
};

struct FrameOptions {
  // A technique's name, overriding the scene's shadow.method; empty: the scene's.
  std::string method;
  // The techniques the name is looked up among; empty: the built-in ones. A test adds its own.
  std::span<const ShadowTechnique* const> techniques;
  // The pipeline the passes draw through (gl/pipeline.h); both give the same bytes.
  PipelineKind pipeline = PipelineKind::Fast;
  // Rasterizer threads (0: all cores). Every buffer comes out byte-identical for any count.
  int threads = 1;
  // Where the frame's pipeline comes from: frames rendered one after another from one maker share
  // its threads (gl/pipeline.h). When set, its kind and threads are the frame's, in place of
  // `pipeline` and `threads`. nullptr: a pipeline of the frame's own.
  const PipelineMaker* pipelines = nullptr;
  // Pixel history: every fragment at (x, y) is reported to the observer.
  int watchX = -1, watchY = -1;
  FragmentObserver* observer = nullptr;
  // Called after every pass with its name ("01-ambient", ...) and the framebuffer as it stands.
  std::function<void(const std::string& pass, const Framebuffer&)> onPass;
  // Keep a copy of the stencil buffer after each light's volume pass (--dump stencil).
  bool keepStencil = false;
  // Keep the shadow maps of the first frame (--dump shadowmap).
  bool keepShadowMaps = false;
  // Compute each scene light's visibility (shadow/visibility.h) into FrameResult::visibility.
  bool keepVisibility = false;
  VolumeViewMode volumeView = VolumeViewMode::None;
  // VolumeViewMode::FrontBack: the colours of each scene light's front and back faces (a soft
  // light's samples share their light's), in scene.lights' order; a light beyond the list, or an
  // empty list, gets red and blue ([SV slides]).
  std::vector<std::array<glm::dvec3, 2>> volumeColours;
  // Shadow-map techniques: called before each camera pass with the lights' shadows it looks up
  // (one per light of that accumulation frame, in scene.lights' order); they stay valid until the
  // pass has ended. The pixel history traces the watched pixel's lookups with them.
  std::function<void(std::span<const LightShadow* const>)> onShadowLookups;
};

// What a shadow map's teaching view draws over it (views::drawShadowMapOutline): the camera's
// frustum, and for TSM's unwarped view the trapezoid.
struct ShadowMapOutline {
  glm::dmat4 worldToClip{1.0};             // world -> the map's clip space (x, y, w as the map was drawn)
  std::array<glm::dvec3, 8> frustum{};     // the camera frustum's corners (world; trapezoid.h's order,
                                           // the far plane fitted to the scene as TSM fits it)
  std::vector<glm::dvec2> trapezoid;       // TSM's unwarped view: the trapezoid's corners (map x-y,
                                           // [-1, 1]^2 the whole map); otherwise empty
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
  // With FrameOptions::keepStencil: the stencil counts after each light's volume pass, and the
  // light's name ("L0", "L1", ... in the order of the expanded light list).
  std::vector<PixelVector<uint8_t>> stencilPerLight;
  std::vector<std::string> stencilLightNames;
  // With FrameOptions::keepShadowMaps: each light's depth map(s), named "L0" or "L0.face3".
  std::vector<DepthTexture> shadowMaps;
  std::vector<std::string> shadowMapNames;
  std::vector<ShadowMapOutline> shadowMapOutlines;  // one per map
  // What the user should know about the scene, once each (`render` prints them on stderr): e.g.
  // a shadow-casting mesh the shadow volumes cannot take as it is written (volume_casting.h).
  std::vector<std::string> warnings;
  // With FrameOptions::keepVisibility: per light of the scene (scene.lights' order, soft lights
  // not expanded) the visibility of every pixel in framebuffer order (shadow/visibility.h).
  std::vector<std::vector<float>> visibility;
};

// "01-ambient", "02-stencil-L0", ...: the next pass name of a frame, numbered in order so that
// the --dump passes files sort as the passes ran.
std::string numberedPass(int& counter, const std::string& what);

// Renders with the technique options.method or else scene.shadow.method names. An unknown name is
// a SceneError at the scene's shadow.method (or std::invalid_argument for options.method), each
// listing the names there are; std::runtime_error for a
// technique or pipeline this build cannot render with, or asked for visibility it does not give.
FrameResult renderFrame(const Scene& scene, const FrameOptions& options = {});

}  // namespace shadowref
