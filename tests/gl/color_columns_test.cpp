// storeColorLanes / storeColorColumns only move values: every fragment's four channels must come
// out bit for bit as the columns held them (NaN, -0.0, infinities), for every count, with the lane
// order kept.
#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/color_columns.h"

using namespace shadowref;

namespace {
// A distinct value per (fragment, channel), with the awkward ones among them.
double valueOf(int k, int channel) {
  const double special[] = {-0.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity(), 1e-310};
  const int i = 4 * k + channel;
  return i % 7 == 3 ? special[(i / 7) % 5] : double(i) + 0.25;
}
bool sameBits(double a, double b) { return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b); }
}  // namespace

TEST_CASE("colour columns become RGBA per fragment, bit for bit, for every count", "[raster][shading]") {
  for (int count = 0; count <= 13; ++count) {
    std::vector<double> r(size_t(count) + 1), g(r.size()), b(r.size());
    for (int k = 0; k < count; ++k) {
      r[size_t(k)] = valueOf(k, 0);
      g[size_t(k)] = valueOf(k, 1);
      b[size_t(k)] = valueOf(k, 2);
    }
    std::vector<glm::dvec4> out(size_t(count) + 1, glm::dvec4(7.0));
    storeColorColumns(r.data(), g.data(), b.data(), -0.0, count, out.data());
    for (int k = 0; k < count; ++k) {
      INFO("count " << count << ", fragment " << k);
      CHECK(sameBits(out[size_t(k)].r, valueOf(k, 0)));
      CHECK(sameBits(out[size_t(k)].g, valueOf(k, 1)));
      CHECK(sameBits(out[size_t(k)].b, valueOf(k, 2)));
      CHECK(sameBits(out[size_t(k)].a, -0.0));
    }
    CHECK(out[size_t(count)] == glm::dvec4(7.0));  // nothing written past the end
  }
  // Fewer than four lanes: only those are written.
  std::vector<glm::dvec4> out(4, glm::dvec4(7.0));
  storeColorLanes(ColorLanes{1, 2, 3, 4}, ColorLanes{5, 6, 7, 8}, ColorLanes{9, 10, 11, 12}, ColorLanes{13, 14, 15, 16}, 2,
                  out.data());
  CHECK(out[0] == glm::dvec4(1, 5, 9, 13));
  CHECK(out[1] == glm::dvec4(2, 6, 10, 14));
  CHECK(out[2] == glm::dvec4(7.0));
  storeColorLanes(ColorLanes{1, 2, 3, 4}, ColorLanes{5, 6, 7, 8}, ColorLanes{9, 10, 11, 12}, ColorLanes{13, 14, 15, 16}, 4,
                  out.data());
  CHECK(out[3] == glm::dvec4(4, 8, 12, 16));
}
