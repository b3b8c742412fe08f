// Comparing a rasterized stencil buffer with the oracle's counts (the rasterized stencil
// must equal that count on every pixel that is not within one pixel of a volume or geometry edge).
// With wrapping ops (INCR_WRAP / DECR_WRAP) the 8-bit stencil holds the count modulo 256.
#pragma once

#include <span>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "oracle/oracle.h"

namespace shadowref::oracle {

enum class CountKind : uint8_t { ZPass, ZFail };

struct StencilComparison {
  size_t compared = 0;    // pixels not near an edge
  size_t mismatches = 0;
  std::string report;     // the first few mismatches: "x,y: stencil s, oracle c (hit instance i)"
  bool matches() const { return mismatches == 0; }
};

// `stencil`: width * height values, row 0 at the bottom (Framebuffer::stencil()).
StencilComparison compareStencil(const OracleImage& oracle, std::span<const uint8_t> stencil, CountKind kind,
                                 size_t reportLimit = 10);

}  // namespace shadowref::oracle
