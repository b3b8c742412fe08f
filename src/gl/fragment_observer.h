// Pixel history: every fragment that reaches one watched pixel is reported with what each test
// decided and what the buffers held before and after. It answers "why is this pixel in shadow?".
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include <glm/glm.hpp>

#include "gl/render_state.h"

namespace shadowref {

struct FragmentEvent {
  int x = 0, y = 0;
  uint64_t drawIndex = 0;   // counts draw calls of this renderer
  uint32_t drawTag = 0;     // what the caller said the draw is (object, volume part, pass)
  Facing facing = FrontFacing;
  double depth = 0.0;       // fragment depth, in the buffer's format
  double storedDepth = 0.0; // what the depth buffer held before
  bool scissorPassed = true, stencilPassed = true, depthPassed = true;
  uint8_t stencilBefore = 0, stencilAfter = 0;
  glm::vec4 colorBefore{0.0f}, colorAfter{0.0f};
  // The shader's first varyings, interpolated as the shader read them, when the fragment was shaded
  // and its shader reads at least three: the scene's shaders keep the world position there
  // (gl/lighting.h, kVaryingPosition), which a shadow-map lookup starts from.
  int varyingCount = 0;
  std::array<double, 3> varyings{};
  // The same three varyings at the triangle's vertices (FragmentInput::triangle): the receiver's
  // plane, which a PCF lookup with receiver-plane depth bias follows.
  std::array<std::array<double, 3>, 3> triangleVaryings{};
};

// A glClear that covered the watched pixel: what each buffer it clears held there before and after
// (only the buffers the request names, each nullopt otherwise).
struct ClearEvent {
  int x = 0, y = 0;
  std::optional<uint8_t> stencilBefore, stencilAfter;
  std::optional<double> depthBefore, depthAfter;
  bool color = false;
};

class FragmentObserver {
 public:
  virtual ~FragmentObserver() = default;
  virtual void onFragment(const FragmentEvent& event) = 0;
  // A clear that reached the watched pixel; observers that only follow fragments ignore it.
  virtual void onClear(const ClearEvent& event) {}
};

// The watched pixel of a draw: its fragments are reported to `observer` (nullptr: none), with the
// draw's index among the pipeline's draws and the caller's tag.
struct PixelWatch {
  int x = -1, y = -1;
  FragmentObserver* observer = nullptr;
  uint64_t drawIndex = 0;
  uint32_t drawTag = 0;
  // The buffers that existed when the draw was made: the event reports what those held before and
  // after. A buffer that a later draw makes did not exist for this one, even where a pipeline
  // renders the draws of a pass together.
  bool hasColor = false, hasDepth = false, hasStencil = false;
};

}  // namespace shadowref
