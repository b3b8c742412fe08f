// The stencil buffer as a picture of counts ([Kuhn 2016, §3.2]: the count decides whether a pixel
// is in shadow). Unsigned by default: the byte as GL stores it, so that 255 under saturating ops
// (INCR clamps at 255, [GL 2.1, §4.1.5]) reads 255, as in --dump-region and the pixel history. The
// signed reading (128..255 as -128..-1) is for wrapping ops, where a count of -1 is stored as
// 255 (z-pass with the camera inside a volume, [Kuhn 2016, Fig. 3.3]).
#pragma once

#include <cstdint>
#include <span>

#include "views/view.h"

namespace shadowref::views {

// Up to this many distinct counts get a swatch each; more get the ramp.
inline constexpr size_t kMaxSwatches = 16;

struct StencilViewSettings {
  bool signedCounts = false;
  size_t maxSwatches = kMaxSwatches;
};

// The count a stencil byte stands for under the reading.
int stencilCountOf(uint8_t value, bool signedCounts);

// Count 0 (lit) is black. With at most maxSwatches distinct counts each gets the palette colour of
// image/stencil_view.h (1 red, 2 green, 3 yellow, 4 blue, ...; -k the colour of k at half
// brightness) and a swatch in the legend (LegendKind::Swatches; "+1"/"-1" when signed). With more,
// every non-zero count is placed on viridis from the least count present (0) to the greatest (1)
// and the legend is a ramp (LegendKind::Ramp) with ticks at the ends, at 0 when it lies between,
// and at about four evenly spaced counts: its size no longer grows with the counts.
View stencilView(std::span<const uint8_t> stencil, int width, int height, const StencilViewSettings& settings = {});

}  // namespace shadowref::views
