// encodeLanes (exec/depth_lanes.h) against DepthCodec::encode, lane for lane: the span loops'
// depth codes for Unorm24 buffers and clamped depths come from it, the pixel history's from encode.
#include <cmath>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/depth_lanes.h"
#include "support/raster_harness.h"

using namespace shadowref;

namespace {

// Every depth of `depths`, four at a time, encoded both ways.
void checkAgainstEncode(const DepthCodec& codec, const std::vector<double>& depths) {
  for (size_t i = 0; i < depths.size(); i += 4) {
    DepthLanes z{};
    for (size_t k = 0; k < 4; ++k) z[k] = depths[std::min(i + k, depths.size() - 1)];
    const DepthCodeLanes codes = encodeLanes(codec, z);
    for (size_t k = 0; k < 4; ++k) {
      INFO("depth " << z[k] << " (" << std::hexfloat << z[k] << std::defaultfloat << ")");
      CHECK(codes[k] == codec.encode(z[k]));
    }
  }
}

}  // namespace

TEST_CASE("depth codes in vector lanes are encode's, for both formats and every special value", "[raster][depth]") {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> depths{0.0,
                             -0.0,
                             1.0,
                             std::nextafter(1.0, 0.0),
                             std::nextafter(1.0, 2.0),
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::min(),
                             -1.0,
                             2.0,
                             inf,
                             -inf,
                             std::numeric_limits<double>::quiet_NaN(),
                             0.5,
                             1e-9,
                             0.999999999};
  testing::TestRandom r(42);
  for (int i = 0; i < 4000; ++i) depths.push_back(r.uniform(-0.1, 1.1));
  for (const DepthFormat format : {DepthFormat::Float32, DepthFormat::Unorm24}) {
    DepthCodec codec;
    codec.format = format;
    checkAgainstEncode(codec, depths);
  }
}

TEST_CASE("Unorm24 codes in vector lanes round halves to even, as nearbyint does", "[raster][depth]") {
  // Depths whose z * (2^24 - 1) is exactly a whole number and a half: there rounding to even and
  // rounding halves up part (for an even whole number), so a loop rounding halves up fails here.
  std::vector<double> ties;
  int evenTies = 0;
  for (uint32_t k = 0; k < 16777215u; k += 997) {
    const double m = double(k) + 0.5;
    const double z = m / 16777215.0;
    if (z * 16777215.0 != m) continue;
    ties.push_back(z);
    ties.push_back(std::nextafter(z, 0.0));
    ties.push_back(std::nextafter(z, 1.0));
    evenTies += k % 2 == 0;
  }
  INFO(ties.size() / 3 << " ties, " << evenTies << " of them above an even number");
  REQUIRE(evenTies >= 10);
  DepthCodec codec;
  codec.format = DepthFormat::Unorm24;
  checkAgainstEncode(codec, ties);
  // The ties themselves: even codes.
  for (size_t i = 0; i < ties.size(); i += 3) CHECK(codec.encode(ties[i]) % 2 == 0);
}
