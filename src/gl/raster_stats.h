// Counters the pipeline keeps while it works; `--stats` prints them.
#pragma once

#include <cstdint>

namespace shadowref {

struct RasterStats {
  uint64_t drawCalls = 0;
  uint64_t trianglesIn = 0;       // triangles submitted
  uint64_t trianglesClipped = 0;  // needed clipping
  uint64_t trianglesCulled = 0;   // culled or zero area
  uint64_t trianglesRasterized = 0;  // after clipping and fan triangulation
  uint64_t fragments = 0;         // covered pixel centres inside scissor and viewport
  uint64_t stencilFailed = 0;
  uint64_t depthFailed = 0;
  uint64_t stencilWrites = 0;     // fragments whose stencil value changed
  uint64_t colorWrites = 0;       // fragments that reached the colour buffer

  RasterStats& operator+=(const RasterStats& o) {
    drawCalls += o.drawCalls;
    trianglesIn += o.trianglesIn;
    trianglesClipped += o.trianglesClipped;
    trianglesCulled += o.trianglesCulled;
    trianglesRasterized += o.trianglesRasterized;
    fragments += o.fragments;
    stencilFailed += o.stencilFailed;
    depthFailed += o.depthFailed;
    stencilWrites += o.stencilWrites;
    colorWrites += o.colorWrites;
    return *this;
  }
};

}  // namespace shadowref
