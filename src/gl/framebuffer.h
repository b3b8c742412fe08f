// The four buffers: colour, depth, stencil, accumulation. Each exists only once a
// pass asks for it (Framebuffer::ensure*), so a scene that never uses stencil never allocates it.
// Pixel (x, y) is at index y * width + x with row 0 at the bottom, as glReadPixels returns it.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "memory/construct_later.h"
#include "memory/pixel_memory.h"

namespace shadowref {

enum class DepthFormat : uint8_t {
  Float32,  // GL_DEPTH_COMPONENT32F: the default, the reference
  Unorm24,  // GL_DEPTH_COMPONENT24: what most GL implementations (and Mesa) offer
};

// Depth values are kept as 32-bit codes whose unsigned order is the depth order: for Float32 the
// IEEE bits of a non-negative float (positive floats sort like their bit patterns), for Unorm24
// round(z * (2^24 - 1)). The depth test therefore compares integers, exactly as the buffer holds
// them, after the fragment depth has been converted to the buffer's format ([GL 2.1, §4.1.5]).
struct DepthCodec {
  DepthFormat format = DepthFormat::Float32;
  // z is clamped to [0, 1] first. Not with std::clamp: it returns -0.0 (and NaN) unchanged, and
  // the bits of -0.0f (0x80000000) would sort above every positive depth. Negative zero,
  // negatives and NaN all become +0.0. Inline: it runs once per fragment.
  uint32_t encode(double z) const {
    z = z > 0.0 ? std::min(z, 1.0) : 0.0;
    if (format == DepthFormat::Unorm24) return uint32_t(std::nearbyint(z * 16777215.0));
    return std::bit_cast<uint32_t>(float(z));
  }
  double decode(uint32_t code) const {
    if (format == DepthFormat::Unorm24) return double(code) / 16777215.0;
    return double(std::bit_cast<float>(code));
  }
  // The minimum resolvable difference r of the polygon offset formula at depth z
  // ([GL 2.1, §3.5.5]).
  double resolvableDifference(double zMax) const;
};

// A buffer's pixels: made unwritten (ConstructLaterAllocator); a large buffer (a frame's colour,
// depth and accumulation buffers, a shadow map) in 2 MB pages kept from frame to frame
// (PixelAllocator, pixel_memory.h).
template <class T>
using PixelVector = std::vector<T, ConstructLaterAllocator<T, PixelAllocator<T>>>;

class Framebuffer {
 public:
  Framebuffer(int width, int height, DepthFormat depthFormat = DepthFormat::Float32);

  int width() const { return width_; }
  int height() const { return height_; }
  const DepthCodec& depthCodec() const { return depthCodec_; }

  void ensureColor();
  void ensureDepth();
  void ensureStencil();
  void ensureAccum();
  bool hasColor() const { return !color_.empty(); }
  bool hasDepth() const { return !depth_.empty(); }
  bool hasStencil() const { return !stencil_.empty(); }
  bool hasAccum() const { return !accum_.empty(); }

  size_t pixelCount() const { return size_t(width_) * size_t(height_); }
  size_t index(int x, int y) const { return size_t(y) * size_t(width_) + size_t(x); }

  // Colour is RGBA float, clamped to [0, 1] on every write like a fixed-point GL colour buffer.
  PixelVector<glm::vec4>& color() { return color_; }
  const PixelVector<glm::vec4>& color() const { return color_; }
  PixelVector<uint32_t>& depthCodes() { return depth_; }
  const PixelVector<uint32_t>& depthCodes() const { return depth_; }
  PixelVector<uint8_t>& stencil() { return stencil_; }
  const PixelVector<uint8_t>& stencil() const { return stencil_; }
  // Accumulation is RGBA float and unclamped (GL keeps signed values in [-1, 1]).
  PixelVector<glm::vec4>& accum() { return accum_; }
  const PixelVector<glm::vec4>& accum() const { return accum_; }

  glm::vec4 colorAt(int x, int y) const { return color_[index(x, y)]; }
  double depthAt(int x, int y) const { return depthCodec_.decode(depth_[index(x, y)]); }
  uint8_t stencilAt(int x, int y) const { return stencil_[index(x, y)]; }
  glm::vec4 accumAt(int x, int y) const { return accum_[index(x, y)]; }

 private:
  int width_, height_;
  DepthCodec depthCodec_;
  PixelVector<glm::vec4> color_;
  PixelVector<uint32_t> depth_;
  PixelVector<uint8_t> stencil_;
  PixelVector<glm::vec4> accum_;
};

}  // namespace shadowref
