#include "gl/depth_compare_sampler.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace shadowref {

std::vector<float> DepthTexture::values() const {
  std::vector<float> out(bits.size());
  for (size_t i = 0; i < bits.size(); ++i) out[i] = std::bit_cast<float>(bits[i]);
  return out;
}

DepthTexture DepthTexture::filled(int width, int height, float depth) {
  DepthTexture t;
  t.width = width;
  t.height = height;
  t.bits.assign(size_t(width) * size_t(height), std::bit_cast<uint32_t>(depth));
  return t;
}

int nearestTexel(double coordinate, int size) {
  // GL nearest: floor(s * size), then clamp to edge.
  const double t = std::floor(coordinate * double(size));
  if (!(t >= 0.0)) return 0;  // also NaN
  return int(std::min(t, double(size - 1)));
}

double DepthCompareSampler::compareTexel(int x, int y, double r) const {
  x = std::clamp(x, 0, texture->width - 1);
  y = std::clamp(y, 0, texture->height - 1);
  // Depth textures compare in float, as they are stored; r is clamped to [0, 1]
  // ([GL 2.1, §3.8.14]).
  const float rf = float(std::clamp(r, 0.0, 1.0));
  const float d = texture->at(x, y);
  bool pass = false;
  switch (func) {
    case CompareFunc::Never: pass = false; break;
    case CompareFunc::Less: pass = rf < d; break;
    case CompareFunc::Equal: pass = rf == d; break;
    case CompareFunc::LEqual: pass = rf <= d; break;
    case CompareFunc::Greater: pass = rf > d; break;
    case CompareFunc::NotEqual: pass = rf != d; break;
    case CompareFunc::GEqual: pass = rf >= d; break;
    case CompareFunc::Always: pass = true; break;
  }
  return pass ? 1.0 : failValue;
}

double DepthCompareSampler::sample(const glm::dvec4& strq) const {
  return sampleDivided(strq.x / strq.w, strq.y / strq.w, strq.z / strq.w);
}

double DepthCompareSampler::sampleDivided(double s, double t, double r) const {
  return compareTexel(nearestTexel(s, texture->width), nearestTexel(t, texture->height), r);
}

double DepthCompareSampler::samplePcf(const glm::dvec4& strq, int k, DepthSlope slope) const {
  if (k <= 1 && !slope.nearestToo) return sample(strq);
  const double s = strq.x / strq.w, t = strq.y / strq.w, r = strq.z / strq.w;
  const int cx = nearestTexel(s, texture->width), cy = nearestTexel(t, texture->height);
  const int half = k > 1 ? k / 2 : 0;
  // The nearest texel's centre from the point, in texels.
  const double ox = double(cx) + 0.5 - s * double(texture->width);
  const double oy = double(cy) + 0.5 - t * double(texture->height);
  double sum = 0.0;
  for (int dy = -half; dy <= half; ++dy)
    for (int dx = -half; dx <= half; ++dx) {
      const bool nearest = dx == 0 && dy == 0 && !slope.nearestToo;
      sum += compareTexel(cx + dx, cy + dy, nearest ? r : r + (slope.x * (ox + dx) + slope.y * (oy + dy)));
    }
  return sum / double((2 * half + 1) * (2 * half + 1));
}

}  // namespace shadowref
