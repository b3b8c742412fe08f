// clampUnit against std::clamp(c, 0.0, 1.0), bit for bit, on the values where a clamp written with
// min and max could go wrong: NaN, both zeros, the bounds, infinities, subnormals.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/clamp_unit.h"
#include "gl/framebuffer.h"

using namespace shadowref;

TEST_CASE("clampUnit is std::clamp to [0, 1] in every lane, NaN and -0.0 included", "[raster][blend]") {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> values{0.0,  -0.0, 1.0,  -1.0, 0.5,  1.0000000000000002, 0.9999999999999999, 2.0,
                                   -1e-300, 1e-310, -1e-310, inf, -inf, nan, -nan, 1e300};
  for (size_t a = 0; a < values.size(); ++a) {
    // Every value in every lane, beside its neighbours.
    const ClampLanes in = {values[a], values[(a + 1) % values.size()], values[(a + 5) % values.size()],
                           values[(a + 11) % values.size()]};
    const ClampLanes out = clampUnit(in);
    for (int lane = 0; lane < 4; ++lane) {
      const double expected = std::clamp(in[lane], 0.0, 1.0);
      INFO("input " << in[lane] << " (bits " << std::bit_cast<uint64_t>(in[lane]) << ")");
      CHECK(std::bit_cast<uint64_t>(out[lane]) == std::bit_cast<uint64_t>(expected));
    }
  }
}

TEST_CASE("clampUnitOrZero clamps as the depth encoder does: NaN and -0.0 to +0.0", "[raster][depth]") {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> values{0.0, -0.0, 1.0, -1.0, 0.5, 1.0000000000000002, 0.9999999999999999, 1e-310,
                                   -1e-310, inf, -inf, nan, -nan, 0.25};
  const DepthCodec float32{DepthFormat::Float32};
  for (size_t a = 0; a < values.size(); ++a) {
    const ClampLanes in = {values[a], values[(a + 1) % values.size()], values[(a + 4) % values.size()],
                           values[(a + 9) % values.size()]};
    const ClampLanes out = clampUnitOrZero(in);
    for (int lane = 0; lane < 4; ++lane) {
      const double expected = in[lane] > 0.0 ? std::min(in[lane], 1.0) : 0.0;
      INFO("input " << in[lane] << " (bits " << std::bit_cast<uint64_t>(in[lane]) << ")");
      CHECK(std::bit_cast<uint64_t>(out[lane]) == std::bit_cast<uint64_t>(expected));
      CHECK(std::bit_cast<uint32_t>(float(out[lane])) == float32.encode(in[lane]));
    }
  }
}

TEST_CASE("clampUnitOrZeroFloat after the conversion gives the depth encoder's float code of every double",
          "[raster][depth]") {
  // The span loops clamp the eight floats rather than the eight doubles; the encoder (clamp in
  // double, then round to float) is the reference, on the values where the two orders could part:
  // doubles that round to 1, to +-0 or to a float subnormal, NaN, infinities, and random doubles.
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> values{0.0,  -0.0, 1.0, -1.0, 0.5, 1.0000000000000002, 0.9999999999999999, 1.00000001,
                             0.99999999, 1e-310, -1e-310, 1e-46, -1e-46, 1e-40, 7e-46, 1.5e-45, inf, -inf, nan, -nan,
                             1e300, -1e300};
  uint64_t state = 0x9E3779B97F4A7C15ull;
  for (int i = 0; i < 4000; ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    values.push_back(std::bit_cast<double>(state));           // any bits: every exponent
    values.push_back(double(state >> 11) * 0x1.0p-53 * 1.25 - 0.125);  // around [0, 1]
  }
  const DepthCodec float32{DepthFormat::Float32};
  for (size_t a = 0; a + 8 <= values.size(); a += 8) {
    ClampFloats8 in;
    for (int lane = 0; lane < 8; ++lane) in[lane] = float(values[a + size_t(lane)]);
    const ClampFloats8 out = clampUnitOrZeroFloat(in);
    for (int lane = 0; lane < 8; ++lane) {
      const double z = values[a + size_t(lane)];
      INFO("input " << z << " (bits " << std::bit_cast<uint64_t>(z) << ")");
      REQUIRE(std::bit_cast<uint32_t>(out[lane]) == float32.encode(z));
    }
  }
}
