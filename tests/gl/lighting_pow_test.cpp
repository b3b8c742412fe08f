#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>

#include <catch2/catch.hpp>

#include "gl/lighting_pow.h"

using namespace shadowref;

namespace {

uint64_t bits(double x) { return std::bit_cast<uint64_t>(x); }

}  // namespace

TEST_CASE("lightingPow is within 1e-13 of glibc's pow over the lighting range", "[raster][lighting]") {
  // glibc's pow is within 0.52 ulp of x^n (its documented bound), so it serves as the reference.
  // x from 2^-1074 up to 1.5 (specular bases end at 1, a rounded dot product a little above),
  // every exponent the scene files allow kind of: small, whole, odd, fractional, the largest.
  const double exponents[] = {0.25, 0.5, 1.0, 2.0, 3.0, 7.5, 8.0, 20.0, 32.0, 64.0, 100.3, 128.0};
  double worst = 0.0;
  int compared = 0;
  for (double n : exponents) {
    for (int i = 0; i <= 20000; ++i) {
      // Half the samples evenly in (0, 1.5], half spread over the exponent range down to 2^-1074.
      const double x = i % 2 == 0 ? 1.5 * double(i + 1) / 20001.0 : std::ldexp(1.0 + double(i % 977) / 977.0, -(i % 1075));
      const double expected = std::pow(x, n), got = lightingPow(x, n);
      if (expected == 0.0 || expected < std::numeric_limits<double>::min()) {
        // Underflow to a subnormal or zero: within a couple of the smallest steps.
        CHECK(std::abs(got - expected) <= 4.0 * std::numeric_limits<double>::denorm_min());
        continue;
      }
      const double relative = std::abs(got - expected) / expected;
      worst = std::max(worst, relative);
      ++compared;
      if (relative > 1e-13) FAIL("x " << x << " n " << n << ": " << got << " against " << expected);
    }
  }
  CHECK(compared > 100000);
  INFO("worst relative error " << worst);
  CHECK(worst < 1e-13);
}

TEST_CASE("lightingPow is exact at 1, at powers of two and for the special values", "[raster][lighting]") {
  CHECK(lightingPow(1.0, 32.0) == 1.0);
  CHECK(lightingPow(1.0, 7.5) == 1.0);
  CHECK(lightingPow(0.5, 3.0) == 0.125);
  CHECK(lightingPow(0.25, 64.0) == std::ldexp(1.0, -128));
  CHECK(lightingPow(2.0, 10.0) == 1024.0);
  CHECK(lightingPow(0.5, 100.0) == std::ldexp(1.0, -100));
  // C's pow: x^0 = 1 for every x, NaN included; +0^n = +0; -0^n = -0 for odd whole n, else +0.
  CHECK(lightingPow(0.3, 0.0) == 1.0);
  CHECK(lightingPow(0.0, 0.0) == 1.0);
  CHECK(lightingPow(std::nan(""), 0.0) == 1.0);
  CHECK(bits(lightingPow(0.0, 8.0)) == bits(0.0));
  CHECK(bits(lightingPow(-0.0, 3.0)) == bits(-0.0));
  CHECK(bits(lightingPow(-0.0, 8.0)) == bits(0.0));
  CHECK(bits(lightingPow(-0.0, 7.5)) == bits(0.0));
  CHECK(std::isnan(lightingPow(std::nan(""), 32.0)));
  CHECK(lightingPow(INFINITY, 2.0) == INFINITY);
  CHECK(lightingPow(1e-300, 128.0) == 0.0);  // far below the smallest subnormal
}
