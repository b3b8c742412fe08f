// The perceptual colour map of the views' continuous quantities (depths, many stencil counts):
// viridis [van der Walt & Smith 2015], dark purple at 0 through teal to yellow at 1. Its
// lightness rises monotonically, so nearer and farther read correctly even in grey print, and
// equal steps of the value look like equal steps of colour.
#pragma once

#include <array>
#include <cstdint>

namespace shadowref::views {

using Rgb8 = std::array<uint8_t, 3>;

// viridis at t (clamped to [0, 1]; NaN as 0), each channel rounded to 8 bits: the degree-6
// polynomial fit of the matplotlib table by [Zucker 2020], evaluated in double by Horner's rule.
Rgb8 viridis(double t);

}  // namespace shadowref::views
