// The shadow-map texture unit ([Hempe 2004, §3.1, §5.1.2]): a depth texture looked up with
// projective coordinates (s, t, r, q), nearest sampling, clamp to edge, and a depth comparison
// of r/q against the stored depth (GL_COMPARE_R_TO_TEXTURE, func LEQUAL by default). A passing
// comparison gives 1, a failing one the compare-fail value (ARB_shadow_ambient; [Hempe 2004]
// uses 0.4).
#pragma once

#include <bit>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/framebuffer.h"
#include "gl/render_state.h"

namespace shadowref {

// A depth map: per texel a depth in [0, 1], row 0 at the bottom. Kept as the bits of the float,
// which is what a Float32 depth buffer holds: a rendered map becomes a texture without a copy.
struct DepthTexture {
  int width = 0, height = 0;
  PixelVector<uint32_t> bits;

  float at(int x, int y) const { return std::bit_cast<float>(bits[index(x, y)]); }
  void set(int x, int y, float depth) { bits[index(x, y)] = std::bit_cast<uint32_t>(depth); }
  std::vector<float> values() const;  // every texel, for dumps and images
  static DepthTexture filled(int width, int height, float depth);

 private:
  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
};

// The texel GL_NEAREST picks along one axis of `size` texels: floor(coordinate · size), clamped to
// the edge (NaN and negatives to 0), as every sample below picks it.
int nearestTexel(double coordinate, int size);

// A receiver's depth slope in the map: how its plane's r/q changes from one texel to the next
// along s (x) and t (y). Zero: the receiver is taken as facing the light (every tap compares r/q).
// nearestToo: the nearest tap follows the plane to its texel's centre as well.
struct DepthSlope {
  double x = 0.0, y = 0.0;
  bool nearestToo = false;
};

struct DepthCompareSampler {
  const DepthTexture* texture = nullptr;
  CompareFunc func = CompareFunc::LEqual;
  double failValue = 0.4;

  // Nearest texel, clamp to edge; returns 1 when (r/q func D) holds, otherwise failValue.
  double sample(const glm::dvec4& strq) const;
  // sample() after its division: the texture coordinates s/q, t/q and the depth r/q.
  double sampleDivided(double s, double t, double r) const;
  // sampleDivided for `count` points, into out[k]: the same bits, four points at a time (defined
  // with the executor's vector kernels, exec/sampler_kernels.cpp).
  void sampleDivided(const double* s, const double* t, const double* r, int count, double* out) const;
  // k x k percentage-closer filtering around the nearest texel (k odd): the mean of the k^2
  // comparisons, each 1 or failValue. Each tap but the nearest compares the receiver's depth at
  // its texel's centre (x_c + 0.5, y_c + 0.5), where the map pass drew that texel's depth:
  // r/q + slope.x · (x_c + 0.5 − s/q · width) + slope.y · (y_c + 0.5 − t/q · height)
  // (receiver-plane depth bias, [Isidoro 2006], who steps whole texels from the point instead:
  // then a tap whose texel holds a flatter face beside a convex crease, with a smaller offset,
  // can fail by the point's distance from its own texel's centre). The nearest tap compares r/q,
  // as sample() does, unless slope.nearestToo (then also for k = 1).
  double samplePcf(const glm::dvec4& strq, int k, DepthSlope slope = {}) const;

 private:
  double compareTexel(int x, int y, double r) const;
};

}  // namespace shadowref
