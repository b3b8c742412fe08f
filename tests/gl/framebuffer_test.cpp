// DepthCodec: the depth buffer's codes for the two formats, and buffers that exist only on demand.
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/framebuffer.h"

using namespace shadowref;

TEST_CASE("float32 depth codes are the IEEE bits of the depth as a float", "[raster][depth]") {
  const DepthCodec c{DepthFormat::Float32};
  CHECK(c.encode(0.0) == 0x00000000u);
  CHECK(c.encode(0.5) == 0x3F000000u);
  CHECK(c.encode(1.0) == 0x3F800000u);
  CHECK(c.encode(0.1) == 0x3DCCCCCDu);  // 0.1 rounded to the nearest float
  CHECK(c.encode(-0.25) == 0x00000000u);  // clamped to +0, never the bits of -0.0
  CHECK(c.encode(7.0) == 0x3F800000u);  // clamped to 1
  CHECK(c.decode(0x3F000000u) == 0.5);
  CHECK(c.decode(0x3DCCCCCDu) == double(0.1f));
  CHECK(c.decode(c.encode(0.3)) == double(0.3f));
}

TEST_CASE("negative zero and NaN depths encode as +0, below every positive depth", "[raster][depth]") {
  for (DepthFormat format : {DepthFormat::Float32, DepthFormat::Unorm24}) {
    const DepthCodec c{format};
    CHECK(c.encode(-0.0) == 0u);
    CHECK(c.encode(std::nan("")) == 0u);
    CHECK(c.encode(-0.0) < c.encode(1e-6));
  }
}

TEST_CASE("unorm24 depth codes are round(z * (2^24 - 1))", "[raster][depth]") {
  const DepthCodec c{DepthFormat::Unorm24};
  CHECK(c.encode(0.0) == 0u);
  CHECK(c.encode(1.0) == 0xFFFFFFu);
  CHECK(c.encode(1.0 / 3.0) == 5592405u);  // (2^24 - 1) / 3 exactly
  CHECK(c.encode(0.25) == 4194304u);       // 4194303.75 rounds up
  CHECK(c.encode(100.0 / 16777215.0) == 100u);
  CHECK(c.encode(100.4 / 16777215.0) == 100u);
  CHECK(c.encode(100.6 / 16777215.0) == 101u);
  CHECK(c.encode(-1.0) == 0u);
  CHECK(c.encode(2.0) == 0xFFFFFFu);
  CHECK(c.decode(0xFFFFFFu) == 1.0);
  CHECK(c.decode(5592405u) == 1.0 / 3.0);
  CHECK(c.decode(1u) == 1.0 / 16777215.0);
}

TEST_CASE("depth codes sort like the depths they encode, in both formats", "[raster][depth]") {
  const std::vector<double> increasing{0.0, 1e-40, 1e-30, 1e-7, 0.1, 0.25, 0.5, 0.5 + 1e-7, 0.75, 0.999999, 1.0};
  for (DepthFormat format : {DepthFormat::Float32, DepthFormat::Unorm24}) {
    const DepthCodec c{format};
    for (size_t i = 1; i < increasing.size(); ++i) {
      INFO("z " << increasing[i - 1] << " < " << increasing[i]);
      CHECK(c.encode(increasing[i - 1]) <= c.encode(increasing[i]));
      CHECK(c.decode(c.encode(increasing[i - 1])) <= c.decode(c.encode(increasing[i])));
    }
  }
  // Float32 keeps the tiny depths apart, unorm24 merges everything below half a unit into 0.
  const DepthCodec f{DepthFormat::Float32}, u{DepthFormat::Unorm24};
  CHECK(f.encode(1e-40) > f.encode(0.0));
  CHECK(f.encode(1e-30) > f.encode(1e-40));
  CHECK(u.encode(1e-8) == u.encode(0.0));
}

TEST_CASE("polygon offset r: 1/(2^24-1) for unorm24, 2^(e-23) of the largest depth for float32", "[raster][depth]") {
  const DepthCodec u{DepthFormat::Unorm24}, f{DepthFormat::Float32};
  CHECK(u.resolvableDifference(0.5) == 1.0 / 16777215.0);
  CHECK(u.resolvableDifference(0.01) == 1.0 / 16777215.0);
  // z in [0.5, 1): exponent e = -1, r = 2^-24; z in [0.25, 0.5): 2^-25; z = 1: e = 0, 2^-23.
  CHECK(f.resolvableDifference(0.75) == std::ldexp(1.0, -24));
  CHECK(f.resolvableDifference(0.5) == std::ldexp(1.0, -24));
  CHECK(f.resolvableDifference(0.4999) == std::ldexp(1.0, -25));
  CHECK(f.resolvableDifference(1.0) == std::ldexp(1.0, -23));
  // r is exactly one float ulp there: adding it moves the code by one.
  CHECK(f.encode(0.75 + f.resolvableDifference(0.75)) == f.encode(0.75) + 1);
  // Every exponent a depth can have, at both ends of its binade and between (the exponent is
  // read from the bits; ilogb is the independent reading), down to the smallest doubles.
  for (int e = -1074; e <= 0; ++e)
    for (const double m : {1.0, 1.5, 2.0 - 0x1p-52}) {
      const double z = std::ldexp(m, e);
      if (z > 1.0 || z == 0.0) continue;
      INFO("z = " << z);
      CHECK(f.resolvableDifference(z) == std::ldexp(1.0, std::ilogb(z) - 23));
    }
}

TEST_CASE("a framebuffer allocates each buffer only when asked, cleared to GL's initial values", "[raster]") {
  Framebuffer fb(3, 2, DepthFormat::Unorm24);
  CHECK_FALSE(fb.hasColor());
  CHECK_FALSE(fb.hasDepth());
  CHECK_FALSE(fb.hasStencil());
  CHECK_FALSE(fb.hasAccum());
  fb.ensureDepth();
  CHECK(fb.hasDepth());
  CHECK_FALSE(fb.hasColor());
  CHECK(fb.depthCodes() == PixelVector<uint32_t>(6, 0xFFFFFFu));
  fb.ensureStencil();
  CHECK(fb.stencil() == PixelVector<uint8_t>(6, 0));
  CHECK(fb.index(2, 1) == 5u);  // row 0 is the bottom row, x fastest
  CHECK_THROWS(Framebuffer(0, 4));
}
