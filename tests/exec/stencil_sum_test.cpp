// addAndZeroCounts against its definition, byte by byte: every length from 0 to 100 (no step of 32,
// whole steps, and every partial tail), at every offset of an unaligned start, with random bytes
// whose sums wrap past 255.
#include <cstdint>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/stencil_sum.h"

using namespace shadowref;

TEST_CASE("addAndZeroCounts adds each count modulo 256 and zeroes it, for any length and start", "[raster][stencil]") {
  std::mt19937 random(20261128);
  std::uniform_int_distribution<int> byte(0, 255);
  int wrapped = 0;
  for (size_t offset = 0; offset < 4; ++offset) {
    for (size_t n = 0; n <= 100; ++n) {
      std::vector<uint8_t> stencil(offset + n + 8), counts(offset + n + 8);
      for (uint8_t& v : stencil) v = uint8_t(byte(random));
      for (uint8_t& v : counts) v = uint8_t(byte(random));
      std::vector<uint8_t> expectStencil = stencil, expectCounts = counts;
      for (size_t i = offset; i < offset + n; ++i) {
        wrapped += expectStencil[i] + expectCounts[i] > 255;
        expectStencil[i] = uint8_t((expectStencil[i] + expectCounts[i]) % 256);
        expectCounts[i] = 0;
      }
      addAndZeroCounts(stencil.data() + offset, counts.data() + offset, n);
      INFO("offset " << offset << ", length " << n);
      CHECK(stencil == expectStencil);  // bytes outside [offset, offset + n) untouched too
      CHECK(counts == expectCounts);
    }
  }
  CHECK(wrapped > 1000);  // the modulo was exercised, not only small sums
}
