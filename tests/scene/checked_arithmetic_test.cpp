#include "scene/checked_arithmetic.h"

#include <catch2/catch.hpp>

#include <cstdint>
#include <limits>

using namespace shadowref;

TEST_CASE("checked arithmetic returns the exact value or nothing, never a wrapped one", "[scene][checked]") {
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  CHECK(checkedAdd<std::uint64_t>(2, 3) == 5u);
  CHECK(checkedAdd<std::uint64_t>(kMax, 0) == kMax);
  CHECK_FALSE(checkedAdd<std::uint64_t>(kMax, 1).has_value());
  CHECK(checkedMul<std::uint64_t>(1u << 31, 1u << 31) == (std::uint64_t{1} << 62));
  CHECK_FALSE(checkedMul<std::uint64_t>(std::uint64_t{1} << 32, std::uint64_t{1} << 32).has_value());
  CHECK(checkedMulAdd<std::uint64_t>(30000, 30000, 7) == 900000007u);
  CHECK_FALSE(checkedMulAdd<std::uint64_t>(kMax / 2, 2, 2).has_value());
  CHECK_FALSE(checkedMul<std::uint32_t>(65536, 65536).has_value());
}

TEST_CASE("rangeInside holds a byte range to its buffer without any addition that can wrap", "[scene][checked]") {
  CHECK(rangeInside(0, 10, 10));
  CHECK(rangeInside(10, 0, 10));
  CHECK_FALSE(rangeInside(10, 1, 10));
  CHECK_FALSE(rangeInside(11, 0, 10));
  // offset + length wraps to 5 in 64 bits: a naive "offset + length <= size" would accept it.
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  CHECK_FALSE(rangeInside(kMax - 4, 10, 100));
  CHECK_FALSE(rangeInside(8, kMax, 100));
}
