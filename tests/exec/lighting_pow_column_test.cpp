// The executor's batch form of the lighting power against the reference's scalar definition
// (gl/lighting_pow.h): every element must have the bits lightingPow gives it alone.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>

#include <catch2/catch.hpp>

#include "exec/lighting_pow_column.h"
#include "gl/lighting_pow.h"

using namespace shadowref;

namespace {

uint64_t bits(double x) { return std::bit_cast<uint64_t>(x); }

}  // namespace

TEST_CASE("lightingPowColumn gives each element the bits lightingPow gives it, whatever its neighbours",
          "[raster][lighting]") {
  // Scalar shading (shade(), Gouraud, the pixel history) and batch shading must agree bit for
  // bit, whatever the other elements of a vector hold.
  const double values[] = {0.0, -0.0, 1e-310, 0.001, 0.37, 0.5, 0.9999999, 1.0, 1.0000001, std::nan("")};
  for (double n : {3.0, 32.0, 77.7}) {
    for (double v : values) {
      for (int at = 0; at < 4; ++at) {
        double x[4] = {0.75, 1e-200, 0.0, std::nan("")};
        x[at] = v;
        lightingPowColumn(x, 4, n);
        CHECK(bits(x[at]) == bits(lightingPow(v, n)));
      }
    }
  }
}

TEST_CASE("lightingPowColumn gives every element the bits lightingPow gives it", "[raster][lighting]") {
  // The batch shaders take the powers of a whole batch at once, several vectors side by side;
  // each element must still be the scalar function's, whatever the column's length (full groups,
  // partial groups, a vector's dead lanes) and its neighbours.
  const double values[] = {0.0, -0.0, 1e-310, 1e-200, 0.001, 0.37, 0.5, 0.75, 0.9999999, 1.0, 1.0000001,
                           1.4142135623730951, 1.5, INFINITY, -0.25, std::nan("")};
  constexpr int kValues = int(std::size(values));
  for (double n : {0.0, 1.0, 3.0, 32.0, 77.7, 128.0, 200.0})
    for (int count = 0; count <= 70; ++count) {
      double x[70], y[70];
      for (int i = 0; i < count; ++i) x[i] = values[(7 * i + int(n)) % kValues];
      std::copy_n(x, count, y);
      lightingPowColumn(y, count, n);
      for (int i = 0; i < count; ++i) {
        INFO("n " << n << " count " << count << " element " << i << ", x " << x[i]);
        CHECK(bits(y[i]) == bits(lightingPow(x[i], n)));
      }
    }
  // And the values themselves, not only agreement: 0.5^3 in every element of a column of 37.
  double halves[37];
  std::fill_n(halves, 37, 0.5);
  lightingPowColumn(halves, 37, 3.0);
  for (double h : halves) CHECK(h == 0.125);
}
