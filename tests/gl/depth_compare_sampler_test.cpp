// The shadow-map lookup ([Hempe 2004, §3.1, §5.1.2]): projective (s, t, r, q), nearest texel, clamp
// to edge, r/q compared against the stored depth, 1 on pass and the compare-fail value (0.4) on
// failure.
#include <cmath>
#include <iterator>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/depth_compare_sampler.h"

using namespace shadowref;

namespace {

// 4x4 texels of depth 0.5, except (1, 2) = 0.2, (2, 3) = 0.1 and (3, 3) = 0.9.
DepthTexture texture() {
  DepthTexture t = DepthTexture::filled(4, 4, 0.5f);
  t.set(1, 2, 0.2f);
  t.set(2, 3, 0.1f);
  t.set(3, 3, 0.9f);
  return t;
}

}  // namespace

TEST_CASE("nearest texel is floor(s * size): 1 when r <= D, else the fail value 0.4", "[raster][sampler]") {
  const DepthTexture tex = texture();
  const DepthCompareSampler sm{&tex};
  // s = 0.3, t = 0.6 -> texel (floor 1.2, floor 2.4) = (1, 2), D = 0.2
  CHECK(sm.sample({0.3, 0.6, 0.1, 1.0}) == 1.0);
  CHECK(sm.sample({0.3, 0.6, 0.2, 1.0}) == 1.0);  // LEQUAL: equal passes
  CHECK(sm.sample({0.3, 0.6, 0.3, 1.0}) == 0.4);
  // s = 0.24 -> floor(0.96) = 0: texel (0, 2), D = 0.5
  CHECK(sm.sample({0.24, 0.6, 0.3, 1.0}) == 1.0);
  // s = 0.25 exactly -> texel 1
  CHECK(sm.sample({0.25, 0.6, 0.3, 1.0}) == 0.4);
}

TEST_CASE("coordinates outside [0, 1] clamp to the edge texels", "[raster][sampler]") {
  const DepthTexture tex = texture();
  const DepthCompareSampler sm{&tex};
  CHECK(sm.sample({1.7, 1.2, 0.8, 1.0}) == 1.0);   // texel (3, 3), D = 0.9
  CHECK(sm.sample({1.0, 1.0, 0.95, 1.0}) == 0.4);  // s = t = 1 -> texel 3, not 4
  CHECK(sm.sample({-0.5, 0.6, 0.3, 1.0}) == 1.0);  // texel (0, 2), D = 0.5
  CHECK(sm.sample({0.3, -3.0, 0.6, 1.0}) == 0.4);  // texel (1, 0), D = 0.5
  // r is clamped to [0, 1] too: r = 1.5 -> 1 > 0.9 fails; r = -1 -> 0 passes.
  CHECK(sm.sample({1.7, 1.2, 1.5, 1.0}) == 0.4);
  CHECK(sm.sample({0.3, 0.6, -1.0, 1.0}) == 1.0);
}

TEST_CASE("the lookup divides s, t and r by q", "[raster][sampler]") {
  const DepthTexture tex = texture();
  const DepthCompareSampler sm{&tex};
  // (0.6, 1.2, 0.3, 2) -> (0.3, 0.6, 0.15): texel (1, 2), D = 0.2, passes. Undivided it would be
  // texel (2, 3), D = 0.1 with r = 0.3, a failure.
  CHECK(sm.sample({0.6, 1.2, 0.3, 2.0}) == 1.0);
  CHECK(sm.sample({0.6, 1.2, 0.3, 1.0}) == 0.4);
}

TEST_CASE("compare func and fail value are settings", "[raster][sampler]") {
  const DepthTexture tex = texture();
  DepthCompareSampler sm{&tex, CompareFunc::Greater, 0.0};
  CHECK(sm.sample({0.3, 0.6, 0.3, 1.0}) == 1.0);  // 0.3 > 0.2
  CHECK(sm.sample({0.3, 0.6, 0.1, 1.0}) == 0.0);
}

TEST_CASE("PCF 3x3 averages the nine comparisons around the nearest texel", "[raster][sampler]") {
  const DepthTexture tex = texture();
  const DepthCompareSampler sm{&tex};
  // Around (1, 2) with r = 0.3: texels x 0..2, y 1..3 hold 0.5 except (1, 2) = 0.2 and (2, 3) = 0.1:
  // 7 pass, 2 fail -> (7 + 2 * 0.4) / 9.
  CHECK(sm.samplePcf({0.3, 0.6, 0.3, 1.0}, 3) == Approx(7.8 / 9.0).epsilon(1e-15));
  // At the corner (3, 3) the neighbours clamp to the edge: columns 2, 3, 3 and rows 2, 3, 3;
  // (2, 3) = 0.1 appears twice -> (7 + 2 * 0.4) / 9.
  CHECK(sm.samplePcf({0.9, 0.9, 0.3, 1.0}, 3) == Approx(7.8 / 9.0).epsilon(1e-15));
  // All pass and all fail.
  CHECK(sm.samplePcf({0.6, 0.3, 0.05, 1.0}, 3) == 1.0);
  CHECK(sm.samplePcf({0.6, 0.3, 0.95, 1.0}, 3) == Approx(0.4).epsilon(1e-15));
  // k = 1 is the plain lookup.
  CHECK(sm.samplePcf({0.3, 0.6, 0.3, 1.0}, 1) == 0.4);
}

TEST_CASE("PCF with a depth slope compares each tap at the receiver's depth there", "[raster][sampler]") {
  // A 4x4 map of a sloped receiver: D = 0.3 + 0.1 x at texel column x. At texel (1, 1) with
  // r = 0.39 (just in front of D = 0.4) the tap of column 0 holds 0.3 < 0.39.
  DepthTexture tex = DepthTexture::filled(4, 4, 0.0f);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) tex.set(x, y, float(0.3 + 0.1 * x));
  const DepthCompareSampler sm{&tex};
  const glm::dvec4 strq(1.5 / 4.0, 1.5 / 4.0, 0.39, 1.0);
  // Every tap compares 0.39: column 0 fails (3 taps) -> (6 + 3 * 0.4) / 9.
  CHECK(sm.samplePcf(strq, 3) == Approx(7.2 / 9.0).epsilon(1e-15));
  // With the receiver's slope, 0.1 per texel along x: the taps compare 0.29, 0.39, 0.49, all pass.
  CHECK(sm.samplePcf(strq, 3, {0.1, 0.0}) == 1.0);
  // A slope along the wrong axis helps nothing; twice the slope fails the other side's column.
  CHECK(sm.samplePcf(strq, 3, {0.0, 0.1}) == Approx(7.2 / 9.0).epsilon(1e-15));
  CHECK(sm.samplePcf(strq, 3, {0.2, 0.0}) == Approx(7.2 / 9.0).epsilon(1e-15));  // 0.59 > 0.5
  // The centre tap alone (k = 1) ignores the slope.
  CHECK(sm.samplePcf({1.5 / 4.0, 1.5 / 4.0, 0.41, 1.0}, 1, {0.1, 0.0}) == 0.4);
}

TEST_CASE("sampleDivided of many points gives each point's own lookup, for every length and func", "[raster][sampler]") {
  // The batch lookup finds every texel first and compares afterwards, vector by vector, in runs
  // of at most a fragment batch; each result must be the one-point lookup's, whatever the count
  // (whole vectors, a tail, more than a batch) and wherever the points fall (outside the map, on
  // texel edges, NaN). A non-square map catches a row and a column exchanged.
  DepthTexture tex = DepthTexture::filled(5, 3, 0.5f);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) tex.set(x, y, float(x * 3 + y) / 16.0f);
  const double coordinates[] = {-0.5, 0.0, 0.1, 0.2, 1.0 / 3.0, 0.4, 0.5, 0.66, 0.8, 0.99, 1.0, 1.7, std::nan("")};
  const double depths[] = {-1.0, 0.0, 0.125, 0.3, 0.4375, 0.5, 0.75, 0.875, 1.0, 2.0, std::nan("")};
  constexpr int kN = int(std::size(coordinates)), kD = int(std::size(depths));
  for (CompareFunc func : {CompareFunc::LEqual, CompareFunc::Less, CompareFunc::GEqual, CompareFunc::Equal}) {
    const DepthCompareSampler sampler{&tex, func, 0.25};
    for (int count : {0, 1, 3, 4, 5, 8, 63, 64, 65, 67, 68, 130}) {
      const size_t n = size_t(count);
      std::vector<double> s(n), t(n), r(n), out(n, -1.0);
      for (int k = 0; k < count; ++k) {
        s[size_t(k)] = coordinates[k % kN];
        t[size_t(k)] = coordinates[(k / kN + 3 * k) % kN];
        r[size_t(k)] = depths[(5 * k) % kD];
      }
      sampler.sampleDivided(s.data(), t.data(), r.data(), count, out.data());
      for (int k = 0; k < count; ++k) {
        INFO("func " << int(func) << " count " << count << " point " << k << ": " << s[size_t(k)] << ", "
                     << t[size_t(k)] << ", " << r[size_t(k)]);
        CHECK(out[size_t(k)] == sampler.sampleDivided(s[size_t(k)], t[size_t(k)], r[size_t(k)]));
      }
    }
  }
  // And one value by hand: (0.5, 0.5) is texel (2, 1), depth 7/16; r = 0.4375 passes LEQUAL.
  const DepthCompareSampler sampler{&tex};
  double s[5] = {0.5, 0.5, 0.5, 0.5, 0.5}, t[5] = {0.5, 0.5, 0.5, 0.5, 0.5}, r[5] = {0.4375, 0.5, 0.0, 1.0, 0.4375},
         out[5];
  sampler.sampleDivided(s, t, r, 5, out);
  CHECK(out[0] == 1.0);
  CHECK(out[1] == 0.4);
  CHECK(out[2] == 1.0);
  CHECK(out[3] == 0.4);
  CHECK(out[4] == 1.0);
}
