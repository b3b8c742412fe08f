// The lighting shaders' batches (FragmentShader::shadeBatch of PerPixelLightingShader and
// GouraudShader, and lightContributions, declared in gl/lighting.h): the scalar definitions of
// gl/lighting.cpp, operation for operation, four fragments at a time in vector lanes, so every
// fragment gets the bits shade() gives it. Kept in the executor so that the reference stays scalar.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "gl/color_columns.h"
#include "gl/lighting.h"
#include "exec/lighting_pow_column.h"

namespace shadowref {

namespace {

// Four fragments' worth of one quantity. GCC's vector types: +, -, *, / and comparisons act on
// all four lanes with IEEE semantics, so a lane holds the bits the scalar code computes. (Eight
// lanes gain nothing here: the divisions and square roots, most of the work but the powers, take
// as long per lane at either width, and a batch's last vector has more dead lanes.)
using v4d = double __attribute__((vector_size(32)));
using v4l = int64_t __attribute__((vector_size(32)));  // comparison results: -1 true, 0 false
constexpr int kBlocks = (kMaxBatch + 3) / 4;

inline v4d splat(double x) { return v4d{x, x, x, x}; }  // (not {} + x, which would turn -0 into +0)
inline v4d vsqrt(v4d x) {
  v4d r;
  for (int i = 0; i < 4; ++i) r[i] = std::sqrt(x[i]);
  return r;
}
inline v4d select(v4l mask, v4d a, v4d b) { return mask ? a : b; }
inline v4d vmax0(v4d x) { return x < 0.0 ? splat(0.0) : x; }  // std::max(x, 0.0)
// glm's dot of two dvec3: (a.x * b.x + a.y * b.y) + a.z * b.z.
inline v4d dot3(v4d ax, v4d ay, v4d az, v4d bx, v4d by, v4d bz) { return ax * bx + ay * by + az * bz; }

// Colours of every block of a batch.
struct BlockColors {
  v4d r[kBlocks], g[kBlocks], b[kBlocks];
};

// lightContribution for a batch, four fragments per block: its operations in the same order, with
// both sides of every early return computed and the result selected (a lane the scalar code would
// have left early gets +0.0, as the early return's zero vector). Each step runs over all blocks
// before the next, so the powers — the longest chains — are taken for the whole batch at once
// (lightingPowColumn); every lane's power is lightingPow's, as the scalar code's is.
struct LightingColumns {
  int count = 0, blocks = 0;
  v4d px[kBlocks], py[kBlocks], pz[kBlocks], nx[kBlocks], ny[kBlocks], nz[kBlocks];

  // Positions, and normals as fragmentNormal makes them; lanes past the batch hold copies of its
  // last fragment.
  explicit LightingColumns(const FragmentBatch& batch) : count(batch.count), blocks((batch.count + 3) / 4) {
    const bool back = batch.facing == BackFacing;
    for (int q = 0; q < blocks; ++q) {
      int k[4];
      for (int lane = 0; lane < 4; ++lane) k[lane] = std::min(4 * q + lane, count - 1);
      const bool whole = 4 * q + 4 <= count;
      auto column = [&](int j) {
        const double* c = batch.varyings[j];
        if (!whole) return v4d{c[k[0]], c[k[1]], c[k[2]], c[k[3]]};
        v4d v;
        std::memcpy(&v, c + 4 * q, sizeof v);
        return v;
      };
      v4d p[3], n[3];
      for (int j = 0; j < 3; ++j) {
        p[j] = column(kVaryingPosition + j);
        n[j] = column(kVaryingNormal + j);
      }
      const v4d len = vsqrt(dot3(n[0], n[1], n[2], n[0], n[1], n[2]));
      const v4l scale = len > 0.0;
      for (int j = 0; j < 3; ++j) {
        const v4d unit = select(scale, n[j] / len, n[j]);
        n[j] = back ? -unit : unit;
      }
      px[q] = p[0];
      py[q] = p[1];
      pz[q] = p[2];
      nx[q] = n[0];
      ny[q] = n[1];
      nz[q] = n[2];
    }
  }

  // Towards the light from block q's fragments: the unit direction, the attenuation without the
  // spot term, and the lanes a point light does not sit on.
  struct Towards {
    v4d x, y, z, att;
    v4l lit;
  };
  Towards towardsLight(const LightTerms& L, int q) const {
    if (L.directional)
      return {splat(L.direction.x), splat(L.direction.y), splat(L.direction.z), splat(1.0), v4l{} - 1};
    const v4d tx = L.point.x - px[q], ty = L.point.y - py[q], tz = L.point.z - pz[q];
    const v4d d = vsqrt(dot3(tx, ty, tz, tx, ty, tz));
    return {tx / d, ty / d, tz / d, 1.0 / (L.attenuation.x + L.attenuation.y * d + L.attenuation.z * d * d), d != 0.0};
  }

  // The diffuse term into out; returns N.L.
  v4d diffuse(const LightTerms& L, int q, Towards& l, BlockColors& out) const {
    const v4d nDotL = dot3(nx[q], ny[q], nz[q], l.x, l.y, l.z);
    l.lit &= ~(nDotL <= 0.0);
    out.r[q] = L.diffuse.x * nDotL;
    out.g[q] = L.diffuse.y * nDotL;
    out.b[q] = L.diffuse.z * nDotL;
    return nDotL;
  }

  static void attenuate(int q, const Towards& l, BlockColors& out) {
    out.r[q] = select(l.lit, l.att * out.r[q], splat(0.0));
    out.g[q] = select(l.lit, l.att * out.g[q], splat(0.0));
    out.b[q] = select(l.lit, l.att * out.b[q], splat(0.0));
  }

  void contributions(const LightTerms& L, const glm::dvec3& eye, BlockColors& out) const {
    if (!L.spot && !L.specular) {  // no powers: block by block, nothing kept between the steps
      for (int q = 0; q < blocks; ++q) {
        Towards l = towardsLight(L, q);
        diffuse(L, q, l, out);
        attenuate(q, l, out);
      }
      return;
    }
    Towards l[kBlocks];
    double power[4 * kBlocks];  // the bases, then the powers, of every lane
    auto powerOf = [&](int q) {
      v4d v;
      std::memcpy(&v, power + 4 * q, sizeof v);
      return v;
    };
    auto setPower = [&](int q, v4d v) { std::memcpy(power + 4 * q, &v, sizeof v); };
    for (int q = 0; q < blocks; ++q) {
      l[q] = towardsLight(L, q);
      if (!L.spot) continue;
      const v4d cosAngle = dot3(-l[q].x, -l[q].y, -l[q].z, splat(L.spotAxis.x), splat(L.spotAxis.y), splat(L.spotAxis.z));
      l[q].lit &= ~(cosAngle < L.spotCosCutoff);
      setPower(q, vmax0(cosAngle));
    }
    if (L.spot) {
      lightingPowColumn(power, 4 * blocks, L.spotExponent);
      for (int q = 0; q < blocks; ++q) l[q].att *= powerOf(q);
    }
    for (int q = 0; q < blocks; ++q) {
      const v4d nDotL = diffuse(L, q, l[q], out);
      if (!L.specular) continue;
      const v4d ex = eye.x - px[q], ey = eye.y - py[q], ez = eye.z - pz[q];
      const v4d ie = 1.0 / vsqrt(dot3(ex, ey, ez, ex, ey, ez));
      const v4d vx = ex * ie, vy = ey * ie, vz = ez * ie;
      if (L.blinn) {
        const v4d hx = l[q].x + vx, hy = l[q].y + vy, hz = l[q].z + vz;
        const v4d ih = 1.0 / vsqrt(dot3(hx, hy, hz, hx, hy, hz));
        setPower(q, vmax0(dot3(nx[q], ny[q], nz[q], hx * ih, hy * ih, hz * ih)));
      } else {
        const v4d twice = 2.0 * nDotL;
        setPower(q, vmax0(dot3(twice * nx[q] - l[q].x, twice * ny[q] - l[q].y, twice * nz[q] - l[q].z, vx, vy, vz)));
      }
    }
    if (L.specular) {
      lightingPowColumn(power, 4 * blocks, L.shininess);
      for (int q = 0; q < blocks; ++q) {
        const v4d spec = powerOf(q);
        out.r[q] += L.specularColor.x * spec;
        out.g[q] += L.specularColor.y * spec;
        out.b[q] += L.specularColor.z * spec;
      }
    }
    for (int q = 0; q < blocks; ++q) attenuate(q, l[q], out);
  }
};

}  // namespace

void lightContributions(const FragmentBatch& batch, const LightTerms& light, const glm::dvec3& eye, double* r,
                        double* g, double* b) {
  if (batch.count == 0) return;
  const LightingColumns columns(batch);
  BlockColors colors;
  columns.contributions(light, eye, colors);
  const int whole = batch.count / 4;
  for (int q = 0; q < whole; ++q) {
    std::memcpy(r + 4 * q, &colors.r[q], sizeof colors.r[q]);
    std::memcpy(g + 4 * q, &colors.g[q], sizeof colors.g[q]);
    std::memcpy(b + 4 * q, &colors.b[q], sizeof colors.b[q]);
  }
  for (int k = 4 * whole; k < batch.count; ++k) {
    r[k] = colors.r[whole][k % 4];
    g[k] = colors.g[whole][k % 4];
    b[k] = colors.b[whole][k % 4];
  }
}

// litColor for a batch: c = base, then c += each light's contribution in order, as litColor adds
// them, but four fragments at a time in the lanes.
void PerPixelLightingShader::shadeBatch(const FragmentBatch& batch, glm::dvec4* out) const {
  if (batch.count == 0) return;
  const LightingColumns columns(batch);
  BlockColors sum, light;
  for (int q = 0; q < columns.blocks; ++q) {
    sum.r[q] = splat(base_.x);
    sum.g[q] = splat(base_.y);
    sum.b[q] = splat(base_.z);
  }
  for (const LightTerms& terms : terms_) {
    columns.contributions(terms, eye_, light);
    for (int q = 0; q < columns.blocks; ++q) {
      sum.r[q] += light.r[q];
      sum.g[q] += light.g[q];
      sum.b[q] += light.b[q];
    }
  }
  const ColorLanes alpha = {1.0, 1.0, 1.0, 1.0};
  for (int q = 0; q < columns.blocks; ++q)
    storeColorLanes(sum.r[q], sum.g[q], sum.b[q], alpha, std::min(4, batch.count - 4 * q), out + 4 * q);
}

// shade() for every fragment: the interpolated colour columns, copied.
void GouraudShader::shadeBatch(const FragmentBatch& batch, glm::dvec4* out) const {
  storeColorColumns(batch.varyings[kVaryingColor], batch.varyings[kVaryingColor + 1], batch.varyings[kVaryingColor + 2],
                    1.0, batch.count, out);
}

}  // namespace shadowref
