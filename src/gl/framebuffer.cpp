#include "gl/framebuffer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace shadowref {

namespace {
constexpr double kUnorm24Max = 16777215.0;  // 2^24 - 1
}


double DepthCodec::resolvableDifference(double zMax) const {
  if (format == DepthFormat::Unorm24) return 1.0 / kUnorm24Max;
  // Float depth: one unit in the last place of the largest depth of the primitive
  // (ARB_depth_buffer_float: r = 2^(e - 23) for the exponent e of max z).
  if (zMax <= 0.0) return std::ldexp(1.0, -126 - 23);
  // The usual case from the bits (set up once per triangle; frexp and ldexp are library calls):
  // a normal zMax has exponent biased - 1023, and 2^(that - 23) has the biased exponent biased - 23.
  const int biased = int(std::bit_cast<uint64_t>(zMax) >> 52) & 0x7ff;
  if (biased > 23 && biased < 0x7ff) return std::bit_cast<double>(uint64_t(biased - 23) << 52);
  int e = 0;
  std::frexp(zMax, &e);  // zMax = m * 2^e, m in [0.5, 1): exponent in IEEE terms is e - 1
  return std::ldexp(1.0, e - 1 - 23);
}

Framebuffer::Framebuffer(int width, int height, DepthFormat depthFormat)
    : width_(width), height_(height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("framebuffer size must be positive");
  depthCodec_.format = depthFormat;
}

void Framebuffer::ensureColor() {
  if (color_.empty()) color_.assign(size_t(width_) * size_t(height_), glm::vec4(0.0f));
}
void Framebuffer::ensureDepth() {
  if (depth_.empty()) depth_.assign(size_t(width_) * size_t(height_), depthCodec_.encode(1.0));
}
void Framebuffer::ensureStencil() {
  if (stencil_.empty()) stencil_.assign(size_t(width_) * size_t(height_), 0);
}
void Framebuffer::ensureAccum() {
  if (accum_.empty()) accum_.assign(size_t(width_) * size_t(height_), glm::vec4(0.0f));
}

}  // namespace shadowref
