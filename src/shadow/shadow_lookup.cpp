#include "shadow/shadow_lookup.h"

#include <cmath>
#include <cstring>

namespace shadowref {

glm::dvec4 shadowCoordinates(const glm::dmat4& T, const glm::dvec3& worldPosition) {
  return T * glm::dvec4(worldPosition, 1.0);
}

glm::dvec4 withConstantBias(const glm::dvec4& strq, double constantBias) {
  return {strq.x, strq.y, strq.z - constantBias * strq.w, strq.w};
}

glm::dvec4 trianglePlane(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  if (!(n != glm::dvec3(0.0))) return glm::dvec4(0.0);
  return glm::dvec4(n, -glm::dot(n, a));
}

DepthSlope receiverDepthSlope(const glm::dmat4& T, const glm::dvec4& worldPlane, int width, int height) {
  if (worldPlane == glm::dvec4(0.0)) return {};
  const glm::dvec4 p = glm::transpose(glm::inverse(T)) * worldPlane;
  const DepthSlope slope{-p.x / (p.z * double(width)), -p.y / (p.z * double(height))};
  if (!(std::isfinite(slope.x) && std::isfinite(slope.y))) return {};
  return slope;
}

namespace {
// Outside the map's square (a NaN is not outside: the sampler handles it as before).
bool outsideMap(double s, double t) { return s < 0.0 || s > 1.0 || t < 0.0 || t > 1.0; }
}  // namespace

DepthSlope ShadowLookup::tapSlope(const glm::dvec4& receiverPlane) const {
  const bool texel = receiverPlaneBias == ReceiverPlaneBias::Texel;
  if (!sampler.texture || !(texel || (receiverPlaneBias == ReceiverPlaneBias::Kernel && pcf > 1))) return {};
  DepthSlope slope = receiverDepthSlope(textureMatrix, receiverPlane, sampler.texture->width, sampler.texture->height);
  slope.nearestToo = true;  // every tap of a PCF kernel, and the one tap of nearest sampling with Texel
  return slope;
}

double ShadowLookup::factorOnSlope(const glm::dvec3& worldPosition, DepthSlope slope) const {
  const glm::dvec4 strq = withConstantBias(shadowCoordinates(textureMatrix, worldPosition), constantBias);
  if (!(strq.w > 0.0)) return 1.0;
  if (outsideLit && outsideMap(strq.x / strq.w, strq.y / strq.w)) return 1.0;
  return pcf > 1 || slope.nearestToo ? sampler.samplePcf(strq, pcf, slope) : sampler.sample(strq);
}

double ShadowLookup::factor(const glm::dvec3& worldPosition, const glm::dvec4& receiverPlane) const {
  return factorOnSlope(worldPosition, tapSlope(receiverPlane));
}

namespace {
// Four points' worth of one quantity (GCC vector types: IEEE operations lane by lane, so a lane
// holds the bits the scalar code computes).
using v4d = double __attribute__((vector_size(32)));
constexpr int kMaxPoints = 64;  // a fragment batch (kMaxBatch)
}  // namespace

void ShadowLookup::factors(const double* x, const double* y, const double* z, int count, double* out,
                           const glm::dvec4& receiverPlane) const {
  int k = 0;
  if (pcf <= 1 && receiverPlaneBias != ReceiverPlaneBias::Texel && count <= kMaxPoints) {
    // The points behind a perspective light (q <= 0) are sampled too (at meaningless
    // coordinates, clamped to the map) and then given 1.
    double divided[3][kMaxPoints];
    bool behind[kMaxPoints];
    const glm::dmat4& T = textureMatrix;
    for (; k + 4 <= count; k += 4) {
      v4d px, py, pz;
      std::memcpy(&px, x + k, sizeof px);
      std::memcpy(&py, y + k, sizeof py);
      std::memcpy(&pz, z + k, sizeof pz);
      // shadowCoordinates: glm's T * (p, 1) sums (c0·x + c1·y) + (c2·z + c3·1), row by row.
      auto row = [&](int i) { return (T[0][i] * px + T[1][i] * py) + (T[2][i] * pz + T[3][i] * 1.0); };
      const v4d s = row(0), t = row(1), q = row(3);
      const v4d r = row(2) - constantBias * q;  // withConstantBias
      const v4d sq = s / q, tq = t / q, rq = r / q;
      std::memcpy(divided[0] + k, &sq, sizeof sq);
      std::memcpy(divided[1] + k, &tq, sizeof tq);
      std::memcpy(divided[2] + k, &rq, sizeof rq);
      for (int lane = 0; lane < 4; ++lane) behind[k + lane] = !(q[lane] > 0.0);
    }
    if (k > 0) sampler.sampleDivided(divided[0], divided[1], divided[2], k, out);
    for (int i = 0; i < k; ++i)
      if (behind[i] || (outsideLit && outsideMap(divided[0][i], divided[1][i]))) out[i] = 1.0;
  }
  if (k == count) return;
  const DepthSlope slope = tapSlope(receiverPlane);  // one plane for all of them
  for (; k < count; ++k) out[k] = factorOnSlope({x[k], y[k], z[k]}, slope);
}

double CubeShadowLookup::factor(const glm::dvec3& worldPosition, const glm::dvec4& receiverPlane) const {
  const CubeFace face = cubeFaceFor(worldPosition - lightPosition);
  return faces[size_t(face)].factor(worldPosition, receiverPlane);
}

}  // namespace shadowref
