// DepthCodec::encode on four depths at once: the span loops make a row's codes four or eight
// pixels at a time, where the codec would be called pixel by pixel.
#pragma once

#include <bit>
#include <cstdint>

#include "exec/clamp_unit.h"
#include "gl/framebuffer.h"

namespace shadowref {

using DepthLanes = double __attribute__((vector_size(32)));
using DepthCodeLanes = uint32_t __attribute__((vector_size(16)));

// The same operations as DepthCodec::encode, lane by lane: the clamp to [0, 1] (NaN and -0.0 to
// +0.0), then a float's bits, or Unorm24's z * (2^24 - 1) rounded as nearbyint rounds. For
// 0 <= m <= 2^24, (m + 2^52) - 2^52 is m rounded to a whole number in the current rounding mode,
// as nearbyint is: from 2^52 on a double's spacing is 1, and the subtraction is exact (nothing
// folds the two steps away without -ffast-math).
inline DepthCodeLanes encodeLanes(const DepthCodec& codec, DepthLanes z) {
  using Floats = float __attribute__((vector_size(16)));
  using Ints = int32_t __attribute__((vector_size(16)));
  const DepthLanes unit = clampUnitOrZero(z);
  if (codec.format == DepthFormat::Float32) return std::bit_cast<DepthCodeLanes>(__builtin_convertvector(unit, Floats));
  constexpr double kWhole = 0x1p52;
  const DepthLanes scaled = unit * 16777215.0;
  const DepthLanes rounded = (scaled + kWhole) - kWhole;
  return std::bit_cast<DepthCodeLanes>(__builtin_convertvector(rounded, Ints));  // whole numbers: exact
}

}  // namespace shadowref
