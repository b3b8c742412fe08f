// shadowref as a library: load a scene, render it with a shadow method, read back every buffer.
// This header is the whole public interface (C++20, no other shadowref header needed); link with
// shadowref::shadowref (CMake: find_package(shadowref)) or `pkg-config --libs shadowref`.
//
//   shadowref::api::Scene scene = shadowref::api::Scene::fromFile("scenes/room.yaml", {"image.width=400"});
//   shadowref::api::RenderOptions options;
//   options.method = "zfail";
//   shadowref::api::Frame frame = shadowref::api::render(scene, options);
//   uint8_t count = frame.stencil[frame.index(400, 220)];  // row 0 is the bottom
//
// The same scene and options give the same bytes in every buffer, for any thread count and either
// pipeline. Bad input (a scene file, an override, a method name) throws shadowref::api::Error
// whose what() is "file:line:col: message", as the command line prints it.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace shadowref::api {

// Bad input: the scene, an override ("<command line>:N:col" for the N-th) or a method name.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "0.1.0".
std::string version();

// The shadow methods this build renders with: "none", "zpass", "zfail", "auto", ...
std::vector<std::string> methods();

// A loaded scene (docs/scene-format.md), with the -D style overrides applied ("camera.near=0.001",
// "shadow.method=zpass", "image.width=400"). Movable, not copyable.
class Scene {
 public:
  static Scene fromFile(const std::string& path, const std::vector<std::string>& overrides = {});
  // `name` is the file name messages give; mesh paths are relative to the working directory.
  static Scene fromString(const std::string& yaml, const std::string& name = "<string>",
                          const std::vector<std::string>& overrides = {});
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;
  ~Scene();

  int width() const;
  int height() const;
  std::string method() const;  // the scene's shadow.method

  // Animation (docs/scene-format.md, "Animation"): whether the scene has an `animation:` section,
  // its frames per second (24 without one), and the still scene at `seconds` — frame n is
  // at(n / fps()). The still of a scene without animation is a copy. Throws Error when that frame
  // fails the scene's checks ("file:line:col: ... (the animation at t = 1.5 s)").
  bool animated() const;
  double fps() const;
  Scene at(double seconds) const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  explicit Scene(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

enum class Pipeline {
  Fast,       // the threaded executor
  Reference,  // the readable GL 2.1 pipeline, one thread: the same bytes
};

struct RenderOptions {
  std::string method;                 // empty: the scene's shadow.method
  Pipeline pipeline = Pipeline::Fast;
  int threads = 0;                    // 0: one per CPU this process may run on (its affinity mask)
  bool stencilPerLight = false;       // keep each light's stencil counts after its volume pass
  int historyX = -1, historyY = -1;   // >= 0: record the pixel history of (x, y) (reference pipeline)
  bool visibility = false;            // each light's shadow mask, Frame::visibility
  bool shadowMaps = false;            // the shadow maps' depths, Frame::shadowMaps (shadow-map methods)
};

// One shadow map of a shadow-map method: the depth texture a light's pass wrote, width * height
// values in [0, 1] with row 0 at the bottom. "L0", or "L0.face3" for a point light's cube face.
struct ShadowMap {
  std::string name;
  int width = 0, height = 0;
  std::vector<float> depth;
};

struct FrameData;  // the renderer's own framebuffer, kept for writeImage

// One fragment that reached the watched pixel, in drawing order.
struct FragmentRecord {
  uint64_t draw = 0;
  std::string what;          // "volume side, object 'room/table/top'", "lit pass, object ...", ...
  bool front = true;         // the facing of its triangle
  double depth = 0.0;        // its window depth
  double storedDepth = 0.0;  // the depth buffer's value before it
  bool stencilPassed = true, depthPassed = true;
  uint8_t stencilBefore = 0, stencilAfter = 0;
  float colorBefore[4] = {}, colorAfter[4] = {};
};

// The buffers of a rendered frame, width * height values each, index y * width + x with row 0 at
// the BOTTOM (as glReadPixels returns them). A buffer the method does not use is empty.
struct Frame {
  int width = 0, height = 0;
  int threads = 0;                 // the threads it was rendered on
  std::vector<float> color;        // R, G, B, A per pixel (4 values a pixel)
  std::vector<float> depth;        // window depth in [0, 1]
  std::vector<uint8_t> stencil;    // the stencil buffer at the end of the frame (the last light's counts)
  std::vector<float> accumulation; // R, G, B, A per pixel, for methods that accumulate (soft shadows)
  // With RenderOptions::stencilPerLight: each light's counts after its volume pass, and its name.
  std::vector<std::vector<uint8_t>> stencilPerLight;
  std::vector<std::string> lightNames;
  std::vector<FragmentRecord> history;  // with RenderOptions::historyX/Y
  // The distance from the camera along its view direction, from the depth buffer through the
  // projection the frame was drawn with; +infinity where the depth is 1 under the infinite
  // projection (the background of a shadow-volume frame).
  std::vector<double> eyeDepth;
  // With RenderOptions::visibility: per light of the scene (in its order, a soft light once) how
  // much of it reaches the surface each pixel shows: 1 lit, 0 in shadow, fractions with PCF and
  // soft lights; the background is 1. The lights' names are in visibilityNames.
  std::vector<std::vector<float>> visibility;
  std::vector<std::string> visibilityNames;
  std::vector<ShadowMap> shadowMaps;    // with RenderOptions::shadowMaps
  // The pipeline's counters (`render --stats`): "draw_calls", "triangles_in", "fragments", ...
  std::vector<std::pair<std::string, uint64_t>> statistics;
  std::vector<std::pair<std::string, double>> passMilliseconds;  // each pass's time, in order
  std::vector<std::string> warnings;    // what `render` prints on stderr about the scene
  std::shared_ptr<const FrameData> data;


  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
};

// Renders one frame. Throws Error for an unknown method, a pixel outside the image, or per-light
// buffers over their limits (stencilPerLight: 2^27 counts, visibility: 2^26 values, as the CLI).
Frame render(const Scene& scene, const RenderOptions& options = {});

// Writes the frame as `render -o` does, chosen by the extension: ".png" (8-bit RGB) or ".exr"
// (R, G, B, A, Z, stencil and, with several lights and RenderOptions::stencilPerLight, one
// "stencil.<light>" channel each). Atomic: the file is complete or absent. Throws Error for
// another extension and std::runtime_error when the file cannot be written.
void writeImage(const Frame& frame, const std::string& path);

}  // namespace shadowref::api
